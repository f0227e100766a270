"""The command line: rebuild the paper's figures without Jupyter.

    python -m icm figure5 --seeds 200 --out fig5.png
    python -m icm goal-babbling --seeds 10 --out babbling.png
    python -m icm --help
"""

import argparse
import io
import pathlib
import sys

from icm import experiments, files
from icm.chapters.forming_actions.strategies import strategy_table
from icm.experiments import babbling_space, goal_babbling, rod_toppling
from icm.learners import actor_critic, goal_oriented, q_learning
from icm.learners.goal_babbling import GoalBabblingSettings


def _figures():
    """icm.figures, imported when a figure is drawn (it loads matplotlib): `--help`
    stays quick."""
    from icm import figures

    return figures


def _figure1(args):
    return _figures().figure1(seed=args.seed)


def _figure5(args):
    figures = _figures()
    result = experiments.run_goal_oriented(n_seeds=args.seeds, n_trials=args.trials,
                                           seed=args.seed, **_settings_of(args))
    return figures.figure5(result)


def _integer_at_least(minimum):
    """An argparse type: an integer >= minimum. Its errors say what is allowed (argparse
    shows an ArgumentTypeError's message as it is)."""
    def parse(text):
        try:
            value = int(text)
        except ValueError:
            raise argparse.ArgumentTypeError(
                f"must be an integer >= {minimum}, got {text!r}") from None
        if value < minimum:
            raise argparse.ArgumentTypeError(f"must be an integer >= {minimum}, got {text!r}")
        return value
    return parse


def _number(text):
    """An argparse type: a finite number (the run functions check its range)."""
    try:
        value = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"must be a number, got {text!r}") from None
    return value


def _buttons(text):
    """An argparse type: buttons, comma-separated ("2", "0,4"), or "none" (the run
    checks the range)."""
    if text.strip().lower() == "none":
        return ()
    try:
        return tuple(int(part) for part in text.split(","))
    except ValueError:
        raise argparse.ArgumentTypeError(f"must be buttons separated by commas (e.g. 0,4) or "
                                         f"none, got {text!r}") from None


_positive_int = _integer_at_least(1)
_seed = _integer_at_least(0)
MAX_DPI = 1200
"""The largest --dpi: a figure of the book at 1200 dpi is about 100 megapixels."""


def _dpi(text):
    """An argparse type: a resolution, an integer from 1 to MAX_DPI."""
    value = _positive_int(text)
    if value > MAX_DPI:
        raise argparse.ArgumentTypeError(f"must be an integer from 1 to {MAX_DPI}, got {text!r}")
    return value


def _check_out(parser, out):
    """Refuses, before anything runs, an --out that cannot be written: a folder, a
    symbolic link (writing would replace what it points to), a name not ending in an
    image's suffix (so no other file is ever replaced), a folder that does not exist or
    cannot be written."""
    if out.is_symlink():
        parser.error(f"--out must be a file, not a symbolic link: {out}")
    if out.is_dir():
        parser.error(f"--out must be a file to write, got the folder {out}")
    if out.suffix.lower() not in IMAGE_FORMATS:
        if out.name.lower() in IMAGE_FORMATS:  # Path(".png").suffix is ""
            parser.error(f"--out must name a file before its suffix (for example "
                         f"figure{out.name}), got {out}")
        parser.error(f"--out must end in .png, .pdf or .svg, got {out} (suffix "
                     f"{out.suffix or 'none'})")
    if not out.parent.exists():
        parser.error(f"--out: the folder {out.parent} does not exist")
    if not files.writable(out.parent):
        parser.error(f"--out: the folder {out.parent} cannot be written")


IMAGE_FORMATS = {".png": "png", ".pdf": "pdf", ".svg": "svg"}
"""The images a figure command writes, by --out's suffix: it replaces only such a file."""


def _save(figure, out, dpi):
    """Writes the figure whole: drawn in memory, then put in place under --out's name
    (`files.write_bytes`), so a run stopped half-way leaves an earlier image whole."""
    buffer = io.BytesIO()
    figure.savefig(buffer, format=IMAGE_FORMATS[out.suffix.lower()], dpi=dpi)
    files.write_bytes(out, buffer.getvalue())


