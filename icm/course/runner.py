"""The program that runs one student's notebook inside its confinement, and the plain
values that it and the grader exchange.

The grader (`icm.course.grade`) never runs a student's code in its own process. It
starts this file as a program inside the submission's confinement
(`icm.course.sandbox`), where only Python's standard library and NumPy are present:
no icm, no otter, no grading material, no other submission. The program

1. reads its job from standard input, before any of the student's code runs: the
   notebook's code cells, the cells to leave out, and the names of the functions the
   exercises ask for;
2. runs the cells in order, in one namespace, as a kernel would (an error in a cell
   is reported and the next cell runs), saying when each starts and ends;
3. says whether each asked-for function exists and what its parameters are;
4. answers calls, one JSON line each way: the grader sends a function's name and its
   arguments, the program sends back what the function returned (or the name and text
   of what it raised) and its arguments as they are after the call (some exercises
   change them in place).

Only plain values cross (`encode`, `decode`): numbers, strings, lists, tuples, dicts,
sets, NumPy arrays and the states of NumPy's random generators. Never a pickle and
never code, so nothing the student's code sends can run in the grader. The expected
results never cross either: the grader compares what comes back with its own
reference, in its own process.

The student's code runs in this process and can change anything in it, this file's
functions included; it can only change what its own answers look like, which it could
do anyway. The grader trusts nothing it reads here beyond its shape.

This module imports nothing from icm: the grader imports it for the codec, and the
confinement runs it as a script with only the standard library and NumPy.
"""

import builtins
import inspect
import json
import math
import os
import re
import sys

MAX_DEPTH = 48
"""The deepest nesting of containers a value may have (deeper is refused, not
recursed into)."""
MAX_LINE = 16 * 2 ** 20
"""The longest message, in bytes, either side accepts (the program's job, with the
notebook's cells, included)."""
GENERATORS = ("PCG64", "PCG64DXSM", "MT19937", "Philox", "SFC64")
"""NumPy's bit generators whose state may cross."""
MAX_TIMES = 100_000
"""The most calls one request may ask for (a random rule drawn many times)."""
NUMBERS = "biuf"
"""NumPy dtype kinds an array may hold (bool, integers, floats)."""


class WireError(ValueError):
    """A value that cannot cross, or a message that is not one of ours."""


def encode(value, depth=0):
    """A value as JSON-ready data, tagged where JSON has no type of its own.

    Args:
      value: None, a bool, an int, a float, a str, a list, a tuple, a set, a dict, a
        NumPy number, array (of bools, integers or floats) or random generator, nested
        up to `MAX_DEPTH`.
      depth: the nesting so far.

    Returns:
      Data that `json.dumps` writes and `decode` reads back as an equal value.

    Raises:
      WireError: for anything else (a function, an object of a class of the
        student's), or a value nested too deeply.
    """
    if depth > MAX_DEPTH:
        raise WireError(f"a value nested more than {MAX_DEPTH} deep")
    if value is None or isinstance(value, (bool, str)):
        return value
    if isinstance(value, int):
        return int(value)
    if isinstance(value, float):
        return value if math.isfinite(value) else {"$float": repr(value)}
    if isinstance(value, list):
        return [encode(item, depth + 1) for item in value]
    if isinstance(value, tuple):
        return {"$tuple": [encode(item, depth + 1) for item in value]}
    if isinstance(value, (set, frozenset)):
        return {"$set": [encode(item, depth + 1) for item in value]}
    if isinstance(value, dict):
        if all(isinstance(key, str) and not key.startswith("$") for key in value):
            return {key: encode(item, depth + 1) for key, item in value.items()}
        return {"$dict": [[encode(key, depth + 1), encode(item, depth + 1)]
                          for key, item in value.items()]}
    return _encode_numpy(value, depth)


def _encode_numpy(value, depth):
    import numpy as np

    if isinstance(value, np.bool_):
        return bool(value)
    if isinstance(value, np.integer):
        return int(value)
    if isinstance(value, np.floating):
        return encode(float(value), depth)
    if isinstance(value, np.ndarray):
        if value.dtype.kind not in NUMBERS:
            raise WireError(f"an array of {value.dtype} (only bools, integers and "
                            f"floats cross)")
        return {"$array": encode(value.tolist(), depth + 1), "dtype": value.dtype.str,
                "shape": list(value.shape)}
    if isinstance(value, np.random.Generator):
        state = value.bit_generator.state
        if state.get("bit_generator") not in GENERATORS:
            raise WireError(f"a generator of {state.get('bit_generator')!r}")
        return {"$generator": encode(state, depth + 1)}
    raise WireError(f"a value of type {type(value).__name__}")


