"""icm: intrinsic motivation on a simulated iCub, after the paper "Intrinsic Motivations
for Forming Actions and Producing Goal Directed Behaviour".

Subpackages: `envs` (the button and rod tasks), `learners` (predictors, interest
measures, agents), `experiments` (seeded multi-run experiments, played through one
loop), `studies` (the long studies behind the chapters, stored in assets/), `chapters`
(what each chapter says of them: claims, verdicts, tables), `figures` (the paper's
figures), `widgets` (interactive panels for the book), `stats` (bands over seeds),
`viewer` (the live 3D views of the HTML book, run in the reader's browser).

Each is imported on first use (`icm.figures` loads matplotlib, a physics environment
loads MuJoCo), so `import icm` is quick.
"""

import importlib

__version__ = "0.1.0"
__all__ = ["chapters", "envs", "exercises", "experiments", "figures", "learners", "stats",
           "studies", "viewer", "widgets"]


def __getattr__(name):
    if name in __all__:
        return importlib.import_module(f"icm.{name}")
    raise AttributeError(f"module 'icm' has no attribute {name!r}")


def __dir__():
    return sorted(list(globals()) + __all__)
