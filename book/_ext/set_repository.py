"""The repository's address, kept in one place, and the one command that changes it.

    python book/_ext/set_repository.py https://github.com/OWNER/NAME

(or `make repository URL=https://github.com/OWNER/NAME`). The address lives in
`_config.yml` (`repository.url`): the Binder and Colab buttons of every chapter and the
repository and issues buttons are built from it. A few files must repeat it, because
they are read where `_config.yml` is not: each notebook's first cell (Colab installs
icm from `git+<address>`), the README (its install line and its citation) and
CONTRIBUTING (the install cell it shows). This command writes the new address into
`_config.yml` and into each of those, and changes nothing else;
`tests/test_launch.py` checks that they all agree (`derived_addresses`).

Exit status: 0 when every place holds the new address; 1 (with the reason) for an
address that is not a GitHub repository's.
"""

import argparse
import pathlib
import re
import sys

ROOT = pathlib.Path(__file__).resolve().parents[2]
ADDRESS = re.compile(r"https://github\.com/[A-Za-z0-9][A-Za-z0-9-]*/[A-Za-z0-9._-]*[A-Za-z0-9_-]")
"""A GitHub repository's address, as _config.yml holds it (no trailing slash, no .git)."""


CONFIG_LINE = re.compile(r"\nrepository:\n(?:  #.*\n)*  url: (\S+)\n")
"""`repository: url:` in _config.yml (read without YAML, so that a plain Python runs
this file)."""


def configured(root=ROOT):
    """The address in `root`/_config.yml."""
    match = CONFIG_LINE.search((root / "_config.yml").read_text())
    if match is None:
        raise ValueError(f"{root / '_config.yml'} has no `repository: url:` line")
    return match.group(1)


def derived_files(root=ROOT):
    """The files that repeat the address: the notebooks, README.md and CONTRIBUTING.md."""
    return sorted((root / "book").glob("*.ipynb")) + [root / "README.md",
                                                      root / "CONTRIBUTING.md"]


def derived_addresses(root=ROOT):
    """{file name: [the repository addresses it holds, in order]} for the files that
    repeat the address: where pip installs from (`git+<address>`: the notebooks'
    install cells, the README's install line, CONTRIBUTING's install cell) and what the
    README's citation cites (`url = {<address>}`)."""
    used = re.compile(rf"git\+({ADDRESS.pattern})|url\s*=\s*\{{({ADDRESS.pattern})\}}")
    return {str(path.relative_to(root)): [a or b for a, b in used.findall(path.read_text())]
            for path in derived_files(root)}


def set_repository(url, root=ROOT):
    """Writes `url` as the repository's address in `root`'s _config.yml and in every
    file that repeats it; returns the files changed.

    Raises:
      ValueError: if `url` is not a GitHub repository's address.
    """
    if not isinstance(url, str) or ADDRESS.fullmatch(url) is None:
        raise ValueError(f"url must be a GitHub repository's address, "
                         f"https://github.com/OWNER/NAME, got {url!r}")
    old = configured(root)
    changed = []
    config = root / "_config.yml"
    text = config.read_text()
    new_text, count = re.subn(rf"(\nrepository:\n(?:  #.*\n)*  url: ){re.escape(old)}\n",
                              rf"\g<1>{url}\n", text)
    if count != 1:
        raise ValueError(f"_config.yml: no `repository: url: {old}` line to change")
    if new_text != text:
        config.write_text(new_text)
        changed.append(config)
    for path in derived_files(root):
        text = path.read_text()
        # The address exactly, not a longer one that starts with it.
        new_text = re.sub(rf"{re.escape(old)}(?![\w.-])", url, text)
        if new_text != text:
            path.write_text(new_text)
            changed.append(path)
    return changed


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("url", help="https://github.com/OWNER/NAME")
    args = parser.parse_args(argv)
    old = configured()
    try:
        changed = set_repository(args.url)
    except ValueError as error:
        print(f"set_repository: {error}", file=sys.stderr)
        return 1
    print(f"{old} -> {args.url}: " + (", ".join(str(p.relative_to(ROOT)) for p in changed)
                                      or "nothing to change"))
    return 0


if __name__ == "__main__":
    sys.exit(main())
