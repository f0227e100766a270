"""`python -m icm.course`: the course's commands (see the instructors' page).

    python -m icm.course assign OUT [--seed N] [--chapters NAME ...] [--no-run-tests]
        [--jobs N] [--force]
    python -m icm.course grade SUBMISSIONS_DIR --out grades.csv [--assignments DIR] ...
    python -m icm.course lms HTML_DIR --out questions.xml [--force]
    python -m icm.course slides HTML_DIR --out DIR [--force]

Every number is checked when the command line is read, against the range its help
states (`NUMBERS`), and every destination before any work (`icm.files`): a command
writes over nothing it did not write, unless `--force`. Every error is one line on the
standard error, naming the option or the file, with exit status 1; no traceback.
"""

import argparse
import math
import sys

from icm._validate import MAX_SEED
from icm.course import limits

CORES = limits.CORES
"""The machine's cores: the most `--jobs`."""
NUMBERS = {
    # option: (kind, lowest, highest, what the number counts)
    "--seed": (int, 0, MAX_SEED, "the hidden tests' seed"),
    "--jobs": (int, *limits.JOBS, "this machine's cores"),
    "--time-limit": (float, *limits.TIME_LIMIT, "seconds"),
    "--memory-limit": (float, *limits.MEMORY_LIMIT, "GiB"),
    "--cell-timeout": (float, *limits.CELL_TIMEOUT, "seconds"),
}
"""The range of every number of the command line, stated in its help and checked as
it is read (`icm.course.grade.grade` checks its own the same)."""


class CourseParser(argparse.ArgumentParser):
    """argparse's parser, whose errors are one line and end the command with status 1."""

    def error(self, message):
        """Prints the error in one line and exits with status 1."""
        self.exit(1, f"{self.prog}: {message} (see {self.prog} --help)\n")


def _range(option):
    kind, low, high, unit = NUMBERS[option]
    if option == "--jobs":
        return f"from 1 to {high} ({unit})"
    if kind is int:
        return f"from {low} to {high}"
    return f"from {low:g} to {high:g} {unit}"


def number(option):
    """An argparse type for `option`: a number of its kind within its range
    (`NUMBERS`); a non-number, nan, an infinity or a number out of range is refused
    with the range (argparse names the option).

    Args:
      option: the option, e.g. "--jobs".

    Returns:
      The function argparse calls on the option's text.
    """
    kind, low, high, _ = NUMBERS[option]
    allowed = f"must be {'an integer' if kind is int else 'a number'} {_range(option)}"

    def parse(text):
        try:
            value = kind(text)
        except (ValueError, OverflowError):
            raise argparse.ArgumentTypeError(f"{allowed}, got {text!r}") from None
        if not math.isfinite(value) or not low <= value <= high:
            raise argparse.ArgumentTypeError(f"{allowed}, got {text!r}")
        return value
    parse.__name__ = option  # (what argparse would name in an unexpected error)
    return parse


def _assign(args):
    from icm.course.assign import assign

    written = assign(args.out, seed=args.seed, names=args.chapters,
                     run_tests=not args.no_run_tests, jobs=args.jobs, force=args.force)
    print(f"{len(written)} assignments in {args.out}: hand out */student/*.ipynb; keep "
          f"*/autograder/ (the solutions and the hidden tests' seed) to yourself.")


def _grade(args):
    from icm.course.grade import grade

    results = grade(args.submissions, args.out, assignments=args.assignments,
                    feedback_dir=args.feedback, roster=args.roster,
                    time_limit=args.time_limit, memory_limit=args.memory_limit,
                    cell_timeout=args.cell_timeout, jobs=args.jobs, trusted=args.trusted,
                    force=args.force)
    problems = sum(1 for graded in results if graded.problem)
    print(f"{len(results)} submissions graded ({problems} with a problem): {args.out}")


def _lms(args):
    from icm.course.lms import export_moodle

    count = export_moodle(args.html, args.out, force=args.force)
    print(f"{count} questions in {args.out} (Moodle XML)")


def _slides(args):
    from icm.course.slides import build_slides

    decks = build_slides(args.html, args.out, force=args.force)
    print(f"{len(decks)} decks in {args.out}: open {decks[0] if decks else args.out}")


def _force(parser, what):
    parser.add_argument("--force", action="store_true",
                        help=f"replace {what} that this command did not write")