SETTINGS_DEST = "settings_"
"""Prefix of the parsed settings' names (args.settings_epsilon, ...)."""


def _setting_type(spec):
    """An argparse type for one learner setting: the value, checked by its `Setting`
    (argparse shows the message, "must be ...", after the option's name)."""
    def parse(text):
        try:
            value = {"real": float, "integer": int}.get(spec.kind, str)(text)
            return spec.check(value)
        except ValueError:
            raise argparse.ArgumentTypeError(f"must be {spec.allowed()}, got {text!r}") \
                from None
    parse.__name__ = spec.name  # what argparse would show for an unexpected error
    return parse


def _settings_options(parser, settings_class, skip=()):
    """An option for every setting of a learner's `settings_class` (but those named in
    `skip`), from its `Setting`: the name with dashes, its type and range, and help with
    its label, range, default and the paper's value or the lack of one."""
    for name, spec in settings_class.specs().items():
        if name in skip:
            continue
        paper = f"the paper's: {spec.paper}" if spec.published else "the paper gives none"
        parser.add_argument(
            "--" + name.replace("_", "-"), dest=SETTINGS_DEST + name, type=_setting_type(spec),
            default=spec.default, choices=tuple(spec.choices) or None,
            metavar=None if spec.choices
            else name.upper(),
            help=f"{spec.label}, {spec.allowed()} (default {spec.default}; {paper})")


def _settings_of(args):
    """The learner settings parsed into `args`, as keyword arguments of a run."""
    return {name[len(SETTINGS_DEST):]: value for name, value in vars(args).items()
            if name.startswith(SETTINGS_DEST)}


def _no_options(parser):
    """Figure 1 has no options beyond --seed, --out and --dpi."""


def _figure5_options(parser):
    seeds, trials = experiments.goal_oriented.CHAPTER_SEEDS, experiments.goal_oriented.CHAPTER_TRIALS
    parser.add_argument("--seeds", type=_positive_int, default=seeds,
                        help=f"number of independent runs (default {seeds})")
    parser.add_argument("--trials", type=_positive_int, default=trials,
                        help=f"trials per run (default {trials})")
    _settings_options(parser, goal_oriented.GoalOrientedSettings)


def _figure6(args):
    figures = _figures()
    result = experiments.run_actor_critic(n_seeds=args.seeds, n_trials=args.trials,
                                          seed=args.seed, **_settings_of(args))
    return figures.figure6(result)


def _figure6_options(parser):
    seeds, trials = experiments.actor_critic.CHAPTER_SEEDS, experiments.actor_critic.CHAPTER_TRIALS
    parser.add_argument("--seeds", type=_positive_int, default=seeds,
                        help=f"number of independent runs (default {seeds})")
    parser.add_argument("--trials", type=_positive_int, default=trials,
                        help=f"trials per run (default {trials})")
    _settings_options(parser, actor_critic.ActorCriticSettings)


def _figure7(args):
    figures = _figures()
    result = experiments.run_rod_toppling(
        n_seeds=1, first_run=args.run, n_episodes=args.episodes, seed=args.seed,
        **_settings_of(args))
    figure = figures.figure7(result, seed=0, reading=args.reading)
    figure.suptitle(f"Run {args.run} of root seed {args.seed}, red predicted well read as "
                    f"\"{args.reading}\"", fontsize=10)
    return figure


def _figure7_options(parser):
    parser.add_argument("--run", type=_seed, default=0,
                        help="which run of the root seed to draw (>= 0, default 0)")
    parser.add_argument("--episodes", type=_positive_int, default=300,
                        help="episodes per run (default 300)")
    _settings_options(parser, q_learning.QLearnerSettings)
    parser.add_argument("--reading", choices=rod_toppling.READINGS, default="toppled",
                        help="when red counts as predicted well: on the pairs the robot "
                             "has toppled it from, or on all (default toppled)")