def decode(data, depth=0):
    """The value `encode` wrote.

    Args:
      data: what `json.loads` read.
      depth: the nesting so far.

    Returns:
      The value.

    Raises:
      WireError: for data `encode` does not write.
    """
    if depth > MAX_DEPTH:
        raise WireError(f"a value nested more than {MAX_DEPTH} deep")
    if data is None or isinstance(data, (bool, int, str)):
        return data
    if isinstance(data, float):
        return data
    if isinstance(data, list):
        return [decode(item, depth + 1) for item in data]
    if not isinstance(data, dict):
        raise WireError(f"not a value: {type(data).__name__}")
    tags = [key for key in data if key.startswith("$")]
    if not tags:
        return {key: decode(item, depth + 1) for key, item in data.items()}
    tag = tags[0]
    body = data[tag]
    if tag == "$float" and set(data) == {tag} and body in ("nan", "inf", "-inf"):
        return float(body)
    if tag in ("$tuple", "$set", "$dict") and set(data) == {tag} and isinstance(body, list):
        items = [decode(item, depth + 1) for item in body]
        if tag == "$tuple":
            return tuple(items)
        try:
            if tag == "$set":
                return set(items)
            if all(isinstance(pair, list) and len(pair) == 2 for pair in items):
                return {key: item for key, item in items}
        except TypeError:  # an unhashable key
            pass
        raise WireError(f"a malformed {tag}")
    if tag == "$array" and set(data) == {tag, "dtype", "shape"}:
        return _decode_array(data, depth)
    if tag == "$generator" and set(data) == {tag}:
        return _decode_generator(decode(body, depth + 1))
    raise WireError(f"an unknown tag {tag!r}")


def _decode_array(data, depth):
    import numpy as np

    dtype, shape = data["dtype"], data["shape"]
    if not (isinstance(dtype, str) and re.fullmatch(r"[<>|=]?[biuf][1248]", dtype)):
        raise WireError(f"an array of dtype {dtype!r}")
    if not (isinstance(shape, list) and all(isinstance(n, int) and n >= 0 for n in shape)):
        raise WireError("an array with a malformed shape")
    try:
        array = np.array(decode(data["$array"], depth + 1), dtype=dtype)
    except (TypeError, ValueError, OverflowError) as error:
        raise WireError(f"a malformed array ({error})") from None
    if list(array.shape) != shape:
        raise WireError(f"an array whose shape is not {shape}")
    return array


def _decode_generator(state):
    import numpy as np

    name = state.get("bit_generator") if isinstance(state, dict) else None
    if name not in GENERATORS:
        raise WireError(f"a generator of {name!r}")
    generator = np.random.Generator(getattr(np.random, name)())
    try:
        generator.bit_generator.state = state
    except Exception as error:  # whatever NumPy makes of a malformed state
        raise WireError(f"a malformed generator state ({type(error).__name__})") from None
    return generator


def dumps(message):
    """A message as one line of JSON, in bytes (NaN is never written bare)."""
    return json.dumps(message, allow_nan=False, separators=(",", ":")).encode() + b"\n"


def loads(line):
    """A message read from one line.

    Args:
      line: the line's bytes.

    Returns:
      The message, a dict.

    Raises:
      WireError: for a line that is not a JSON object of a sane size and depth.
    """
    if len(line) > MAX_LINE:
        raise WireError(f"a message of more than {MAX_LINE} bytes")
    try:
        message = json.loads(line)
    except (ValueError, RecursionError, UnicodeDecodeError) as error:
        raise WireError(f"a message that is not JSON ({type(error).__name__})") from None
    if not isinstance(message, dict):
        raise WireError("a message that is not a JSON object")
    return message


def describe(value):
    """What the grader needs to know of a name the notebook defined: whether it is a
    function, and its parameters (name, kind, and default if any, encoded).

    Args:
      value: the value bound to the name, or None if the name is not bound.

    Returns:
      {"callable": bool, "type": its type's name, "parameters": [[name, kind,
      has_default, default], ...] or None}.
    """
    found = {"callable": callable(value) and not isinstance(value, type),
             "type": type(value).__name__, "parameters": None}
    if found["callable"]:
        try:
            parameters = inspect.signature(value).parameters.values()
            found["parameters"] = [
                [p.name, int(p.kind), p.default is not p.empty,
                 _plain_default(p.default) if p.default is not p.empty else None]
                for p in parameters]
        except (TypeError, ValueError):
            pass
    return found


