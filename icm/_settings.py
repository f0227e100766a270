"""Settings written once: a learner's settings as one frozen object.

Every setting of a learner is declared once, as a `Setting`: its default, the paper's
value (or why there is none), its type and allowed range, its slider (a label in
words, the live slider's range, the static panel's grid) and, for the settings the
paper does not publish, the values the chapter "What the result depends on" sweeps.
A learner's settings object (`GoalOrientedSettings`, `ActorCriticSettings`,
`QLearnerSettings`: frozen dataclasses made with `settings_class`) checks every value
once, when it is built; a value may be one number per batch row (an array), so that a
grid of settings is still one batch.

Everything else is derived from these declarations: the run functions' keyword
arguments and their checks (`with_settings`), the grids' per-row arguments, the live
sliders of `icm.widgets`, the static panels' grids and labels, the CLI's options and
their help, the robustness study's settings and the API reference. Adding a setting to
a learner is one entry in its settings class (CONTRIBUTING shows an example).
"""

import collections.abc
import dataclasses
import functools
import inspect
import math

import numpy as np

from icm import _validate

class Names(collections.abc.Sequence):
    """A live tuple of names: `produce()` is asked at every use, so that the choices of
    a setting can follow a registry (the interest signals) as it grows."""

    def __init__(self, produce):
        self._produce = produce

    def __getitem__(self, index):
        return self._produce()[index]

    def __len__(self):
        return len(self._produce())

    def __repr__(self):
        return repr(self._produce())


KINDS = ("real", "integer", "choice")
"""What a setting holds: a real number, an integer, or one of a few names."""


@dataclasses.dataclass(frozen=True)
class Slider:
    """How a setting is offered on the book's panels.

    Attributes:
      live: (low, high, step) of the live ipywidgets slider, which reruns the learner.
      grid: the values of the static panel's precomputed grid, evenly spaced, each on
        the live slider and one of them the default.
    """

    live: tuple
    grid: tuple


