"""The registry of the long studies: each study is registered beside its units, in its
own module of `icm.studies` (`register(Study(...))`, as dm_control's suite registers its
tasks), and the engine (`icm.studies.engine`) and the command line (`python -m icm
study NAME`, `icm.cli`) read `STUDIES`."""

import dataclasses

from icm import _validate


@dataclasses.dataclass(frozen=True)
class Study:
    """One registered study.

    Attributes:
      name: its name on the command line.
      description: one line for `--help`.
      seeds: (default seeds, what a seed count means), e.g. (80, "per condition").
      options: the other size options: {name: (default, minimum, help)}.
      units: settings -> the list of units (JSON lists that carry everything deciding a
        unit's result, its seeds included).
      run_unit: a module-level function (settings, unit) -> the unit's result, a
        JSON value.
      assemble: (settings, units, results) -> the study's dict.
      seeding: what seeds its units use, in words (its file's "produced_by" keeps it).
      check: settings -> settings, raising ValueError for a bad combination.
      indent: the JSON file's indentation (None: compact), as its committed file has it.
      unit_seconds: (settings, unit) -> a rough figure of the unit's CPU seconds, its
        source stated where it is defined (None: `DEFAULT_UNIT_SECONDS` a unit), from
        which the engine estimates a run's time before it starts
        (`icm.studies.engine.estimate`; a run measured beside the output file scales
        it).
    """

    name: str
    description: str
    seeds: tuple
    options: dict
    units: object
    run_unit: object
    assemble: object
    seeding: str
    check: object = None
    indent: object = None
    unit_seconds: object = None


SEEDS = (1, 100_000)
"""The range of a study's seeds (`--seeds`): 100,000 seeds of the remedies' 7
conditions are 700,000 units, about 1,500 CPU-hours; the estimate of a run's time
refuses far less (`icm.studies.engine.MAX_CPU_HOURS`)."""
SIZE_MAX = 1_000_000
"""The largest value of a study's other size options (rollouts, trials, episodes, ...;
each has its own least value, `Study.options`)."""
DEFAULT_UNIT_SECONDS = 10.0
"""CPU seconds a unit is taken to cost when its study states no figure (the formed
actions' units, the slowest registered, take 5 to 8 at their defaults)."""

STUDIES = {}
"""The registered studies, by name, in the order their modules registered them."""


def register(study):
    """Adds `study` (a `Study`) to `STUDIES`; returns it.

    Raises:
      ValueError: for a name registered already.
    """
    _validate.instance("study", study, Study)
    if study.name in STUDIES:
        raise ValueError(f"study.name must be a new study, got {study.name!r}: registered "
                         f"already")
    STUDIES[study.name] = study
    return study


def unregister(name):
    """Removes study `name` from `STUDIES` (a test's made-up study, for example)."""
    del STUDIES[_validate.one_of("name", name, tuple(STUDIES))]


def plain(value):
    """`value` with NumPy scalars and arrays made Python numbers and lists (JSON)."""
    if isinstance(value, dict):
        return {str(k): plain(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [plain(v) for v in value]
    if hasattr(value, "tolist"):
        return plain(value.tolist())
    return value
