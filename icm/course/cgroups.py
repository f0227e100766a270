"""Control groups for the grader's confinement (`icm.course.sandbox`): one group per
submission, under `GROUP`, with a limit on the memory and on the processes of
everything in it, which reports whether the kernel killed a process for want of
memory and the most memory used, and kills all its processes when the submission
ends.

Version 1 (the memory and pids hierarchies, as on this project's machines) and version 2
(the unified hierarchy with the memory and pids controllers). Writing them needs root,
or a group delegated to the user.
"""

import os
import pathlib
import signal
import time

GROUP = "icm-grade"
"""The control group under which each submission's group is made."""


class _Group:
    """One submission's control group (in one or two hierarchies)."""

    def __init__(self, folders, limits, kill_file):
        self.folders = folders
        self.kill_file = kill_file
        self.limits = limits

    def add(self, pid):
        """Moves a process into the group (in every hierarchy)."""
        for folder in self.folders:
            (folder / "cgroup.procs").write_text(str(pid))

    def pids(self):
        """The processes in the group."""
        found = set()
        for folder in self.folders:
            try:
                found.update(int(p) for p in (folder / "cgroup.procs").read_text().split())
            except OSError:
                pass
        return found

    def peak_memory(self):
        """The most memory the group used at once, in bytes (0 if unknown)."""
        for folder in self.folders:
            for name in ("memory.peak", "memory.max_usage_in_bytes"):
                try:
                    return int((folder / name).read_text().split()[0])
                except (OSError, ValueError, IndexError):
                    continue
        return 0

    def out_of_memory(self):
        """Whether the kernel killed a process of the group for want of memory."""
        for folder in self.folders:
            for name in ("memory.events", "memory.oom_control"):
                try:
                    for line in (folder / name).read_text().splitlines():
                        key, _, value = line.partition(" ")
                        if key == "oom_kill" and int(value) > 0:
                            return True
                except (OSError, ValueError):
                    continue
        return False

    def kill_and_remove(self, timeout=10.0):
        """Kills every process of the group and removes it.

        Returns:
          Whether the group was emptied (False: a process survived `timeout`).
        """
        deadline = time.monotonic() + timeout
        while True:
            pids = self.pids()
            if not pids:
                break
            if self.kill_file is not None and self.kill_file.exists():
                self.kill_file.write_text("1")
            for pid in pids:
                try:
                    os.kill(pid, signal.SIGKILL)
                except ProcessLookupError:
                    pass
            if time.monotonic() > deadline:
                return False
            time.sleep(0.02)
        for folder in self.folders:
            for _ in range(100):  # a group is removable once its last process is reaped
                try:
                    folder.rmdir()
                    break
                except FileNotFoundError:
                    break
                except OSError:
                    time.sleep(0.02)
        return True


CPU_PERIOD = 100_000
"""The scheduler's period for a group's share of the processor, in microseconds."""


class CgroupV1:
    """Control groups of version 1: the memory and pids hierarchies, and the cpu one
    where it is mounted (a submission's processes then share `Limits.cpus` cores at
    most, however many they are: 60 spinning processes take one core, not 60 shares).

    Args:
      root: where the hierarchies are mounted (/sys/fs/cgroup).
    """

    version = 1

    def __init__(self, root="/sys/fs/cgroup"):
        self.root = pathlib.Path(root)
        self.parents = [self.root / "memory" / GROUP, self.root / "pids" / GROUP]
        self.cpu = self.root / "cpu" / GROUP

    def usable(self):
        """Why these groups cannot be used here, or "" if they can."""
        for hierarchy, probe in (("memory", "memory.limit_in_bytes"), ("pids", "pids.max")):
            folder = self.root / hierarchy
            if not (folder / "cgroup.procs").exists():
                return f"no cgroup v1 {hierarchy} hierarchy at {folder}"
            try:
                (folder / GROUP).mkdir(exist_ok=True)
            except OSError as error:
                return f"cannot make a control group in {folder} ({error.strerror})"
            if not (folder / GROUP / probe).exists():
                return f"the {hierarchy} controller is missing at {folder}"
        if (self.root / "cpu" / "cpu.cfs_quota_us").exists():
            try:
                self.cpu.mkdir(exist_ok=True)
            except OSError as error:
                return f"cannot make a control group in {self.cpu.parent} ({error.strerror})"
        return ""

    def create(self, name, limits):
        """A new group with `limits`.

        Args:
          name: its name, unique among the groups alive.
          limits: a `Limits`.

        Returns:
          A `_Group`.
        """
        memory, pids = (parent / name for parent in self.parents)
        memory.mkdir()
        pids.mkdir()
        (memory / "memory.limit_in_bytes").write_text(str(limits.memory))
        swap = memory / "memory.memsw.limit_in_bytes"
        if swap.exists():  # with swap accounting: no swapping past the limit
            swap.write_text(str(limits.memory))
        (pids / "pids.max").write_text(str(limits.processes))
        folders = [memory, pids]
        if self.cpu.is_dir():
            cpu = self.cpu / name
            cpu.mkdir()
            (cpu / "cpu.cfs_period_us").write_text(str(CPU_PERIOD))
            (cpu / "cpu.cfs_quota_us").write_text(str(int(limits.cpus * CPU_PERIOD)))
            folders.append(cpu)
        return _Group(folders, limits, None)


class CgroupV2:
    """Control groups of version 2, with the memory and pids controllers (and cpu's,
    where it is enabled: see `CgroupV1`).

    Args:
      root: where the unified hierarchy is mounted (/sys/fs/cgroup).
    """

    version = 2

    def __init__(self, root="/sys/fs/cgroup"):
        self.root = pathlib.Path(root)
        self.parent = self.root / GROUP

    def usable(self):
        """Why these groups cannot be used here, or "" if they can."""
        try:
            controllers = (self.root / "cgroup.controllers").read_text().split()
        except OSError:
            return f"no cgroup v2 hierarchy at {self.root}"
        missing = {"memory", "pids"} - set(controllers)
        if missing:
            return f"the cgroup v2 hierarchy at {self.root} lacks {sorted(missing)}"
        wanted = ["memory", "pids"] + (["cpu"] if "cpu" in controllers else [])
        try:
            self.parent.mkdir(exist_ok=True)
            for folder in (self.root, self.parent):
                enabled = (folder / "cgroup.subtree_control").read_text().split()
                if not set(wanted) <= set(enabled):
                    (folder / "cgroup.subtree_control").write_text(
                        " ".join(f"+{name}" for name in wanted))
        except OSError as error:
            return f"cannot make a control group in {self.root} ({error.strerror})"
        return ""

    def create(self, name, limits):
        """A new group with `limits` (see `CgroupV1.create`)."""
        folder = self.parent / name
        folder.mkdir()
        (folder / "memory.max").write_text(str(limits.memory))
        if (folder / "memory.swap.max").exists():
            (folder / "memory.swap.max").write_text("0")
        (folder / "pids.max").write_text(str(limits.processes))
        if (folder / "cpu.max").exists():
            (folder / "cpu.max").write_text(f"{int(limits.cpus * CPU_PERIOD)} {CPU_PERIOD}")
        return _Group([folder], limits, folder / "cgroup.kill")
