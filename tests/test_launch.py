"""The launch buttons: every notebook's first cell (it installs icm on Binder or Colab),
the Binder files, and a fresh launch reproduced locally.

The fresh launch (marker `launch`, run by `make test`) builds a new virtual
environment from binder/ alone (its packages linked in from the environment the same
pins installed, then checked by pip), copies a notebook out of the repository and
executes it there with the install cell run, pointed at a copy of this checkout
instead of the repository's address.
"""

import json
import os
import pathlib
import re
import shutil
import subprocess
import sys
import time
import tomllib

import nbformat
import pytest
import yaml

from conftest import ROOT, toc_files

CONFIG = yaml.safe_load((ROOT / "_config.yml").read_text())
REPOSITORY = CONFIG["repository"]["url"]
INSTALL_TAGS = ["skip-execution", "remove-cell"]
INSTALL_CELL = f'''\
# On Binder or Colab, install icm when it is missing. Harmless when icm is
# installed; the book build skips this cell.
import importlib.util
import os
import subprocess
import sys

if importlib.util.find_spec("icm") is None:
    source = os.environ.get("ICM_SOURCE", "git+{REPOSITORY}")
    pip = [sys.executable, "-m", "pip", "install", "--quiet"]
    subprocess.check_call(pip + ["--no-deps", source])  # icm, then what it needs:
    subprocess.check_call([sys.executable, "-m", "icm._install"])'''
"""The exact first cell of every notebook of the book (tags: INSTALL_TAGS)."""
NOTEBOOKS = [ROOT / f"{name}.ipynb" for name in toc_files() if (ROOT / f"{name}.ipynb").exists()]
LAUNCHED = ROOT / "book" / "button_experiment.ipynb"
"""The notebook the fresh launch runs: a light one (the tabular twin, figures)."""
BINDER = ROOT / "binder"


def test_the_book_has_notebooks():
    assert len(NOTEBOOKS) >= 5


@pytest.mark.parametrize("path", NOTEBOOKS, ids=lambda p: p.name)
def test_every_notebook_starts_with_exactly_the_install_cell(path):
    notebook = nbformat.read(path, as_version=4)
    first = notebook.cells[0]
    assert first.cell_type == "code", f"{path.name}: the first cell must be the install cell"
    assert first.source == INSTALL_CELL, (
        f"{path.name}: the first cell must be exactly the install cell of CONTRIBUTING.md "
        f"(with the address of _config.yml, {REPOSITORY})")
    assert dict(first.metadata) == {"tags": INSTALL_TAGS}, f"{path.name}: {first.metadata}"
    assert sum(c.source == INSTALL_CELL for c in notebook.cells) == 1


def test_contributing_shows_the_install_cell():
    indented = "\n".join(f"  {line}" if line else "" for line in INSTALL_CELL.splitlines())
    assert indented in (ROOT / "CONTRIBUTING.md").read_text()


def test_the_repository_address_is_one_github_repository_everywhere():
    assert re.fullmatch(r"https://github\.com/[\w.-]+/[\w.-]+", REPOSITORY), REPOSITORY
    for path in NOTEBOOKS:
        addresses = re.findall(r'"git\+(https://[^"]+)"', nbformat.read(path, as_version=4)
                               .cells[0].source)
        assert addresses == [REPOSITORY], f"{path.name} installs from {addresses}"
    readme = (ROOT / "README.md").read_text()
    cited = re.findall(r"url\s*=\s*\{(https://github\.com/[^}]+)\}", readme)
    installed = re.findall(r"git\+(https://github\.com/[\w./-]*\w)", readme)
    assert cited == [REPOSITORY] and set(installed) == {REPOSITORY}, (cited, installed)


