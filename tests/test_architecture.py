"""The package's architecture, read from its source with `ast`: no module uses another
module's private name, and no module imports upwards between the layers CONTRIBUTING.md
lists (its map of the package)."""

import ast
import pathlib

import pytest

import icm

ROOT = pathlib.Path(icm.__file__).parent

LAYERS = (
    ("icm._validate", "icm._streams", "icm._system", "icm._install", "icm._book",
     "icm._exact", "icm.files", "icm.records"),
    ("icm._settings", "icm.stats"),
    ("icm.envs",),
    ("icm.learners",),
    ("icm.experiments",),
    ("icm.chapters",),
    ("icm.figures", "icm.viewer"),
    ("icm.widgets", "icm.exercises"),
    ("icm.cli", "icm.course", "icm.__main__", "icm"),
)
"""CONTRIBUTING's map, bottom up: a module may import its own layer's and lower
layers' modules, never a higher layer's (the modules that are not in its table sit
with the ones they use: `stats` under the experiments, `viewer` with the figures,
`exercises` with the widgets, `course` with the command line)."""


def modules(root=ROOT):
    """{dotted name: path} of every module under `root` (the package `icm`)."""
    found = {}
    for path in sorted(root.rglob("*.py")):
        parts = ("icm",) + path.relative_to(root).with_suffix("").parts
        if parts[-1] == "__init__":
            parts = parts[:-1]
        found[".".join(parts)] = path
    return found


def _is_private(name):
    return name.startswith("_") and not (name.startswith("__") and name.endswith("__"))


def _source_of(module, path, node):
    """The dotted module a `from ... import` statement reads from."""
    if node.level == 0:
        return node.module
    base = module.split(".")
    if path.name != "__init__.py":
        base = base[:-1]
    base = base[:len(base) - (node.level - 1)]
    return ".".join(base + ([node.module] if node.module else []))


def imports_and_private_uses(known):
    """(imports, private): every (module, line, imported module) and every (module,
    line, what) where a module uses another module's private name, through
    `from x import _name` or `x._name` on an imported module `x`."""
    imports, private = [], []
    for module, path in known.items():
        tree = ast.parse(path.read_text(), str(path))
        aliases = {}
        for node in ast.walk(tree):
            if isinstance(node, ast.ImportFrom):
                source = _source_of(module, path, node)
                for alias in node.names:
                    full = f"{source}.{alias.name}"
                    if full in known:  # a module, imported from its package
                        aliases[alias.asname or alias.name] = full
                        imports.append((module, node.lineno, full))
                        continue
                    if source in known:  # a name the module `source` defines
                        imports.append((module, node.lineno, source))
                    if _is_private(alias.name) and source != module:
                        private.append((module, node.lineno,
                                        f"from {source} import {alias.name}"))
            elif isinstance(node, ast.Import):
                for alias in node.names:
                    if alias.name in known:
                        imports.append((module, node.lineno, alias.name))
                        if alias.asname:
                            aliases[alias.asname] = alias.name
        for node in ast.walk(tree):
            if not (isinstance(node, ast.Attribute) and _is_private(node.attr)):
                continue
            chain, value = [], node.value
            while isinstance(value, ast.Attribute):
                chain.append(value.attr)
                value = value.value
            if isinstance(value, ast.Name) and value.id in aliases:
                target = ".".join([aliases[value.id]] + chain[::-1])
                if target in known and target != module and f"{target}.{node.attr}" not in known:
                    private.append((module, node.lineno, f"{target}.{node.attr}"))
    return imports, private


def layer_of(module):
    """The index in `LAYERS` of a module (that of its longest listed prefix)."""
    best, best_length = None, -1
    for index, names in enumerate(LAYERS):
        for name in names:
            if (module == name or module.startswith(name + ".")) and len(name) > best_length:
                best, best_length = index, len(name)
    return best


def upward_imports(imports):
    """The (module, line, imported) whose imported module sits in a higher layer."""
    return [(m, line, target) for m, line, target in imports
            if layer_of(target) > layer_of(m)]


@pytest.fixture(scope="module")
def package():
    known = modules()
    return known, *imports_and_private_uses(known)


def test_every_module_has_a_layer(package):
    known, _, _ = package
    assert [m for m in known if layer_of(m) is None] == []


def test_no_module_uses_another_modules_private_name(package):
    _, _, private = package
    assert [f"{m}:{line}: {what}" for m, line, what in private] == []


def test_no_module_imports_upwards(package):
    _, imports, _ = package
    assert len(imports) > 300  # the parse found the package's imports
    assert [f"{m}:{line} imports {target}" for m, line, target in upward_imports(imports)] == []


def test_the_checks_find_what_they_look_for(tmp_path):
    """The checks themselves, on a made-up package: a private use of each kind and an
    upward import are found; a private module, and a module's own private names, are
    not."""
    package = tmp_path / "icm"
    (package / "learners").mkdir(parents=True)
    (package / "experiments").mkdir()
    for folder in (package, package / "learners", package / "experiments"):
        (folder / "__init__.py").write_text("")
    (package / "_validate.py").write_text("def check(x):\n    return x\n")
    (package / "learners" / "agent.py").write_text(
        "from icm import _validate\nfrom icm.experiments import runs\n\n"
        "def _helper():\n    return _validate.check(1)\n\nVALUE = _helper()\n")
    (package / "experiments" / "runs.py").write_text(
        "from icm.learners import agent\nfrom icm.learners.agent import _helper\n\n"
        "def run():\n    return agent._helper(), _helper()\n")
    known = modules(package)
    imports, private = imports_and_private_uses(known)
    assert sorted(what for _, _, what in private) == [
        "from icm.learners.agent import _helper", "icm.learners.agent._helper"]
    assert [(m, target) for m, _, target in upward_imports(imports)] == [
        ("icm.learners.agent", "icm.experiments.runs")]


MAX_LINES = 600
"""No module of icm is longer (issue 29): a longer one mixes ideas; split it."""


def test_no_module_is_over_600_lines(package):
    known, _, _ = package
    lengths = {m: len(path.read_text().splitlines()) for m, path in known.items()}
    assert {m: n for m, n in lengths.items() if n > MAX_LINES} == {}
