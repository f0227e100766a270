"""The system calls a submission's program may not make, as a seccomp filter that
bubblewrap installs before the program starts (`icm.course.sandbox`). The filter is
built by libseccomp (the system's libseccomp2, through `pyseccomp`), which knows each
architecture's numbers; nothing here is written by hand."""

import errno
import os

REFUSED_CALLS = ("add_key", "request_key", "keyctl", "unshare", "setns", "ptrace",
                 "process_vm_readv", "process_vm_writev", "userfaultfd", "perf_event_open",
                 "bpf", "mount", "umount2", "pivot_root", "open_by_handle_at",
                 "name_to_handle_at", "kexec_load", "kexec_file_load", "init_module",
                 "finit_module", "delete_module", "acct", "swapon", "swapoff", "reboot")
"""The system calls the confined program may not make (they fail with EPERM), as
Docker's default profile refuses them: the keyrings (kept per user, so one run could
leave a key for the next), new namespaces, reading or tracing other processes, and
the kernel's riskier interfaces. `clone` with a new user namespace is refused too, and
`clone3` says it does not exist (ENOSYS), so that the C library falls back to `clone`,
whose flags the filter can read."""
CLONE_NEWUSER = 0x10000000


def seccomp_filter():
    """The confined program's seccomp filter, as BPF (bubblewrap's `--seccomp`): every
    system call allowed but `REFUSED_CALLS`. Built by libseccomp, which knows each
    architecture's numbers (through `pyseccomp`).

    Returns:
      The filter's bytes.

    Raises:
      OSError: where libseccomp is missing (`probe` says so).
    """
    import pyseccomp

    rules = pyseccomp.SyscallFilter(pyseccomp.ALLOW)
    for name in REFUSED_CALLS:
        rules.add_rule(pyseccomp.ERRNO(errno.EPERM), name)
    rules.add_rule(pyseccomp.ERRNO(errno.ENOSYS), "clone3")
    rules.add_rule(pyseccomp.ERRNO(errno.EPERM), "clone",
                   pyseccomp.Arg(0, pyseccomp.MASKED_EQ, CLONE_NEWUSER, CLONE_NEWUSER))
    read, write = os.pipe()
    try:
        with os.fdopen(write, "wb") as file:
            rules.export_bpf(file)
        chunks = []
        while chunk := os.read(read, 65536):
            chunks.append(chunk)
    finally:
        os.close(read)
    return b"".join(chunks)