@dataclasses.dataclass(frozen=True)
class Setting:
    """One setting: what it is, where it comes from and what values it may take.

    Attributes:
      default: the library's value.
      label: what it is, in words (slider labels, CLI help, tables).
      kind: "real", "integer" or "choice" (`KINDS`).
      low, high: the bounds of a number (None: unbounded on that side).
      low_open, high_open: whether a bound itself is excluded.
      choices: the names a "choice" may take (the default among them).
      paper: the paper's value, or None where the paper gives none.
      source: where the paper gives its value (its words), or why it gives none and
        what the library chose instead; the chapter that uses it says so.
      slider: its `Slider` on the book's panels, or None.
      swept: the values "What the result depends on" sweeps (an unpublished choice
        the results may depend on), or None.
      others: for an unpublished setting that is not swept, the other values (other
        readings) that "What the result depends on" measures one at a time against
        the default, or None; an unpublished "choice" setting's other choices are
        measured without being listed here (`other_readings`).
      per_row: whether the batched learners take one value per row (a grid of
        settings may vary it).
      name: the setting's name (filled in by `settings_class`).
    """

    default: object
    label: str
    kind: str
    low: object = None
    high: object = None
    low_open: bool = False
    high_open: bool = False
    choices: tuple = ()
    paper: object = None
    source: str = ""
    slider: Slider = None
    swept: tuple = None
    others: tuple = None
    per_row: bool = True
    name: str = ""

    def __post_init__(self):
        if self.kind not in KINDS:
            raise ValueError(f"kind must be one of {', '.join(KINDS)}, got {self.kind!r}")
        # Live choices (`Names`) may still be filling when the setting is declared.
        if self.kind == "choice" and not isinstance(self.choices, Names) and \
                self.default not in self.choices:
            raise ValueError(f"{self.label}: the default {self.default!r} is not among "
                             f"the choices {self.choices}")

    @property
    def published(self):
        """Whether the paper gives this setting's value."""
        return self.paper is not None

    def other_readings(self):
        """The values other than the default that "What the result depends on"
        measures one at a time, for an unpublished setting that its maps do not sweep:
        `others` if declared, else an unpublished choice's other choices; () for a
        published or swept setting."""
        if self.published or self.swept is not None:
            return ()
        if self.others is not None:
            return tuple(self.others)
        if self.kind == "choice":
            return tuple(c for c in self.choices if c != self.default)
        return ()

    def allowed(self):
        """What is allowed, in words (for messages and help)."""
        if self.kind == "choice":
            return "one of " + ", ".join(repr(c) for c in self.choices)
        what = "an integer" if self.kind == "integer" else "a number"
        if self.low is not None and self.high is not None:
            left, right = "(" if self.low_open else "[", ")" if self.high_open else "]"
            if self.kind == "integer":  # as icm._validate.integer says it
                return f"{what} in {self.low}..{self.high}"
            return f"{what} in {left}{self.low:g}, {self.high:g}{right}"
        if self.low is not None:
            return f"{what} {'>' if self.low_open else '>='} {self.low:g}"
        if self.high is not None:
            return f"{what} {'<' if self.high_open else '<='} {self.high:g}"
        return "a finite number" if self.kind == "real" else what

    def check(self, value, name=None):
        """`value` checked and normalised (a float, an int or a name); raises an
        ArgumentTypeError (wrong type) or a ValueError (out of range) naming the
        setting, showing the value and saying what is allowed."""
        name = name or self.name
        if self.kind == "choice":
            return _validate.one_of(name, value, self.choices)
        if self.kind == "integer":
            return _validate.integer(name, value, self.low, self.high)
        low = -math.inf if self.low is None else self.low
        high = math.inf if self.high is None else self.high
        return _validate.real(name, value, low, high, self.low_open, self.high_open,
                              allowed=self.allowed())

    def check_rows(self, value, name=None):
        """`check` for one value, or for each value of a 1-d array or list (one per
        batch row, which `per_row` settings allow); returns a value or an array."""
        name = name or self.name
        if isinstance(value, (np.ndarray, list, tuple)) and not (
                isinstance(value, np.ndarray) and value.ndim == 0):
            if not self.per_row:
                raise _validate.ArgumentTypeError(
                    f"{name} must be one value for every row ({self.allowed()}), got "
                    f"{_validate.show(value)}")
            values = np.asarray(value, dtype=object)
            if values.ndim != 1 or len(values) == 0:
                raise ValueError(f"{name} must be one value or a 1-d array of values, one "
                                 f"per row, got {_validate.show(value)}")
            checked = [self.check(v, f"{name}[{i}]") for i, v in enumerate(values)]
            dtype = {"real": float, "integer": np.int64}.get(self.kind, object)
            return np.array(checked, dtype=dtype)
        return self.check(value, name)


def setting(**declaration):
    """A field of a settings class: `Setting(**declaration)`, whose default is the
    field's default."""
    spec = Setting(**declaration)
    return dataclasses.field(default=spec.default, metadata={"setting": spec})


def setting_from(spec, **changes):
    """A field of a settings class declared by a `Setting` that a module defines once
    and several learners share (e.g. the predictor's action weight), with `changes`."""
    declared = {f.name: getattr(spec, f.name) for f in dataclasses.fields(spec)
                if f.name != "name"}
    return setting(**{**declared, **changes})


def settings_class(cls):
    """Makes `cls` (a subclass of `Settings` whose fields are `setting(...)`) a frozen
    dataclass, with every `Setting` named after its field."""
    cls = dataclasses.dataclass(frozen=True, eq=False)(cls)
    specs = {}
    for field in dataclasses.fields(cls):
        spec = field.metadata.get("setting")
        if spec is None:
            raise TypeError(f"{cls.__name__}.{field.name} must be declared with setting()")
        specs[field.name] = dataclasses.replace(spec, name=field.name)
    cls._specs = specs
    generated = cls.__init__

    @functools.wraps(generated)
    def init(self, *args, **values):
        if args:
            raise _validate.ArgumentTypeError(
                f"{cls.__name__} takes its settings by name (e.g. {next(iter(specs))}=...), "
                f"got {len(args)} positional value(s): {_validate.show(args)}")
        unknown = [name for name in values if name not in specs]
        if unknown:
            raise _validate.ArgumentTypeError(
                f"{', '.join(map(repr, unknown))} is not a setting of {cls.__name__}; its "
                f"settings are {', '.join(specs)}")
        generated(self, **values)

    cls.__init__ = init
    return cls


