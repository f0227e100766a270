"""The long studies behind the chapters, each cut into units of work that run on the
sweep engine, on every core of this machine (joblib) or on a Dask cluster, with the
same numbers either way, and written, with what produced them, to a file in assets/.

A study is registered beside its units, in its own module (`icm.studies.registry.
register`): the chapter "Forming actions"'s (`forming_actions`: "goal-babbling",
"remedies", "remedies-replication"), the maps of "What the result depends on"
(`robustness`, with the other readings of its choices in `readings`) and the
comparisons of "Which curiosity?" (`curiosity`). `engine.run_study` runs one (a run
killed half-way continues from its journal); `python -m icm study NAME` is its command
line (`icm.cli`). A study's module reads its own file too; what the chapters say of it
is `icm.chapters`'.
"""

from icm.studies.registry import STUDIES, Study, register
from icm.studies.engine import check_settings, import_seeds, run_study
from icm.studies import forming_actions, robustness, curiosity  # noqa: E402 (they register)
from icm.studies import readings  # noqa: E402

__all__ = ["STUDIES", "Study", "check_settings", "curiosity", "forming_actions",
           "import_seeds", "readings", "register", "robustness", "run_study"]