def _goal_babbling(args):
    figures = _figures()
    strategies = goal_babbling.STRATEGIES if args.strategy == "all" else (args.strategy,)
    results = {}
    for strategy in strategies:
        results[strategy] = experiments.run_goal_babbling(
            strategy=strategy, n_seeds=args.seeds, n_rollouts=args.rollouts, seed=args.seed,
            outcome_space=args.outcome_space, threads=args.threads,
            demonstrations=args.demonstrations, **_settings_of(args))
    maturation = _settings_of(args)["maturation"]
    print(strategy_table(results))
    if maturation != "none" or args.demonstrations:
        shown = ", ".join(map(str, args.demonstrations))
        plural = "s" if len(args.demonstrations) > 1 else ""
        print(f"(maturation {maturation}, "
              + (f"the teacher showed button{plural} {shown})" if shown else "no teacher)"))
    labels = figures.forming_actions.STRATEGY_LABELS
    return figures.test_error_figure({labels[s]: r for s, r in results.items()})


def _goal_babbling_options(parser):
    parser.add_argument("--strategy", choices=goal_babbling.STRATEGIES + ("all",),
                        default="all", help="which strategy to run (default all: "
                             f"{', '.join(goal_babbling.STRATEGIES)})")
    parser.add_argument("--seeds", type=_positive_int, default=5,
                        help="number of independent runs per strategy (default 5)")
    parser.add_argument("--rollouts", type=_positive_int,
                        default=goal_babbling.DEFAULT_N_ROLLOUTS,
                        help="movements per run, each simulated "
                             f"(default {goal_babbling.DEFAULT_N_ROLLOUTS})")
    parser.add_argument("--outcome-space", choices=babbling_space.OUTCOME_SPACES,
                        default=babbling_space.DEFAULT_OUTCOME_SPACE,
                        help="what a movement's outcome is: where the finger stopped, or "
                             "that and how far each cap went down "
                             f"(default {babbling_space.DEFAULT_OUTCOME_SPACE})")
    _settings_options(parser, GoalBabblingSettings, skip=("strategy",))
    parser.add_argument("--demonstrations", type=_buttons, default=(),
                        help="the buttons a teacher shows first, by moving the arm to the "
                             "scripted press, e.g. 2 or 0,4 (each at most once; default "
                             "none)")
    parser.add_argument("--threads", type=_integer_at_least(1), default=None,
                        help="threads stepping the rollouts (default: the cores this "
                             "process may use); the results do not depend on it")


COMMANDS = {
    "figure1": ("Figure 1: the two scenes, rendered from the simulated iCub",
                _figure1, _no_options),
    "figure5": ("Figure 5: interest of the goal-oriented learner, many seeds",
                _figure5, _figure5_options),
    "figure6": ("Figure 6: prediction errors of the intrinsic actor-critic, many seeds",
                _figure6, _figure6_options),
    "figure7": ("Figure 7: Q-learning on the rods, the paper's three moments in one run",
                _figure7, _figure7_options),
    "goal-babbling": ("Forming actions: goal babbling on the simulated iCub; prints the "
                      "strategies' numbers and draws their test error",
                      _goal_babbling, _goal_babbling_options),
}
"""name -> (help text, function(args) -> Figure, function(subparser) adding options)."""


def _integer_from(low, high, note=""):
    """An argparse type: an integer from `low` to `high` (`note` says what the highest
    is). Its errors say what is allowed."""
    allowed = f"must be an integer from {low} to {high:,}{note}"

    def parse(text):
        try:
            value = int(text)
        except ValueError:
            raise argparse.ArgumentTypeError(f"{allowed}, got {text!r}") from None
        if not low <= value <= high:
            raise argparse.ArgumentTypeError(f"{allowed}, got {text!r}")
        return value
    return parse


def _study_jobs(text):
    """An argparse type for `study --jobs`: -1 (one per core) or from 1 to this
    machine's cores (`icm.course.limits.CORES`): never more processes than cores."""
    from icm.course import limits

    allowed = (f"must be -1 (one per core) or an integer from 1 to {limits.CORES} (this "
               f"machine's cores)")
    try:
        value = int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"{allowed}, got {text!r}") from None
    if value != -1 and not 1 <= value <= limits.CORES:
        raise argparse.ArgumentTypeError(f"{allowed}, got {text!r}")
    return value


