"""Compares the values two builds of the book glued into its chapters, and lists every
difference: the check that a change of the code left the book's numbers as they were.

    python benchmarks/compare_glue.py BEFORE AFTER

BEFORE and AFTER are folders of a build's glued values, `<chapter>.glue.json` each (the
build writes them to _build/jupyter_execute/book/; copy that folder before the change).
Every glued value is compared in every form the notebook gave it (text, Markdown, an
image's bytes). The values that measure the machine rather than the numbers
(`EXPECTED_TO_DIFFER`) are listed apart, with their reason, and do not count as
differences. The exit status is 1 when a value differs, a chapter or a value is missing
from one build, or an expected difference names a value that no build of its chapter
glues.
"""

import argparse
import json
import pathlib
import sys

EXPECTED_TO_DIFFER = {
    ("rod_toppling", "physics_seconds"):
        "wall-clock seconds of the physics run, timed while the chapter is built",
    ("rod_toppling", "physics_ms_per_move"):
        "the same seconds per move",
    ("simulated_icub", "physics_cpu"):
        "CPU-seconds of the physics run, timed while the chapter is built",
    ("simulated_icub", "tabular_cpu"):
        "CPU-seconds of the tabular run, timed while the chapter is built",
    ("simulated_icub", "speedup"):
        "the ratio of those two times",
}
"""{(chapter, glued name): why}: the glued values that are times measured on the machine
that builds the book, not numbers of the runs. A study's CPU hours read from its run log
are not among them: the log is a stored file, the same in both builds."""


def load(folder):
    """{chapter: {name: {mime type: value}}} of the glue files in `folder`."""
    found = {}
    for path in sorted(pathlib.Path(folder).glob("*.glue.json")):
        chapter = path.name[:-len(".glue.json")]
        found[chapter] = {name: output["data"]
                          for name, output in json.loads(path.read_text()).items()}
    return found


def compare(before, after):
    """(differences, expected, compared): the differences, as lines; the expected ones,
    as lines with their reason; and how many (chapter, name) values were compared."""
    differences, expected, compared = [], [], 0
    for chapter in sorted(set(before) | set(after)):
        if chapter not in before or chapter not in after:
            differences.append(f"{chapter}: only in {'after' if chapter in after else 'before'}")
            continue
        old, new = before[chapter], after[chapter]
        for name in sorted(set(old) | set(new)):
            if name not in old or name not in new:
                differences.append(f"{chapter}.{name}: glued only "
                                   f"{'after' if name in new else 'before'}")
                continue
            compared += 1
            if old[name] == new[name]:
                continue
            kinds = sorted(k for k in set(old[name]) | set(new[name])
                           if old[name].get(k) != new[name].get(k))
            shown = {k: (str(old[name].get(k))[:60], str(new[name].get(k))[:60])
                     for k in kinds}
            line = f"{chapter}.{name}: " + "; ".join(f"{k} {a!r} -> {b!r}"
                                                     for k, (a, b) in shown.items())
            if (chapter, name) in EXPECTED_TO_DIFFER:
                expected.append(f"{line} (expected: {EXPECTED_TO_DIFFER[(chapter, name)]})")
            else:
                differences.append(line)
    for chapter, name in EXPECTED_TO_DIFFER:
        built = chapter in before or chapter in after  # (a chapter not built: above)
        if built and name not in before.get(chapter, {}) and name not in after.get(chapter, {}):
            differences.append(f"{chapter}.{name}: expected to differ, but glued in "
                               f"neither build")
    return differences, expected, compared


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("before", type=pathlib.Path)
    parser.add_argument("after", type=pathlib.Path)
    args = parser.parse_args(argv)
    differences, expected, compared = compare(load(args.before), load(args.after))
    print(f"{compared} glued values compared; {len(differences)} differ"
          + (f", {len(expected)} more differ as expected" if expected else ""))
    for line in differences:
        print("DIFFERS  " + line)
    for line in expected:
        print("EXPECTED " + line)
    return 1 if differences else 0


if __name__ == "__main__":
    sys.exit(main())
