"""One student's notebook, run in its confinement, and its functions as the grader
calls them.

A `Session` runs a notebook's code cells in the runner program
(`icm.course.runner`) inside a `icm.course.sandbox.Confined`, and hands out each
function the exercises ask for as a `RemoteFunction`: a callable that the exercises'
checks call like any function, which sends its arguments to the confined program and
returns what the student's function returned there (arguments changed in place are
changed here too). Only plain values cross (the runner's codec).

Time limits: each cell has `cell_timeout` seconds; a cell that runs past it is left
out, and the notebook is run again without it (the confined program is killed, with
everything it started). Each call has the deadline the grader gives (a test's time
limit); a call past it ends the run (`CallStopped`), and the next exercise starts a
fresh run. The whole session has its own deadline (the submission's time limit).
"""

import builtins
import inspect
import time

import numpy as np

from icm.course import runner, sandbox
from icm.exercises import _own

BUILTIN_ERRORS = {name: value for name, value in vars(builtins).items()
                  if isinstance(value, type) and issubclass(value, Exception)}
"""Python's own exception classes, by name: an error the student's function raised in
its process is raised here as the same class when it is one of these."""


PARAMETER_KINDS = type(inspect.Parameter.POSITIONAL_ONLY)
"""The kinds of a parameter (positional only, ..., keyword only), by number."""


REPLY_BYTES = 2 ** 20
"""The longest reply to a call, in bytes (3,000 draws of a rule take about 10 kB): a
longer one is refused before the grader decodes it."""


class Unsendable:
    """What a student's function returned that cannot cross (an object of a class of
    its own, a function): a wrong result, shown as what it was.

    Args:
      what: the runner's description of it.
    """

    def __init__(self, what):
        self.what = what

    def __repr__(self):
        return f"<{self.what}: not a number, string, list, tuple, dict or array>"

    def __eq__(self, other):
        return False

    __hash__ = None


class StudentError(Exception):
    """An exception the student's function raised, of a class of its own (its name is
    kept: `type(error).__name__` reads as the student's class)."""


class CallStopped(BaseException):
    """A call that did not come back: its deadline passed, the program ended, or it
    raised SystemExit or KeyboardInterrupt (a BaseException, so that the checks'
    `except Exception` lets it through to the grader).

    Attributes:
      reason: what stopped it, as the feedback says it.
    """

    def __init__(self, reason):
        super().__init__(reason)
        self.reason = reason


class SessionOver(Exception):
    """The session's deadline passed or its notebook could not run at all."""


def _raised(reply):
    """The exception to raise here for what the student's function raised there."""
    raised = reply["raised"]
    if not isinstance(raised, dict):
        raise runner.WireError("a malformed error")
    name, message = str(raised.get("type"))[:80], str(raised.get("message"))[:2000]
    if raised.get("base"):
        return CallStopped(f"your function raised {name} ({message})")
    cls = BUILTIN_ERRORS.get(name)
    if cls is None:
        cls = type(name if name.isidentifier() else "StudentError", (StudentError,), {})
    try:
        return cls(message)
    except TypeError:  # a builtin class whose constructor wants more
        return type(name, (StudentError,), {})(message)


def write_back(original, new):
    """Makes `original` equal to `new` in place, keeping its containers (the checks
    read arguments that the student's function may change in place).

    Args:
      original: a list, dict, set, NumPy array or generator the grader passed.
      new: the same argument as it came back.

    Returns:
      Whether it could be written back (False: `new` is not of `original`'s kind,
      which the caller then sees by comparing).
    """
    if isinstance(original, np.random.Generator):
        if not isinstance(new, np.random.Generator):
            return False
        original.bit_generator.state = new.bit_generator.state
        return True
    if isinstance(original, np.ndarray):
        new = np.asarray(new)
        if new.shape != original.shape:
            return False
        original[...] = new
        return True
    if isinstance(original, list) and isinstance(new, list):
        if len(original) == len(new):
            for i, item in enumerate(new):
                if not write_back(original[i], item):
                    original[i] = item
        else:
            original[:] = new
        return True
    if isinstance(original, dict) and isinstance(new, dict):
        for key in [key for key in original if key not in new]:
            del original[key]
        for key, item in new.items():
            if key not in original or not write_back(original[key], item):
                original[key] = item
        return True
    if isinstance(original, set) and isinstance(new, set):
        original.clear()
        original.update(new)
        return True
    if isinstance(original, tuple) and isinstance(new, tuple) and len(original) == len(new):
        return all(write_back(o, n) or o == n for o, n in zip(original, new))
    return False