class Settings:
    """The base of the learners' settings objects (see the module docstring).

    Build one with keyword arguments (`GoalOrientedSettings(epsilon=0.2)`): every value
    is checked, and an unknown name is refused with the list of the known ones.
    `settings.epsilon` reads a value; `replace(**changes)` makes a changed copy.
    """

    _specs = {}

    def __post_init__(self):
        for name, spec in self._specs.items():
            object.__setattr__(self, name, spec.check_rows(getattr(self, name), name))

    @classmethod
    def specs(cls):
        """{name: Setting}, in declaration order."""
        return dict(cls._specs)

    @classmethod
    def spec(cls, name):
        """The `Setting` called `name`."""
        return cls._specs[_validate.one_of("name", name, tuple(cls._specs))]

    @classmethod
    def names(cls):
        """The settings' names, in declaration order."""
        return tuple(cls._specs)

    @classmethod
    def from_arguments(cls, arguments, function=None):
        """The settings made from `arguments` (a dict of some of the settings' names);
        a name that is not a setting is refused, naming `function` if given."""
        unknown = [name for name in arguments if name not in cls._specs]
        if unknown:
            where = f" of {function}" if function else ""
            raise _validate.ArgumentTypeError(
                f"{', '.join(map(repr, unknown))} is not an argument{where}; its settings "
                f"are {', '.join(cls._specs)}")
        return cls(**arguments)

    def as_dict(self):
        """{name: value}, in declaration order."""
        return {name: getattr(self, name) for name in self._specs}

    def replace(self, **changes):
        """A copy with some values changed (checked like a new object)."""
        return type(self).from_arguments({**self.as_dict(), **changes})

    def per_row(self, name, n_rows, dtype=None):
        """The value of `name` for each of `n_rows` rows (an array [n_rows])."""
        value = getattr(self, self.spec(name).name)
        if dtype is None:
            dtype = {"real": float, "integer": np.int64}.get(self._specs[name].kind, object)
        array = np.asarray(value, dtype=dtype)
        if array.ndim == 1 and len(array) != n_rows:
            raise ValueError(f"{name} has {len(array)} values for {n_rows} rows")
        return np.broadcast_to(array, (n_rows,))

    def one(self, name):
        """The value of `name`, which must be the same for every row."""
        value = getattr(self, name)
        if isinstance(value, np.ndarray):
            if len(set(value.tolist())) != 1:
                raise ValueError(f"{name} must be the same for every row, got "
                                 f"{_validate.show(value)}")
            return value.tolist()[0]
        return value

    @classmethod
    def stack(cls, blocks, n_rows):
        """One settings object for a grid: settings `blocks` (each a settings object of
        one value per setting) side by side, each repeated for its `n_rows` rows.

        A setting that is not per row (`Setting.per_row`) is one value for the whole
        batch: it must be the same in every block, and a grid whose blocks differ in
        it is refused, naming it and its values (never run with the first block's).

        Raises:
          ArgumentTypeError: if `blocks` is not a non-empty list of `cls` objects.
          ValueError: if `n_rows` is not an integer >= 1, a block holds several
            values of a setting, or a setting that is not per row differs between
            blocks.
        """
        if not isinstance(blocks, (list, tuple)) or not blocks or \
                not all(isinstance(block, cls) for block in blocks):
            raise _validate.ArgumentTypeError(
                f"blocks must be a non-empty list of {cls.__name__} objects, got "
                f"{_validate.show(blocks)}")
        n_rows = _validate.integer_at_least("n_rows", n_rows, 1)
        values = {}
        for name, spec in cls._specs.items():
            column = [getattr(block, name) for block in blocks]
            several = [i for i, v in enumerate(column) if isinstance(v, np.ndarray)]
            if several:
                raise ValueError(f"{name} must be one value in each block of a grid, got "
                                 f"{_validate.show(column[several[0]])} in block "
                                 f"{several[0]}")
            if spec.per_row:
                values[name] = np.repeat(np.array(column, dtype=object), n_rows)
            elif any(v != column[0] for v in column[1:]):
                raise ValueError(f"{name} must be the same in every setting of a grid (it "
                                 f"is one value for the whole batch), got {column}")
            else:
                values[name] = column[0]
        return cls(**values)

    def __eq__(self, other):
        if type(other) is not type(self):
            return NotImplemented
        return all(np.array_equal(np.asarray(getattr(self, n), dtype=object),
                                  np.asarray(getattr(other, n), dtype=object))
                   for n in self._specs)

    __hash__ = None

    def __repr__(self):
        shown = ", ".join(f"{n}={_validate.show(getattr(self, n), 40)}" for n in self._specs)
        return f"{type(self).__name__}({shown})"