def parser():
    """The command line's parser.

    Returns:
      A `CourseParser`.
    """
    main_parser = CourseParser(prog="python -m icm.course",
                               description=__doc__.split("\n\n")[0])
    commands = main_parser.add_subparsers(dest="command", required=True)

    assign = commands.add_parser("assign", help="write each chapter's assignment (the "
                                 "student's notebook and the autograder) with otter")
    assign.add_argument("out", help="the folder to write (make assignments: "
                        "_build/assignments): new, empty, or one this command wrote, whose "
                        "chapters written are replaced and others kept")
    assign.add_argument("--seed", type=number("--seed"), default=None,
                        help=f"the hidden tests' seed, an integer {_range('--seed')} "
                             f"(default: a fresh random one)")
    assign.add_argument("--chapters", nargs="+", default=None, metavar="NAME",
                        help="only these chapters (their notebooks' names)")
    assign.add_argument("--no-run-tests", action="store_true",
                        help="do not grade the solutions with their autograders (faster)")
    assign.add_argument("--jobs", type=number("--jobs"), default=min(2, CORES),
                        help=f"solutions graded at once, {_range('--jobs')} "
                             f"(default {min(2, CORES)})")
    _force(assign, "a folder of someone else's (its other files stay)")
    assign.set_defaults(run=_assign)

    grade = commands.add_parser("grade", help="grade a folder of notebooks: a CSV and a "
                                "feedback file per student")
    grade.add_argument("submissions", help="the folder of submitted notebooks (*.ipynb)")
    grade.add_argument("--out", required=True, help="the grade sheet to write (CSV)")
    grade.add_argument("--assignments", default="_build/assignments",
                       help="the folder `assign` wrote (default: _build/assignments)")
    grade.add_argument("--feedback", default=None,
                       help="the feedback files' folder (default: <out>-feedback beside it)")
    grade.add_argument("--roster", default=None, help="the class: a CSV with the "
                       "columns id, name and file; the sheet gets a row per student")
    grade.add_argument("--time-limit", type=number("--time-limit"), default=600.0,
                       help=f"seconds for one submission, {_range('--time-limit')} "
                            f"(default 600)")
    grade.add_argument("--memory-limit", type=number("--memory-limit"), default=4.0,
                       help=f"memory for one submission, all its processes together, "
                            f"{_range('--memory-limit')} (default 4)")
    grade.add_argument("--cell-timeout", type=number("--cell-timeout"), default=120.0,
                       help=f"seconds for one cell before it is left out, "
                            f"{_range('--cell-timeout')} (default 120)")
    grade.add_argument("--jobs", type=number("--jobs"), default=1,
                       help=f"submissions graded at once, {_range('--jobs')} (default 1)")
    grade.add_argument("--trusted", action="store_true",
                       help="run the notebooks without confinement: only for notebooks "
                            "you trust (your own tests), where bubblewrap or control "
                            "groups are missing")
    _force(grade, "a sheet or feedback folder")
    grade.set_defaults(run=_grade)

    lms = commands.add_parser("lms", help="export the book's \"predict, then check\" "
                              "questions for a learning platform (Moodle XML)")
    lms.add_argument("html", help="the built book's HTML folder (make book: _build/html)")
    lms.add_argument("--out", required=True, help="the XML file to write (.xml): new, or "
                     "an export of this command")
    _force(lms, "a file")
    lms.set_defaults(run=_lms)

    slides = commands.add_parser("slides", help="one reveal.js deck per chapter, from the "
                                 "built book")
    slides.add_argument("html", help="the built book's HTML folder (make book: _build/html)")
    slides.add_argument("--out", required=True, help="the decks' folder: new, empty, or one "
                        "this command wrote (its decks are replaced)")
    _force(slides, "a folder of someone else's (its other files stay)")
    slides.set_defaults(run=_slides)
    return main_parser


def one_line(error):
    """An error as one line: an `OSError` as its file and its reason, any other as its
    message with its lines joined.

    Args:
      error: the exception.

    Returns:
      The text.
    """
    if isinstance(error, OSError) and error.strerror:
        where = f"{error.filename}: " if error.filename is not None else ""
        return f"{where}{error.strerror}"
    return "; ".join(line.strip() for line in str(error).splitlines() if line.strip()) or \
        type(error).__name__


def main(argv=None):
    """Runs a command of the course.

    Args:
      argv: the arguments (default: the command line's).

    Returns:
      The exit status: 0, or 1 after an error printed in one line.
    """
    args = parser().parse_args(argv)
    try:
        args.run(args)
    except (ValueError, OSError) as error:  # bad input, said plainly
        print(f"python -m icm.course {args.command}: {one_line(error)}", file=sys.stderr)
        return 1
    except KeyboardInterrupt:
        print(f"python -m icm.course {args.command}: interrupted", file=sys.stderr)
        return 130
    return 0


if __name__ == "__main__":
    sys.exit(main())