def _signature(parameters):
    """An `inspect.Signature` from the runner's description of a function's
    parameters (defaults are read as plain values; one that cannot cross is None)."""
    built = []
    for name, kind, has_default, default in parameters:
        if not (isinstance(name, str) and name.isidentifier() and kind in range(5)):
            raise runner.WireError("a malformed signature")
        value = runner.decode(default) if has_default else inspect.Parameter.empty
        built.append(inspect.Parameter(name, PARAMETER_KINDS(kind), default=value))
    return inspect.Signature(built)


class RemoteFunction(_own.Remote):
    """A student's function, called in its confinement.

    Args:
      session: the `Session` that runs it.
      name: the function's name.
      signature: its `inspect.Signature` (as the student wrote it).
    """

    def __init__(self, session, name, signature):
        self.session = session
        self.__name__ = self.__qualname__ = name
        self.__signature__ = signature

    def __repr__(self):
        return f"<the student's function {self.__name__}>"

    def __call__(self, *arguments):
        return self._call(arguments, None)

    def many(self, arguments, times):
        """Calls the function `times` times in one exchange (see
        `icm.exercises._own.call_own_many`)."""
        return self._call(tuple(arguments), int(times))

    def _call(self, arguments, times):
        reply = self.session.call(self.__name__, arguments, times)
        for original, new in zip(arguments, reply.get("args") or ()):
            write_back(original, new)
        if "raised" in reply:
            raise _raised(reply)
        return reply.get("value")