def settings_doc(cls, indent="    "):
    """The settings of `cls` as the lines of a bullet list: name, what it is, what is
    allowed, the default, and the paper's value."""
    lines = []
    for name, spec in cls.specs().items():
        paper = f"the paper's: {spec.paper!r}" if spec.published else "the paper gives none"
        lines.append(f"{indent}- `{name}`: {spec.label}; {spec.allowed()} (default "
                     f"{spec.default!r}; {paper}).")
    return "\n".join(lines)


def with_settings(settings_cls, positional=()):
    """Decorates a run function whose last parameter is `settings`, so that it also
    takes every setting of `settings_cls` as a keyword argument: the wrapper builds
    the settings object once (checked, unknown names refused), from `settings=` if
    given and the keywords, and calls the function with it. Its signature and
    docstring list the settings, so that `inspect.signature`, the API reference and
    `help()` show them.

    Args:
      settings_cls: the `Settings` class.
      positional: settings that may also come first, by position, in this order (goal
        babbling's `strategy`: ``run_goal_babbling("random_goal", n_seeds=3)``).
    """
    positional = tuple(positional)
    for name in positional:
        settings_cls.spec(name)  # a setting of the class

    def decorate(function):
        signature = inspect.signature(function)
        parameters = list(signature.parameters.values())
        if not parameters or parameters[-1].name != "settings":
            raise TypeError(f"{function.__name__} must take settings as its last parameter")
        names = settings_cls.names()

        own_names = [p.name for p in parameters]

        @functools.wraps(function)
        def run(*args, **kwargs):
            for name, value in zip(positional, args):
                if name in kwargs:
                    raise _validate.ArgumentTypeError(
                        f"{function.__name__} got {name} both by position and by name")
                kwargs[name] = value
            args = args[len(positional):]
            unknown = [k for k in kwargs if k not in names and k not in own_names]
            if unknown:
                raise _validate.ArgumentTypeError(
                    f"{', '.join(map(repr, unknown))} is not an argument of "
                    f"{function.__name__}; its arguments are "
                    f"{', '.join(own_names[:-1] + list(names) + ['settings'])}")
            given = {name: kwargs.pop(name) for name in list(kwargs) if name in names}
            base = kwargs.pop("settings", None)
            if base is None:
                made = settings_cls.from_arguments(given, function.__name__)
            else:
                _validate.instance("settings", base, settings_cls)
                made = base.replace(**given) if given else base
            return function(*args, settings=made, **kwargs)

        own = [p for p in parameters[:-1]]
        specs = settings_cls.specs()
        leading = [inspect.Parameter(name, inspect.Parameter.POSITIONAL_OR_KEYWORD,
                                     default=specs[name].default) for name in positional]
        keyword = [inspect.Parameter(name, inspect.Parameter.KEYWORD_ONLY, default=spec.default)
                   for name, spec in specs.items() if name not in positional]
        settings_parameter = parameters[-1].replace(kind=inspect.Parameter.KEYWORD_ONLY,
                                                    default=None)
        own = [p.replace(kind=inspect.Parameter.POSITIONAL_OR_KEYWORD)
               if p.kind == inspect.Parameter.KEYWORD_ONLY else p for p in own]
        # Parameters after the first with a default keep defaults (a valid signature).
        run.__signature__ = signature.replace(
            parameters=leading + own + keyword + [settings_parameter])
        run.settings_class = settings_cls
        run.__doc__ = (function.__doc__ or "").rstrip() + (
            f"\n\n    Settings of the learner (keyword arguments, or `settings`, a "
            f"`{settings_cls.__name__}`; see its documentation for the paper's values "
            f"and sources):\n\n{settings_doc(settings_cls)}\n")
        return run
    return decorate
