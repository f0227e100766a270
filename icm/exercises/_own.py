"""Whether an answer is the student's own: what a student's function calls while a
check runs it.

An exercise asks the student to write one piece of a learner; the package holds that
piece (the library's implementation, and the exercises' references). An answer that
calls it passes every case without doing the exercise, so the checks run the
student's function under a profiler (`sys.setprofile`) and stop it at the first call
into what the exercise forbids: a module of the library (every function and method
of it, found by the file its code comes from), the exercises and the grader
themselves, or a function that reads the caller's frames or turns the profiler off.
Detecting calls, not imports, catches an answer that reaches the library in any way
(an import inside the function, `importlib`, a name passed around).

No library does this for us: otter-grader and nbgrader grade what a function
returns, not what it calls.
"""

import copy
import dataclasses
import gc
import importlib
import inspect
import os
import sys
import threading

ALWAYS = ("icm.exercises", "icm.course")
"""Modules no answer may call: the checks with their references, and the grader."""
PRYING = (sys._getframe, sys._current_frames, sys.setprofile, sys.settrace,
          gc.get_objects, gc.get_referrers, gc.get_referents)
"""Built-in functions that read the checker's frames or objects, or turn the watch
off: called from a student's own code, the answer is not graded."""
PRYING_PYTHON = (inspect.currentframe, inspect.stack, inspect.getouterframes,
                 inspect.trace, threading.setprofile, threading.settrace)
"""The same, written in Python (the standard library's wrappers)."""
CHECKER_CODE = set()
"""Code objects the checker itself runs inside a student's function (the grader's time
limit's signal handler): never the student's doing. `allow` adds to it."""
_LIBRARY_PREFIXES = tuple(sorted({os.path.realpath(p) + os.sep for p in
                                  (sys.prefix, sys.base_prefix, sys.exec_prefix)}))


def allow(function):
    """Lets the checker's own `function` run inside a student's function without
    counting as the student's call (a signal handler).

    Args:
      function: a Python function.

    Returns:
      The function (a decorator).
    """
    CHECKER_CODE.add(function.__code__)
    return function


class BorrowedAnswer(BaseException):
    """Raised inside a student's function at its first forbidden call, to stop it
    (a BaseException, so that `except Exception` in the student's code does not
    swallow it)."""


@dataclasses.dataclass(frozen=True)
class Borrowed:
    """What an answer called that it must not.

    Attributes:
      name: the function called, as "module.name".
      why: "library" (the library's implementation of the exercise), "reference"
        (the exercises or the grader) or "prying" (the checker's frames, or the
        profiler).
    """

    name: str
    why: str

    def hint(self, exercise):
        """The sentence a report shows.

        Args:
          exercise: the exercise's name, as the report shows it.

        Returns:
          The text.
        """
        if self.why == "prying":
            return (f"Your function calls `{self.name}`, which reads the checker's own "
                    f"frames or turns its watch off: a graded answer that does this gets 0 "
                    f"for {exercise}. Compute the answer from the arguments alone.")
        what = ("the library's implementation of what this exercise asks you to write"
                if self.why == "library" else "a reference answer of the exercises")
        return (f"Your function calls `{self.name}`, {what}: the answer must be your own "
                f"code. A graded answer that calls it gets 0 for {exercise}.")


class Forbidden:
    """What an exercise's answer must not call.

    Args:
      modules: names of the library's modules (or packages) that hold the exercise's
        answer, e.g. ("icm.learners.interest",); `ALWAYS` is added.
    """

    def __init__(self, modules=()):
        self.modules = tuple(modules) + ALWAYS
        self._resolved = None

    def _resolve(self):
        if self._resolved is None:
            files, folders = {}, {}
            for name in self.modules:
                module = importlib.import_module(name)
                path = os.path.realpath(module.__file__)
                why = "reference" if name in ALWAYS else "library"
                if os.path.basename(path) == "__init__.py":
                    folders[os.path.dirname(path) + os.sep] = (name, why)
                else:
                    files[path] = (name, why)
            codes = {f.__code__: f"{f.__module__}.{f.__qualname__}" for f in PRYING_PYTHON}
            builtins = {f: f"{getattr(f, '__module__', None) or 'sys'}.{f.__name__}"
                        for f in PRYING}
            self._resolved = files, folders, codes, builtins, {}
        return self._resolved

    def __repr__(self):
        return f"Forbidden({', '.join(self.modules)})"