def _set_repository():
    import importlib.util

    spec = importlib.util.spec_from_file_location(
        "set_repository", ROOT / "book" / "_ext" / "set_repository.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


set_repository = _set_repository()


def test_everything_derived_from_the_address_agrees_with_config():
    derived = set_repository.derived_addresses()
    assert set_repository.configured() == REPOSITORY
    for name, addresses in derived.items():
        expected = 2 if name == "README.md" else 1  # the README: install line, citation
        assert addresses == [REPOSITORY] * expected, (name, addresses)
    assert len(derived) == len(NOTEBOOKS) + 2


def test_one_command_changes_the_address_everywhere(tmp_path):
    for path in [ROOT / "_config.yml"] + set_repository.derived_files():
        target = tmp_path / path.relative_to(ROOT)
        target.parent.mkdir(parents=True, exist_ok=True)
        shutil.copy(path, target)
    new = "https://github.com/a-university/icm-course"
    changed = set_repository.set_repository(new, root=tmp_path)
    assert len(changed) == 1 + len(set_repository.derived_files())
    assert set_repository.configured(tmp_path) == new
    for name, addresses in set_repository.derived_addresses(tmp_path).items():
        assert addresses and set(addresses) == {new}, name
    # Only the address changed, and the install cells are the new address's.
    for path in [ROOT / "_config.yml"] + set_repository.derived_files():
        after = (tmp_path / path.relative_to(ROOT)).read_text()
        assert after.replace(new, REPOSITORY) == path.read_text(), path.name
    first = nbformat.read(tmp_path / "book" / LAUNCHED.name, as_version=4).cells[0].source
    assert first == INSTALL_CELL.replace(REPOSITORY, new)
    with pytest.raises(ValueError, match="url must be a GitHub repository's address"):
        set_repository.set_repository("https://gitlab.com/a/b", root=tmp_path)
    assert "make repository URL=" in (ROOT / "README.md").read_text()
    assert "repository:" in (ROOT / "Makefile").read_text()


def _run_install_cell(args, env, cwd):
    return subprocess.run([sys.executable, *args, "-c", INSTALL_CELL], env=env, cwd=cwd,
                          capture_output=True, text=True, timeout=300)


def _without_python_path():
    return {k: v for k, v in os.environ.items() if k not in ("PYTHONPATH", "PYTHONHOME")}


def test_the_install_cell_installs_only_when_icm_is_missing(tmp_path):
    env = _without_python_path() | {"ICM_SOURCE": str(tmp_path / "no-such-project")}
    # icm importable (this checkout first on the path): nothing happens, even with a
    # source that cannot be installed.
    done = _run_install_cell([], env | {"PYTHONPATH": str(ROOT)}, tmp_path)
    assert done.returncode == 0, done.stderr
    assert done.stdout == "" and done.stderr == ""
    # icm not importable (no site-packages, no path): the cell runs pip on ICM_SOURCE,
    # which fails here because that folder does not exist.
    done = _run_install_cell(["-S"], env, tmp_path)
    assert done.returncode != 0
    assert "no-such-project" in done.stderr and "CalledProcessError" in done.stderr


def _requirement_lines(path):
    lines = (line.split("#", 1)[0].strip() for line in path.read_text().splitlines())
    return [line for line in lines if line]


def test_binder_reuses_the_pinned_requirements():
    # repo2docker runs `pip install -r binder/requirements.txt` from the repository's
    # root after copying the whole repository (a file that refers to another one is not
    # installed before the copy); pip reads `-r` relative to the including file.
    assert _requirement_lines(BINDER / "requirements.txt") == ["-r ../requirements.txt"]
    pins = _requirement_lines(ROOT / "requirements.txt")
    assert "dm-control==1.0.50" in pins and "mujoco==3.17.0" in pins
    assert "jupyter-book==1.0.4.post1" in pins


def test_binder_cannot_drift_from_the_project():
    # Binder installs requirements.txt, then icm without its dependencies (postBuild):
    # every dependency icm declares, and the notebooks' extra, must be pinned there, to
    # a version its declaration allows.
    from packaging.requirements import Requirement

    pins = {Requirement(line).name.lower().replace("_", "-"): Requirement(line)
            for line in _requirement_lines(ROOT / "requirements.txt")}
    project = tomllib.loads((ROOT / "pyproject.toml").read_text())["project"]
    declared = project["dependencies"] + project["optional-dependencies"]["notebooks"]
    for text in declared:
        wanted = Requirement(text)
        pin = pins.get(wanted.name.lower().replace("_", "-"))
        assert pin is not None, f"{wanted.name} is not pinned in requirements.txt"
        version = next(iter(pin.specifier)).version
        assert wanted.specifier.contains(version), (text, str(pin))
    # The system packages: those the README and `make` (icm/_system.py) ask for.
    from icm import _system

    apt = set(_requirement_lines(BINDER / "apt.txt"))
    assert set(_system.DEBIAN_PACKAGES) <= apt
    readme = (ROOT / "README.md").read_text()
    listed = re.search(r"sudo apt-get install ([a-z0-9 .+-]+)\n", readme).group(1).split()
    assert set(listed) <= apt and set(listed) == set(_system.DEBIAN_PACKAGES)


def test_binder_python_is_the_projects_python():
    # repo2docker's default Python (3.10) is older than icm's requires-python; with a
    # binder/ folder it reads the version from binder/runtime.txt only.
    runtime = (BINDER / "runtime.txt").read_text().strip()
    version = re.fullmatch(r"python-(3\.\d+)", runtime).group(1)
    assert f"PYTHON ?= python{version}" in (ROOT / "Makefile").read_text()
    requires = tomllib.loads((ROOT / "pyproject.toml").read_text())["project"]["requires-python"]
    assert requires == ">=3.11" and tuple(map(int, version.split("."))) >= (3, 11)


def test_binder_installs_the_system_packages_for_rendering():
    packages = _requirement_lines(BINDER / "apt.txt")
    for package in packages:  # repo2docker refuses anything else
        assert re.fullmatch(r"[a-z0-9.+-]+", package), package
    # the EGL loader, Mesa's EGL with its software driver (MUJOCO_GL=egl), OSMesa
    assert {"libegl1", "libegl-mesa0", "libgl1-mesa-dri", "libosmesa6"} <= set(packages)


def test_binder_post_build_installs_icm():
    post_build = BINDER / "postBuild"
    assert os.access(post_build, os.X_OK), "binder/postBuild must be executable"
    text = post_build.read_text()
    assert text.startswith("#!/bin/bash\n") and "set -euo pipefail" in text
    assert "pip install --no-cache-dir --no-deps -e ." in text


# --- the fresh launch -----------------------------------------------------------------

RUN_NOTEBOOK = """\
import importlib.util, pathlib, sys
spec = importlib.util.spec_from_file_location("execute_book", sys.argv[1])
execute_book = importlib.util.module_from_spec(spec)
spec.loader.exec_module(execute_book)  # first: it spares nbformat's slow import
import nbformat
path, out = pathlib.Path(sys.argv[2]), pathlib.Path(sys.argv[3])
nb = nbformat.read(path, as_version=4)
for cell in nb.cells:  # a reader's Jupyter ignores the tag that the book build obeys
    tags = cell.metadata.get("tags", [])
    if execute_book.SKIP_TAG in tags:
        tags.remove(execute_book.SKIP_TAG)
nbformat.write(nb, path)
import threading
executed, seconds = execute_book.execute(path, threading.Event())
nbformat.write(executed, out)
print(f"{seconds:.1f}")
"""

INSTALLED = """\
import importlib.metadata, json, os
os.environ.setdefault("MUJOCO_GL", "egl")
import icm
from icm.figures import icub
url = json.loads(importlib.metadata.distribution("icm").read_text("direct_url.json"))
env = icm.envs.load("buttons", physics=True, seed=0)
env.reset()
image = icub.render(env.physics, "front", 48, 64)
print(json.dumps({"file": icm.__file__, "url": url, "image": list(image.shape),
                  "lit": int(image.max())}))
"""


UNMET_PINS = """\
import importlib.metadata, json, sys
from packaging.requirements import Requirement
unmet = []
for line in sys.argv[1:]:
    requirement = Requirement(line)
    if requirement.marker is not None and not requirement.marker.evaluate():
        continue
    try:
        version = importlib.metadata.version(requirement.name)
    except importlib.metadata.PackageNotFoundError:
        version = None
    if version is None or version not in requirement.specifier:
        unmet.append([line, version])
print(json.dumps(unmet))
"""
"""The requirement lines given as arguments whose package is missing, or installed at a
version the line does not allow, as JSON [[line, installed version or null], ...]."""


def _copy_checkout(destination):
    """The files of this checkout that git tracks or would track (what a clone of the
    repository holds, with the changes not committed yet)."""
    listed = subprocess.run(["git", "ls-files", "-z", "--cached", "--others", "--exclude-standard"],
                            cwd=ROOT, capture_output=True, check=True).stdout.decode()
    for name in filter(None, listed.split("\0")):
        source = ROOT / name
        if not source.exists() and not source.is_symlink():
            continue  # deleted, not committed yet
        target = destination / name
        target.parent.mkdir(parents=True, exist_ok=True)
        shutil.copy2(source, target, follow_symlinks=False)
    return destination


def _link_installed_packages(source, venv):
    """Hard-links into the new virtual environment `venv` what the environment `source`
    installed (site-packages, share/, etc/), except icm and the distributions `venv`
    holds already (its own pip and setuptools): the same files as installing the same
    pins again, in seconds. Safe for `source`: pip and Python never write into an
    installed file, they remove it or replace it by a new one, which here unlinks
    `venv`'s name only. (Its scripts in bin/ are not linked: they name `source`'s
    Python.)"""
    version = f"python{sys.version_info.major}.{sys.version_info.minor}"
    site = pathlib.Path("lib") / version / "site-packages"
    present = {_project(entry.name) for entry in (venv / site).iterdir()}
    for top in (site, pathlib.Path("share"), pathlib.Path("etc")):
        if not (source / top).is_dir():
            continue
        for entry in (source / top).iterdir():
            name = _project(entry.name)
            if top == site and (name in present or name == "icm"
                                or entry.name.startswith("__editable__")):
                continue
            _link_tree(entry, venv / top / entry.name)


def _project(name):
    """The distribution a top-level entry of site-packages belongs to, as far as its
    name tells ("pip" for pip/ and pip-25.2.dist-info; normalised)."""
    name = re.sub(r"-[^-]*\.(dist|egg)-info$", "", name)
    return re.sub(r"[-_.]+", "-", name.removesuffix(".py")).lower()


def _link_tree(source, target):
    if source.is_dir() and not source.is_symlink():
        target.mkdir(parents=True, exist_ok=True)
        for entry in source.iterdir():
            _link_tree(entry, target / entry.name)
    elif not target.exists():
        target.parent.mkdir(parents=True, exist_ok=True)
        if source.is_symlink():
            target.symlink_to(os.readlink(source))
        else:
            os.link(source, target)


def _run(command, **kwargs):
    done = subprocess.run([str(c) for c in command], capture_output=True, text=True, **kwargs)
    assert done.returncode == 0, f"{' '.join(map(str, command))} failed:\n" \
        f"{(done.stdout + done.stderr)[-6000:]}"
    return done.stdout


@pytest.mark.launch
def test_a_fresh_launch_installs_icm_with_the_first_cell_and_runs_a_notebook(
        tmp_path, note):
    times = {}
    clock = time.perf_counter()
    env = _without_python_path() | {"PIP_DISABLE_PIP_VERSION_CHECK": "1"}
    env.pop("VIRTUAL_ENV", None)
    venv = tmp_path / "venv"
    python = venv / "bin" / "python"
    # Without pip: this run's pip is linked in with the rest (ensurepip takes 5 s).
    _run([sys.executable, "-m", "venv", "--without-pip", venv], env=env)
    # The Binder files alone: the requirements as repo2docker installs them. They are
    # requirements.txt itself (test_binder_reuses_the_pinned_requirements), which this
    # run's environment was installed from on a bare Python (make's set-up, on every
    # fresh clone): its packages, icm left out, are linked in rather than unpacked a
    # second time (100 s). Then every pin of the file must be installed at its version
    # (what `pip install -r` would find satisfied, in 0.2 s instead of 8 s of pip's
    # resolver), and pip checks that every installed package has what it requires.
    _link_installed_packages(pathlib.Path(sys.prefix), venv)
    unmet = _run([python, "-c", UNMET_PINS, *_requirement_lines(ROOT / "requirements.txt")],
                 env=env, cwd=ROOT)
    assert unmet.strip() == "[]", f"pins not installed as pinned: {unmet}"
    _run([python, "-m", "pip", "check"], env=env, cwd=ROOT)
    times["venv from binder/requirements.txt"] = time.perf_counter() - clock
    where = [python, "-c", "import importlib.util; print(importlib.util.find_spec('icm'))"]
    assert _run(where, env=env, cwd=tmp_path).strip() == "None"

    # A reader's launch: the notebook alone in a folder outside the repository, every
    # cell run, the first one installing icm from ICM_SOURCE (the repository's address
    # on Colab; here a copy of this checkout, as a clone would hold it).
    clock = time.perf_counter()
    source = _copy_checkout(tmp_path / "clone")
    launch = tmp_path / "launch"
    launch.mkdir()
    notebook = launch / LAUNCHED.name
    shutil.copy(LAUNCHED, notebook)
    executed_path = tmp_path / "executed.ipynb"
    _run([python, "-c", RUN_NOTEBOOK, ROOT / "book" / "_ext" / "execute_book.py", notebook,
          executed_path], env=env | {"ICM_SOURCE": str(source)}, cwd=launch)
    executed = nbformat.read(executed_path, as_version=4)
    code = [c for c in executed.cells if c.cell_type == "code"]
    assert code[0].source == INSTALL_CELL and code[0].execution_count == 1
    assert [c.execution_count for c in code] == list(range(1, len(code) + 1))
    assert not [o for c in code for o in c.outputs if o.output_type == "error"]
    times["notebook, the install cell included"] = time.perf_counter() - clock

    # The icm that the cell installed: in the new environment, from ICM_SOURCE, with the
    # models (physics) and the system's rendering working.
    clock = time.perf_counter()
    installed = json.loads(_run([python, "-c", INSTALLED], env=env, cwd=tmp_path))
    assert installed["file"].startswith(str(venv / "lib")), installed["file"]
    assert installed["url"]["url"] == source.as_uri()
    assert installed["url"].get("dir_info", {}).get("editable") is not True
    assert installed["image"] == [48, 64, 3] and installed["lit"] > 0
    times["physics and rendering in the installed icm"] = time.perf_counter() - clock

    # Binder: postBuild installs icm (editable) from the repository's root; the
    # notebook's first cell then does nothing (ICM_SOURCE cannot be installed, so a
    # cell that tried would fail), and the physics and rendering work from the
    # repository's own files. (The rest of the notebook ran above against the same
    # files, installed: running it again here took 14 s of a make test and caught
    # nothing the checks here do not.)
    clock = time.perf_counter()
    _run(["bash", source / "binder" / "postBuild"], cwd=source,
         env=env | {"PATH": f"{venv / 'bin'}{os.pathsep}{env['PATH']}"})
    binder = env | {"ICM_SOURCE": str(tmp_path / "no-such-project")}
    first_cell = nbformat.read(LAUNCHED, as_version=4).cells[0].source
    _run([python, "-c", first_cell], env=binder, cwd=launch)
    installed = json.loads(_run([python, "-c", INSTALLED], env=binder, cwd=launch))
    assert installed["file"] == str(source / "icm" / "__init__.py"), installed["file"]
    assert installed["url"].get("dir_info", {}).get("editable") is True
    assert installed["image"] == [48, 64, 3] and installed["lit"] > 0
    times["postBuild, then the first cell and the physics again"] = time.perf_counter() - clock

    # Colab: its own Python gets icm's declared dependencies, not requirements.txt:
    # they must resolve to the MuJoCo major version that dm-control is pinned with.
    clock = time.perf_counter()
    report = tmp_path / "report.json"
    # --no-build-isolation: icm's own metadata is built with the setuptools at hand
    # rather than one installed into a temporary environment first (5 s); what is
    # resolved, icm's dependencies, is the same.
    _run([python, "-m", "pip", "install", "--quiet", "--dry-run", "--ignore-installed",
          "--no-build-isolation", "--report", report, source], env=env, cwd=tmp_path)
    resolved = {re.sub(r"[-_.]+", "-", item["metadata"]["name"]).lower():
                item["metadata"]["version"]
                for item in json.loads(report.read_text())["install"]}
    pinned = dict(line.split("==") for line in _requirement_lines(ROOT / "requirements.txt")
                  if "==" in line)
    assert resolved["mujoco"].split(".")[0] == pinned["mujoco"].split(".")[0], resolved
    assert "dm-control" in resolved
    times["what pip resolves for icm on a bare Python"] = time.perf_counter() - clock

    note("fresh launch: " + ", ".join(f"{k} {v:.0f} s" for k, v in times.items()))


# --- icm's dependencies, as the install cell asks for them ---------------------------

def _install_module():
    import importlib

    return importlib.import_module("icm._install")


def test_the_install_step_asks_for_dm_control_alone_then_everything_else(capsys):
    install = _install_module()
    project = tomllib.loads((ROOT / "pyproject.toml").read_text())["project"]
    # icm's requirements as its installed metadata lists them (pip install of this
    # checkout writes them from pyproject.toml).
    metadata = project["dependencies"] + [
        f'{r}; extra == "{extra}"' for extra, listed in project["optional-dependencies"].items()
        for r in listed]
    assert install.main(["--dry-run"], requires=metadata) == 0
    first, second = capsys.readouterr().out.strip().splitlines()
    assert first.endswith("--no-warn-conflicts --no-deps dm-control")
    asked = second.split("--no-warn-conflicts ", 1)[1].split()
    names = {install._name(r) for r in asked}
    for text in project["dependencies"] + project["optional-dependencies"]["notebooks"]:
        assert install._name(text) in names | {"dm-control"}, text
    assert "labmaze" not in names and "dask" not in names
    assert install.main(["--please"]) == 2


def test_the_install_step_reads_extras_and_markers():
    install = _install_module()
    requires = ["numpy", "h5py; extra == \"hdf5\"", "myst-nb; extra == 'notebooks'",
                "tomli; python_version < \"3.11\""]
    assert install._plain(requires) == ["numpy", "tomli; python_version < \"3.11\""]
    assert install._plain(requires, "notebooks") == [
        "numpy", "myst-nb", "tomli; python_version < \"3.11\""]
    assert [install._name(r) for r in ("dm_control>=1", "Dm.Control", "PyYAML==6")] == [
        "dm-control", "dm-control", "pyyaml"]


COLAB_PACKAGES = ROOT / "tests" / "data" / "colab-packages.txt"
COLAB_PYTHON = shutil.which("python3.13")
COLAB_NOTEBOOKS = ("button_experiment.ipynb", "simulated_icub.ipynb")
"""A chapter without physics, and one with physics and drawing."""

RUN_AS_COLAB = """\
import pathlib, sys, time
import nbformat
from nbclient import NotebookClient
path, out = pathlib.Path(sys.argv[1]), pathlib.Path(sys.argv[2])
nb = nbformat.read(path, as_version=4)
# A reader's Jupyter runs every cell, the install cell too (no tag is obeyed).
NotebookClient(nb, timeout=1800, kernel_name="python3", skip_cells_with_tag="none",
               resources={"metadata": {"path": str(path.parent)}}).execute()
nbformat.write(nb, out)
"""


@pytest.mark.launch
@pytest.mark.skipif(os.environ.get("ICM_COLAB_CHECK") != "1" or COLAB_PYTHON is None,
                    reason="the Colab check runs with ICM_COLAB_CHECK=1 and python3.13 on "
                           "the PATH (it installs about 110 packages)")
def test_a_colab_like_python_installs_icm_and_runs_a_chapter_with_and_without_physics(
        tmp_path, note):
    env = _without_python_path() | {"PIP_DISABLE_PIP_VERSION_CHECK": "1",
                                    "PYDEVD_DISABLE_FILE_VALIDATION": "1"}
    env.pop("VIRTUAL_ENV", None)
    venv = tmp_path / "colab"
    python = venv / "bin" / "python"
    _run([COLAB_PYTHON, "-m", "venv", venv], env=env)
    _run([python, "-m", "pip", "install", "--quiet", "--no-deps", "-r", COLAB_PACKAGES],
         env=env)
    shipped = _run([python, "-m", "pip", "freeze"], env=env)
    source = _copy_checkout(tmp_path / "clone")
    launch = tmp_path / "launch"
    launch.mkdir()
    for name in COLAB_NOTEBOOKS:
        notebook = launch / name
        shutil.copy(ROOT / "book" / name, notebook)
        _run([python, "-Xfrozen_modules=off", "-c", RUN_AS_COLAB, notebook,
              tmp_path / f"executed-{name}"], env=env | {"ICM_SOURCE": str(source)}, cwd=launch)
        executed = nbformat.read(tmp_path / f"executed-{name}", as_version=4)
        code = [c for c in executed.cells if c.cell_type == "code"]
        assert all(c.execution_count for c in code), name
        assert not [o for c in code for o in c.outputs if o.output_type == "error"], name
        stderr = [o.text for c in code for o in c.outputs
                  if o.output_type == "stream" and o.name == "stderr"]
        assert stderr == [], (name, stderr)
    # Colab's own numpy, scipy, matplotlib, pandas and numba were kept.
    after = _run([python, "-m", "pip", "freeze"], env=env)
    for package in ("numpy", "scipy", "matplotlib", "pandas", "numba", "ipykernel"):
        pinned = [line for line in shipped.splitlines() if line.lower().startswith(package + "==")]
        assert pinned and pinned[0] in after.splitlines(), package
    added = sorted(set(after.splitlines()) - set(shipped.splitlines()))
    note("Colab-like launch: the install cell added " + ", ".join(
        line.split(" @ ")[0] for line in added))