def _add_study_command(subparsers):
    """`python -m icm study NAME ...`: runs a long study (`icm.studies`)."""
    from icm import studies
    from icm.studies import engine, registry

    text = ("Run a long study (every local core with joblib, or a Dask cluster) and write "
            "its JSON file; a run killed half-way continues from its journal "
            "(<out>.journal) when started again with the same options. Its estimated "
            "run time is printed before it starts; a run estimated at more than "
            f"{engine.MAX_CPU_HOURS:g} CPU-hours needs --confirm-long-run.")
    sub = subparsers.add_parser("study", help="run a long study: "
                                + ", ".join(studies.STUDIES), description=text)
    sub.add_argument("name", choices=tuple(studies.STUDIES), metavar="NAME",
                     help="; ".join(f"{n}: {s.description}" for n, s in
                                    studies.STUDIES.items()))
    low, high = registry.SEEDS
    sub.add_argument("--seeds", type=_integer_from(low, high), default=None,
                     help=f"seeds, from {low} to {high:,}; "
                          + "; ".join(f"{n}: {s.seeds[1]} (default {s.seeds[0]})"
                                      for n, s in studies.STUDIES.items()))
    options = {}
    for study in studies.STUDIES.values():
        for option, (default, minimum, help_text) in study.options.items():
            options.setdefault(option, (minimum, []))[1].append(
                f"{study.name}: {help_text} (default {default})")
    for option, (minimum, helps) in options.items():
        sub.add_argument(f"--{option.replace('_', '-')}",
                         type=_integer_from(minimum, registry.SIZE_MAX), default=None,
                         help=f"from {minimum} to {registry.SIZE_MAX:,}; " + "; ".join(helps))
    sub.add_argument("--backend", choices=("joblib", "dask", "serial"), default="joblib",
                     help="joblib: processes on this machine (default); dask: a Dask "
                          "cluster (--scheduler, or a local one with --jobs workers); "
                          "serial: this process")
    sub.add_argument("--jobs", type=_study_jobs, default=-1,
                     help="joblib processes, or the workers of the local Dask cluster: "
                          "from 1 to this machine's cores (default -1: one per core)")
    sub.add_argument("--scheduler", default=None,
                     help="the address of an existing Dask cluster's scheduler, e.g. "
                          "tcp://10.0.0.5:8786 (with --backend dask); one that does not "
                          "answer within a few seconds is refused")
    sub.add_argument("--import-seeds", type=pathlib.Path, default=None, metavar="FILE",
                     help="an earlier file of the study with fewer seeds per root: its "
                          "seeds are kept after recomputing a sample of them")
    sub.add_argument("--out", type=pathlib.Path, required=True,
                     help="the JSON file to write: new, or a file of this study (its "
                          "journal <out>.journal and run log <out>.runs.jsonl beside it)")
    sub.add_argument("--force", action="store_true",
                     help="replace an --out (or a journal or run log beside it) that is "
                          "not this study's")
    sub.add_argument("--confirm-long-run", action="store_true",
                     help=f"run even if the estimate is more than "
                          f"{engine.MAX_CPU_HOURS:g} CPU-hours")
    sub.add_argument("--no-progress", action="store_true", help="no progress bar")

    def one_line(message):
        sub.exit(2, f"{sub.prog}: error: {message} (see {sub.prog} --help)\n")
    sub.error = one_line  # (argparse would print the usage too: errors are one line)
    return sub


