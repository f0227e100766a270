"""The scenarios, registered where they are defined, as dm_control's suite registers
its tasks: each scenario package adds itself to `SUITE` (`@SUITE.add(...)` on its
tabular twin), and `icm.envs.load`, `load_continuous`, `NAMES` and the Gymnasium
adapter read `SUITE`. Adding a scenario is one package plus its registration."""

import collections.abc
import dataclasses
import importlib

from icm import _validate


@dataclasses.dataclass(frozen=True)
class Scenario:
    """One registered scenario.

    Attributes:
      name: what `icm.envs.load` calls it.
      twin: its tabular environment (a `dm_env.Environment` class taking `seed=`).
      episodes: the class of its episode rules, which every discrete version of it
        subclasses (the Gymnasium adapter accepts its instances).
      physics: its simulated version, as "module:Class" (imported on first use), or
        None (tabular only).
      continuous: "module:function" loading its dm_control task, or None.
      task: "module:Class", the dm_control task whose arguments `load_continuous`
        accepts, or None.
    """

    name: str
    twin: type
    episodes: type
    physics: str = None
    continuous: str = None
    task: str = None

    def resolve(self, part):
        """The object a "module:name" part names (`physics`, `continuous` or `task`),
        imported now.

        Raises:
          ValueError: for a part the scenario does not have.
        """
        where = getattr(self, part)
        if where is None:
            raise ValueError(f"scenario {self.name!r} has no {part} version")
        module, name = where.split(":")
        return getattr(importlib.import_module(module), name)


class Suite(collections.abc.Mapping):
    """The registry of scenarios, by name, in the order they were added."""

    def __init__(self):
        self._scenarios = {}

    def add(self, name, episodes, physics=None, continuous=None, task=None):
        """Registers the decorated class (a scenario's tabular twin) as scenario `name`.

        Args:
          name: a new scenario name.
          episodes: its episode rules' class (the twin's base class).
          physics, continuous, task: see `Scenario` ("module:name" strings or None).

        Raises:
          ValueError: for a name registered already, or a twin that does not subclass
            `episodes`.
        """
        name = _validate.text("name", name)
        if name in self._scenarios:
            raise ValueError(f"name must be a new scenario, got {name!r}: registered already")
        for part, where in (("physics", physics), ("continuous", continuous), ("task", task)):
            if where is not None and (not isinstance(where, str) or where.count(":") != 1):
                raise _validate.ArgumentTypeError(
                    f"{part} must be 'module:name' or None, got {_validate.show(where)}")

        def register(twin):
            if not (isinstance(twin, type) and isinstance(episodes, type)
                    and issubclass(twin, episodes)):
                raise _validate.ArgumentTypeError(
                    f"the registered class must subclass episodes ({episodes!r}), got "
                    f"{_validate.show(twin)}")
            self._scenarios[name] = Scenario(name, twin, episodes, physics, continuous, task)
            return twin
        return register

    def remove(self, name):
        """Unregisters scenario `name` (a test's made-up scenario, for example)."""
        del self._scenarios[self.check(name)]

    def check(self, name):
        """`name` if it is a registered scenario, else a ValueError naming the known ones
        (an ArgumentTypeError for what is not a string)."""
        if not isinstance(name, str):
            raise _validate.ArgumentTypeError(
                f"name must be an environment name ({', '.join(self)}), got {name!r}")
        if name not in self._scenarios:
            raise ValueError(f"unknown environment {name!r}; known: {', '.join(self)}")
        return name

    def episode_classes(self):
        """The episode rules' classes of every scenario, a tuple."""
        return tuple(s.episodes for s in self._scenarios.values())

    def __getitem__(self, name):
        return self._scenarios[name]

    def __iter__(self):
        return iter(self._scenarios)

    def __len__(self):
        return len(self._scenarios)


SUITE = Suite()
"""Every scenario, registered by its package (`icm.envs.buttons`, `icm.envs.rods`)."""