def _plain_default(value):
    try:
        return encode(value)
    except WireError:
        return None


def without_magics(source):
    """A cell's source as plain Python: IPython's line magics and shell escapes (lines
    that start with % or !) become `pass`, so that the rest of the cell runs.

    Args:
      source: the cell's source.

    Returns:
      The source, or None for a cell magic (%%), which is not Python at all.
    """
    if source.lstrip().startswith("%%"):
        return None
    lines = []
    for line in source.splitlines():
        stripped = line.lstrip()
        lines.append(line[:len(line) - len(stripped)] + "pass"
                     if stripped.startswith(("%", "!")) else line)
    return "\n".join(lines)


def _fresh(arguments):
    """A deep copy of `arguments` that shares their random generators (as
    `icm.exercises._own.call_own_many` makes them)."""
    import copy

    memo = {id(value): value for value in arguments
            if type(value).__name__ == "Generator"}
    return copy.deepcopy(arguments, memo)


def _error_text(error):
    text = f"{type(error).__name__}: {error}"
    return text if len(text) <= 2000 else text[:1997] + "..."


class _Program:
    """The program's two channels: requests on standard input, answers on a private
    copy of standard output (standard output itself goes to the log, with the
    notebook's prints)."""

    def __init__(self):
        self.inbox = os.fdopen(os.dup(0), "rb", buffering=0)
        self.outbox = os.fdopen(os.dup(1), "wb", buffering=0)
        devnull = os.open(os.devnull, os.O_RDONLY)
        os.dup2(devnull, 0)  # the notebook reads nothing of the grader's
        os.dup2(2, 1)  # its prints go to the log
        self.pending = b""

    def send(self, message):
        self.outbox.write(dumps(message))

    def receive(self):
        while b"\n" not in self.pending:
            chunk = self.inbox.read(1 << 16)
            if not chunk:
                return None
            self.pending += chunk
            if len(self.pending) > MAX_LINE:
                raise WireError("a request too long")
        line, self.pending = self.pending.split(b"\n", 1)
        return loads(line)


def _run_cells(program, job, namespace):
    skip = set(job.get("skip", ()))
    for index, source in enumerate(job["cells"]):
        if index in skip:
            continue
        program.send({"cell": index})
        code = without_magics(source)
        error = None
        if code is None:
            error = "a cell magic (%%), which only IPython runs: left out"
        else:
            try:
                exec(compile(code, f"<cell {index + 1}>", "exec"), namespace)
            except BaseException as raised:  # SystemExit and KeyboardInterrupt too
                error = _error_text(raised)
        program.send({"cell": index, "done": True, "error": error})


def _serve(program, namespace):
    while True:
        request = program.receive()
        if request is None:
            return
        reply = {"id": request.get("id")}
        function = namespace.get(request.get("call"))
        try:
            arguments = decode(request.get("args"))
        except WireError as error:
            program.send({**reply, "refused": str(error)})
            continue
        times = request.get("times")
        if times is not None and not (type(times) is int and 1 <= times <= MAX_TIMES):
            program.send({**reply, "refused": f"times must be 1 to {MAX_TIMES}"})
            continue
        try:
            if times is None:
                value = function(*arguments)
            else:  # each call on fresh arguments, the generators shared
                value = [function(*_fresh(arguments)) for _ in range(times)]
        except BaseException as raised:  # what the student's code raised, by name
            reply["raised"] = {"type": type(raised).__name__,
                               "base": not isinstance(raised, Exception),
                               "message": _error_text(raised).split(": ", 1)[-1]}
            value = None
        try:
            reply["args"] = encode(arguments)
            if "raised" not in reply:
                reply["value"] = encode(value)
        except (WireError, RecursionError) as error:
            reply = {"id": reply["id"], "unsendable": str(error)}
        program.send(reply)


def main():
    """Runs the job read from standard input (see the module's docstring)."""
    program = _Program()
    job = program.receive()
    if job is None:
        return 1
    for folder in job.get("path", ()):
        sys.path.insert(0, folder)
    import numpy  # noqa: F401 (before the notebook, so that a failing import is ours)

    namespace = {"__name__": "__main__", "__builtins__": builtins}
    _run_cells(program, job, namespace)
    program.send({"ready": {name: describe(namespace.get(name))
                            for name in job.get("functions", ())}})
    _serve(program, namespace)
    return 0


if __name__ == "__main__":
    sys.exit(main())
