"""What the system must provide besides Python packages: checked before anything slow,
and named with the command that installs it when physics cannot start."""

import ctypes.util
import subprocess
import sys

import pytest

from conftest import ROOT
from icm import _system


def test_the_check_passes_on_this_machine():
    completed = subprocess.run([sys.executable, str(ROOT / "icm" / "_system.py")],
                               capture_output=True, text=True)
    assert completed.returncode == 0 and completed.stderr == ""


@pytest.mark.parametrize("missing, says", [("EGL", "libEGL is missing"),
                                           ("EGL_mesa", "libEGL_mesa) is missing")])
def test_missing_egl_is_named_with_the_command_that_installs_it(monkeypatch, missing, says):
    real = ctypes.util.find_library
    monkeypatch.setattr(_system.platform, "system", lambda: "Linux")
    monkeypatch.setattr(_system.ctypes.util, "find_library",
                        lambda name: None if name == missing else real(name))
    problem = _system.missing_rendering()
    assert says in problem and _system.INSTALL_COMMAND in problem
    assert _system.main() == 1


def test_an_old_python_is_named(monkeypatch):
    monkeypatch.setattr(_system.sys, "version_info", (3, 9, 18))
    assert any("Python 3.11 or newer" in p for p in _system.problems())


def test_the_check_needs_only_the_standard_library():
    # It runs with the system's Python before .venv exists.
    source = (ROOT / "icm" / "_system.py").read_text()
    imports = {line.split()[1].split(".")[0] for line in source.splitlines()
               if line.startswith(("import ", "from "))}
    assert imports <= set(sys.stdlib_module_names)


def test_a_physics_that_cannot_start_for_lack_of_egl_says_what_to_install(monkeypatch):
    from icm.envs import icub
    from icm.envs.buttons import physics

    def fails(model):  # what dm_control raises without libEGL, as it builds a physics
        raise AttributeError("'NoneType' object has no attribute 'eglQueryString'")

    monkeypatch.setattr(physics.ButtonsPhysics, "from_model", fails)
    monkeypatch.setattr(icub._system, "missing_rendering", lambda: "libEGL is missing: "
                        + _system.INSTALL_COMMAND)
    monkeypatch.setenv("MUJOCO_GL", "egl")
    with pytest.raises(RuntimeError, match="cannot be built: libEGL is missing.*apt-get"):
        physics.load_physics()
    monkeypatch.setattr(icub._system, "missing_rendering", lambda: None)
    with pytest.raises(AttributeError, match="eglQueryString"):  # another cause: as it is
        physics.load_physics()