class _Watch:
    """The profiler: records the first forbidden call and stops the function there."""

    def __init__(self, forbidden, home):
        self.files, self.folders, self.codes, self.builtins, self.seen = forbidden._resolve()
        self.home = home
        self.found = None

    def _module_of(self, filename):
        known = self.seen.get(filename)
        if known is None:
            path = os.path.realpath(filename)
            known = self.files.get(path, False)
            if not known:
                for folder, entry in self.folders.items():
                    if path.startswith(folder):
                        known = entry
                        break
            self.seen[filename] = known
        return known

    def __call__(self, frame, event, arg):
        if self.found is not None or frame is self.home:
            return
        if event == "call":
            code = frame.f_code
            if code in CHECKER_CODE:
                return
            if code in self.codes:
                self._stop(Borrowed(self.codes[code], "prying"))
            known = self._module_of(code.co_filename)
            if known:
                module = frame.f_globals.get("__name__") or known[0]
                self._stop(Borrowed(f"{module}.{code.co_qualname}", known[1]))
        elif event == "c_call" and arg in self.builtins and not \
                os.path.realpath(frame.f_code.co_filename).startswith(_LIBRARY_PREFIXES):
            self._stop(Borrowed(self.builtins[arg], "prying"))

    def _stop(self, borrowed):
        self.found = borrowed
        sys.setprofile(None)
        raise BorrowedAnswer(borrowed.name)


class Remote:
    """A student's function that runs in another process: the grader's confinement
    (`icm.course.grade`), where the library is absent. The checks call it as any
    function; it calls nothing in this process, so it is called unwatched.

    Subclasses implement `__call__` and `many`.
    """

    def many(self, arguments, times):
        """Calls the function `times` times (see `call_own_many`).

        Args:
          arguments: the arguments, a tuple.
          times: how many calls.

        Returns:
          The list of what each call returned.
        """
        raise NotImplementedError


def _fresh(arguments):
    """A deep copy of `arguments` that shares their random generators."""
    memo = {id(value): value for value in arguments
            if type(value).__name__ == "Generator"}
    return copy.deepcopy(arguments, memo)


def call_own_many(function, arguments, times, forbidden):
    """Calls `function` `times` times, each on a fresh copy of `arguments` except
    their random generators, which every call shares (a random rule drawn many times
    from one generator). A `Remote` function does it in one exchange with its process.

    Args:
      function: the student's function.
      arguments: its arguments, a tuple.
      times: how many calls, an integer >= 1.
      forbidden: a `Forbidden`, or None to call it unwatched.

    Returns:
      (the list of results, None), or (the results before it, a `Borrowed`) for an
      answer that called what it must not.

    Raises:
      Whatever the function raises, unchanged.
    """
    if isinstance(function, Remote):
        return function.many(arguments, times), None
    results = []
    for _ in range(times):
        result, borrowed = call_own(function, _fresh(arguments), forbidden)
        if borrowed is not None:
            return results, borrowed
        results.append(result)
    return results, None


def call_own(function, arguments, forbidden):
    """Calls `function(*arguments)` watching what it calls.

    Args:
      function: the student's function.
      arguments: its arguments, a tuple.
      forbidden: a `Forbidden`, or None to call it unwatched.

    Returns:
      (the result, None) for an answer that called nothing forbidden, or (None, a
      `Borrowed`) for one that did (it is stopped at that call).

    Raises:
      Whatever the function raises, unchanged.
    """
    if forbidden is None or isinstance(function, Remote):
        return function(*arguments), None
    forbidden._resolve()  # (imports, before the watch starts)
    watch = _Watch(forbidden, sys._getframe())
    previous, previous_threads = sys.getprofile(), threading.getprofile()
    threading.setprofile(watch)  # (threads the function starts are watched too)
    sys.setprofile(watch)
    try:
        result = function(*arguments)
    except BorrowedAnswer:
        result = None
    except BaseException:
        if watch.found is None:
            raise
        result = None  # the student's code turned the stop into another error
    finally:
        sys.setprofile(previous)
        threading.setprofile(previous_threads)
    return (None, watch.found) if watch.found is not None else (result, None)
