"""`python -m icm.course`: the course's commands (see the instructors' page).

    python -m icm.course assign OUT [--seed N] [--chapters NAME ...] [--no-run-tests]
    python -m icm.course grade SUBMISSIONS_DIR --out grades.csv [--assignments DIR] ...
    python -m icm.course lms HTML_DIR --out questions.xml
    python -m icm.course slides HTML_DIR --out DIR
"""

import argparse
import sys


def _assign(args):
    from icm.course.assign import assign

    written = assign(args.out, seed=args.seed, names=args.chapters,
                     run_tests=not args.no_run_tests, jobs=args.jobs)
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

    count = export_moodle(args.html, args.out)
    print(f"{count} questions in {args.out} (Moodle XML)")


def _slides(args):
    from icm.course.slides import build_slides

    decks = build_slides(args.html, args.out)
    print(f"{len(decks)} decks in {args.out}: open {decks[0] if decks else args.out}")


def main(argv=None):
    parser = argparse.ArgumentParser(prog="python -m icm.course", description=__doc__
                                     .split("\n\n")[0])
    commands = parser.add_subparsers(dest="command", required=True)

    assign = commands.add_parser("assign", help="write each chapter's assignment (the "
                                 "student's notebook and the autograder) with otter")
    assign.add_argument("out", help="the folder to write (make assignments: "
                        "_build/assignments)")
    assign.add_argument("--seed", type=int, default=None,
                        help="the hidden tests' seed (default: a fresh random one)")
    assign.add_argument("--chapters", nargs="+", default=None, metavar="NAME",
                        help="only these chapters (their notebooks' names)")
    assign.add_argument("--no-run-tests", action="store_true",
                        help="do not grade the solutions with their autograders (faster)")
    assign.add_argument("--jobs", type=int, default=2,
                        help="solutions graded at once (their test, on 2 cores)")
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
    grade.add_argument("--time-limit", type=float, default=600.0,
                       help="seconds for one submission (default 600)")
    grade.add_argument("--memory-limit", type=float, default=4.0,
                       help="GiB of memory for one submission, all its processes "
                            "together (default 4)")
    grade.add_argument("--cell-timeout", type=float, default=120.0,
                       help="seconds for one cell before it is left out (default 120)")
    grade.add_argument("--jobs", type=int, default=1,
                       help="submissions graded at once (at most the machine's cores)")
    grade.add_argument("--trusted", action="store_true",
                       help="run the notebooks without confinement: only for notebooks "
                            "you trust (your own tests), where bubblewrap or control "
                            "groups are missing")
    grade.add_argument("--force", action="store_true",
                       help="replace a sheet or feedback folder this command did not write")
    grade.set_defaults(run=_grade)

    lms = commands.add_parser("lms", help="export the book's \"predict, then check\" "
                              "questions for a learning platform (Moodle XML)")
    lms.add_argument("html", help="the built book's HTML folder (make book: _build/html)")
    lms.add_argument("--out", required=True, help="the XML file to write")
    lms.set_defaults(run=_lms)

    slides = commands.add_parser("slides", help="one reveal.js deck per chapter, from the "
                                 "built book")
    slides.add_argument("html", help="the built book's HTML folder (make book: _build/html)")
    slides.add_argument("--out", required=True, help="the decks' folder")
    slides.set_defaults(run=_slides)

    args = parser.parse_args(argv)
    try:
        args.run(args)
    except ValueError as error:  # bad input, said plainly
        print(f"python -m icm.course {args.command}: {error}", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