def run_study_command(args, parser):
    """Runs `python -m icm study` with parsed `args`; returns the exit status.
    Everything is checked before any work (the options, the destinations, the
    estimated run time, the file whose seeds are imported, the Dask scheduler), and
    every error is one line with status 2."""
    from icm import studies
    from icm.experiments.sweep import UnitError, connect
    from icm.records import RecordError
    from icm.studies import engine

    def fail(message):
        parser.exit(2, f"{parser.prog} study: error: {message}\n")

    study = studies.STUDIES[args.name]
    options = {o: getattr(args, o) for o in study.options}
    given = [o for o in set().union(*(s.options for s in studies.STUDIES.values()))
             if o not in study.options and getattr(args, o) is not None]
    if given:
        fail(f"--{given[0].replace('_', '-')} is not an option of study {args.name!r}")
    if args.scheduler is not None and args.backend != "dask":
        fail("--scheduler needs --backend dask")
    common = dict(backend=args.backend, progress=not args.no_progress)
    cluster = client = None
    try:
        settings = studies.check_settings(args.name, args.seeds, **options)
        inputs = [] if args.import_seeds is None else [args.import_seeds]
        engine.check_destinations(args.name, args.out, force=args.force, inputs=inputs,
                                  what="--out")
        done = ()
        if args.import_seeds is not None:
            try:
                old = engine.read_seed_blocks(args.name, args.import_seeds)
            except RecordError as error:  # (its message starts with the file's name)
                fail(f"--import-seeds {error}")
            settings = studies.check_settings(args.name, args.seeds,
                                              imported_seeds=old.n_seeds, **options)
            done = engine.imported_units(old)
        seconds, n_units, basis = engine.check_run_length(
            args.name, settings, args.out, done, long_run=args.confirm_long_run)
        workers = (_cores() if args.jobs == -1 else args.jobs) \
            if args.backend != "serial" and args.scheduler is None else 1
        print(f"study {args.name}: {n_units} units to compute, estimated at "
              f"{engine.duration(seconds)} of CPU ({basis})"
              + (f", about {engine.duration(seconds / workers)} on {workers} "
                 f"core{'s' if workers > 1 else ''}" if args.scheduler is None else ""),
              flush=True)
        if args.backend == "dask" and args.scheduler is None:
            from dask import distributed

            cluster = distributed.LocalCluster(n_workers=workers, threads_per_worker=1,
                                               processes=True, dashboard_address=None)
            client = distributed.Client(cluster)
            common["client"] = client
        elif args.backend == "dask":
            client = common["client"] = connect(args.scheduler)
        else:
            common["n_jobs"] = args.jobs
        extra = None
        if args.import_seeds is not None:
            kept, extra = studies.import_seeds(args.name, args.out, args.import_seeds,
                                               args.seeds, force=args.force, **common,
                                               **options)
            options["imported_seeds"] = kept
        studies.run_study(args.name, args.out, args.seeds, extra=extra, force=args.force,
                          inputs=inputs, long_run=args.confirm_long_run, **common,
                          **options)
    except (ValueError, OSError, UnitError) as error:
        fail(str(error).replace("\n", " "))
    except KeyboardInterrupt:
        parser.exit(130, f"{parser.prog} study: interrupted; the units finished are kept "
                         f"in {engine.journal_of(args.out)}: run the same command again "
                         f"to continue\n")
    finally:
        if client is not None:
            client.close()
        if cluster is not None:
            cluster.close()
    print(f"wrote {args.out}")
    return 0


def _cores():
    """This machine's cores (`icm.course.limits.CORES`)."""
    from icm.course import limits

    return limits.CORES


def build_parser():
    """The argument parser of `python -m icm` (one subcommand per figure, and `study`)."""
    parser = argparse.ArgumentParser(
        prog="python -m icm",
        description="Rebuild the paper's figures from the icm package and save them as "
                    "images.")
    subparsers = parser.add_subparsers(dest="figure", required=True, metavar="FIGURE")
    for name, (help_text, _, add_options) in COMMANDS.items():
        sub = subparsers.add_parser(name, help=help_text, description=help_text)
        add_options(sub)
        sub.add_argument("--seed", type=_seed, default=0,
                         help="root random seed, an integer >= 0 (default 0)")
        sub.add_argument("--out", type=pathlib.Path, default=pathlib.Path(f"{name}.png"),
                         help=f"image file to write, .png, .pdf or .svg (default {name}.png)")
        sub.add_argument("--dpi", type=_dpi, default=150,
                         help=f"resolution of a .png, 1 to {MAX_DPI} (default 150)")
    _add_study_command(subparsers)
    return parser


def main(argv=None):
    """Runs the command line; returns the exit status (0 on success)."""
    parser = build_parser()
    args = parser.parse_args(argv)
    if args.figure == "study":
        return run_study_command(args, parser)
    _check_out(parser, args.out)
    _, make_figure, _ = COMMANDS[args.figure]
    try:
        figure = make_figure(args)
    except ValueError as error:
        parser.exit(2, f"{parser.prog} {args.figure}: error: {error}\n")
    try:
        _save(figure, args.out, args.dpi)
    except OSError as error:  # e.g. the disk filled up while the run went on
        parser.exit(2, f"{parser.prog} {args.figure}: error: --out: {error}\n")
    print(f"wrote {args.out}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
