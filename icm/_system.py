"""What the system must provide besides Python packages, checked before anything slow.

Run as a script (`make book` and `make test` do, with the system's Python, before
they install anything), it prints what is missing and the one command that installs
it, and exits with status 1; it imports nothing but the standard library. The package
calls `missing_rendering()` to explain a failed physics environment the same way.
"""

import ctypes.util
import platform
import sys

PYTHON = (3, 11)
"""The oldest Python the package supports."""
DEBIAN_PACKAGES = ("libegl1", "libegl-mesa0", "libgl1-mesa-dri")
"""Mesa's EGL with its software driver: MuJoCo draws (and dm_control builds its
physics) through it without a screen."""
INSTALL_COMMAND = "sudo apt-get install " + " ".join(DEBIAN_PACKAGES)


def missing_rendering():
    """A sentence saying what MuJoCo's headless rendering lacks on this machine, or
    None if nothing is missing (or the system is not Linux, where EGL is not used)."""
    if platform.system() != "Linux":
        return None
    if ctypes.util.find_library("EGL") is None:
        return ("libEGL is missing: MuJoCo cannot draw without a screen, and dm_control "
                f"cannot build a physics simulation. On Debian or Ubuntu: {INSTALL_COMMAND}")
    if ctypes.util.find_library("EGL_mesa") is None:
        return ("Mesa's EGL driver (libEGL_mesa) is missing: MuJoCo cannot open a "
                f"headless display. On Debian or Ubuntu: {INSTALL_COMMAND}")
    return None


def problems():
    """Everything missing, as sentences (empty if nothing is)."""
    found = []
    if sys.version_info[:2] < PYTHON:
        found.append(f"Python {PYTHON[0]}.{PYTHON[1]} or newer is needed, this is "
                     f"{platform.python_version()} ({sys.executable})")
    rendering = missing_rendering()
    if rendering:
        found.append(rendering)
    return found


def main():
    found = problems()
    for problem in found:
        print(f"missing: {problem}", file=sys.stderr)
    if found:
        print("Install what is missing, then run the command again.", file=sys.stderr)
    return 1 if found else 0


if __name__ == "__main__":
    sys.exit(main())