class Session:
    """A notebook's code, run confined, and its functions.

    Args:
      cells: the sources of its code cells, in order (None for a cell left out from
        the start: the handed-out cells that only the student's own kernel runs).
      functions: the names of the functions the exercises ask for.
      confinement: a `sandbox.Confinement` (None: a plain process, trusted work).
      limits: a `sandbox.Limits`.
      deadline: the session's end, a `time.monotonic()` time.
      cell_timeout: seconds one cell may run.
    """

    def __init__(self, cells, functions, confinement, limits, deadline, cell_timeout):
        self.cells = [cell if cell is not None else "" for cell in cells]
        self.skip = {i for i, cell in enumerate(cells) if cell is None}
        self.functions = list(functions)
        self.confinement = confinement
        self.limits = limits
        self.deadline = deadline
        self.cell_timeout = cell_timeout
        self.run = None
        self.described = None
        self.cell_errors = {}
        self.left_out = {}
        self.runs = 0
        self.out_of_memory = False
        self.peak_memory = 0
        self.survivors = False
        self.last_log = ""
        self.ended = ""
        self.call_deadline = deadline
        self.next_id = 0

    def __enter__(self):
        return self

    def __exit__(self, *error):
        self.stop()
        return False

    def stop(self):
        """Ends the current run, if any (every process it started is killed)."""
        if self.run is not None:
            self.run.close()
            self.out_of_memory |= self.run.out_of_memory
            self.peak_memory = max(self.peak_memory, self.run.peak_memory)
            self.survivors |= self.run.survivors
            self.last_log = self.run.log_tail()
            self.run = None

    def _remaining(self, seconds):
        return min(time.monotonic() + seconds, self.deadline)

    def _start(self):
        """Runs the notebook's cells in a new run, until its functions are described;
        a cell that runs past its limit, or ends the program, is left out and the run
        starts again without it."""
        while True:
            if time.monotonic() >= self.deadline:
                raise SessionOver("the submission's time limit passed while its cells ran")
            self.runs += 1
            job = {"cells": self.cells, "skip": sorted(self.skip), "functions": self.functions}
            if len(runner.dumps(job)) > runner.MAX_LINE - 4096:
                raise SessionOver(f"the notebook's code is larger than the grader takes "
                                  f"({runner.MAX_LINE // 2 ** 20} MiB, written as JSON)")
            self.run = sandbox.Confined(self.confinement, self.limits)
            current = None
            try:
                self.run.start(job, self.deadline)
                while True:
                    message = self.run.receive(self._remaining(self.cell_timeout)
                                               if current is not None else self.deadline)
                    if "ready" in message:
                        self.described = message["ready"]
                        if not isinstance(self.described, dict):
                            raise runner.WireError("a malformed description")
                        return
                    cell = message.get("cell")
                    if not isinstance(cell, int) or not 0 <= cell < len(self.cells):
                        raise runner.WireError("a message about no cell")
                    if message.get("done"):
                        if message.get("error"):
                            self.cell_errors[cell] = str(message["error"])[:2000]
                        current = None
                    else:
                        current = cell
            except sandbox.TimedOut:
                reason = (f"it ran past the time limit of a cell ({self.cell_timeout:g} s)"
                          if current is not None and time.monotonic() < self.deadline
                          else "the submission's time limit passed")
            except sandbox.Ended:
                reason = "it ended the notebook's process (os._exit, a crash, or memory)"
            except runner.WireError as error:
                reason = f"it broke the grader's channel ({error})"
            self.stop()
            if self.out_of_memory:
                reason = (f"it used more than the memory limit of a submission "
                          f"({self.limits.memory / 2 ** 30:g} GiB)")
            if current is None or time.monotonic() >= self.deadline:
                raise SessionOver(f"the notebook could not be run: {reason}")
            self.left_out[current] = reason
            self.skip.add(current)

    def function(self, name):
        """The student's function `name`, ready to be called.

        Args:
          name: one of `functions`.

        Returns:
          (a `RemoteFunction`, "") or (None, why there is none).

        Raises:
          SessionOver: when the notebook cannot be run any more.
        """
        if self.run is None:
            self._start()
        found = self.described.get(name)
        if not isinstance(found, dict) or found.get("type") == "NoneType":
            return None, f"`{name}` is not defined"
        if not found.get("callable"):
            return None, (f"`{name}` must be a function, not a "
                          f"{str(found.get('type'))[:40]}")
        try:
            signature = _signature(found.get("parameters") or [])
        except Exception:  # whatever the notebook's process described
            return None, f"`{name}`'s parameters could not be read"
        return RemoteFunction(self, name, signature), ""

    def call(self, name, arguments, times=None):
        """One exchange: the student's function `name` called on `arguments` (`times`
        times, if given) in the confined program, before `call_deadline`.

        Returns:
          The reply, decoded: {"value": ..., "args": [...]} or with "raised".

        Raises:
          CallStopped: when the call did not come back in time, or the program
            ended (the run is then stopped).
        """
        if self.run is None:
            raise CallStopped(self.ended or "the notebook's run had ended")
        self.next_id += 1
        request = {"id": self.next_id, "call": name, "args": runner.encode(list(arguments))}
        if times is not None:
            request["times"] = times
        deadline = min(self.call_deadline, self.deadline)
        try:
            self.run.send(request, deadline)
            reply = self.run.receive(deadline, limit=REPLY_BYTES)
            if reply.get("id") != self.next_id:
                raise runner.WireError("an answer to another call")
            if "refused" in reply:
                raise runner.WireError(str(reply["refused"])[:200])
            if "unsendable" in reply:
                return {"value": Unsendable(str(reply["unsendable"])[:200]), "args": []}
            try:
                decoded = {"args": runner.decode(reply.get("args"))}
                if "raised" in reply:
                    decoded["raised"] = reply["raised"]
                else:
                    decoded["value"] = runner.decode(reply.get("value"))
            except runner.WireError:
                raise
            except Exception as error:  # whatever a malformed value makes of decoding
                raise runner.WireError(f"a malformed value ({type(error).__name__})") \
                    from None
            return decoded
        except sandbox.TimedOut:
            reason = "it took longer than its time limit: look for a loop that never ends"
        except sandbox.Ended:
            reason = "its process ended during the call (os._exit, a crash, or memory)"
        except runner.WireError as error:
            reason = f"what it returned could not be read ({error})"
        self.stop()
        if self.out_of_memory:
            reason = (f"it used more than the memory limit of a submission "
                      f"({self.limits.memory / 2 ** 30:g} GiB)")
        self.ended = reason
        raise CallStopped(reason)

    def restart(self):
        """Forgets the current run: the next `function` runs the notebook again (after
        a call that stopped)."""
        self.stop()
        self.ended = ""
