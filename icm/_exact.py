"""Arithmetic that rounds the same way on every machine, for the learners whose runs
the stored studies pin.

NumPy hands matrix products (`@`, `dot`) and solves (`linalg.solve`) to OpenBLAS,
which picks its kernels for the processor it finds, and it computes `exp`, `log`
and their kin on float64 with code of its own where the processor has AVX-512, with
the C library's elsewhere. Each choice adds in another order or rounds otherwise in
the last bit, and a learner that compares numbers (which movement is nearest, which
goal to try) can take another path after one such bit: the same seed then gives
another run on another machine. Seen here: a goal-babbling study made on an Intel
machine with AVX-512 and rerun on an AMD EPYC without it differed from the fifth
digit on, and the runs of being shown buttons pressed other buttons. The studies
written again with these functions on the machine without AVX-512 passed every pin
of `make test` on an AMD EPYC with it (NumPy's exp differs from the C library's
there in 4.7% of a hundred thousand values).

So these functions use only what IEEE 754 rounds the same way everywhere:
elementwise +, -, *, / (each rounded once; NumPy never fuses a multiply and an add)
and sums along an axis (added in an order fixed by the array's shape, whatever the
processor), and the C library's exp (through Python's `math.exp`, or a loop
Numba compiles that calls it; the C
library's: glibc picks its exp by the processor too, but only by whether it has FMA,
which every machine seen here has). They are
slower than BLAS on large matrices and as fast on the small ones they get here (a
local model of 8 coefficients on 12 neighbours). NumPy offers no switch for this:
its settings (`NPY_DISABLE_CPU_FEATURES`, `OPENBLAS_CORETYPE`) are read once, when
NumPy is imported, and cannot be relied on from a library imported after it.
"""

import math
import platform

import numpy as np


def _numpy_exp_is_the_c_librarys():
    """Whether NumPy's float64 exp here is the C library's: on x86-64 without AVX-512
    it calls it element by element (NumPy's own code is for AVX512F only; seen equal on
    a million values, and `tests/test_exact.py` checks a hundred thousand on every
    run). Read from NumPy's private record of the processor's features: if it moves,
    the answer is False and `exp` takes the slow path, never a wrong one."""
    try:
        from numpy._core._multiarray_umath import __cpu_features__ as features
    except ImportError:
        return False
    return platform.machine().lower() in ("x86_64", "amd64") and \
        features.get("AVX512F") is False


_FAST_EXP = _numpy_exp_is_the_c_librarys()


def _exp(value):
    try:
        return math.exp(value)
    except OverflowError:  # NumPy's answer, not an error
        return math.inf


COMPILED_FROM = 64
"""Where NumPy's exp is not the C library's, `exp` takes arrays of at least this many
values to a loop compiled by Numba (`_compiled_exp`), fewer to Python's `math.exp`
one at a time (a call into the compiled loop costs more than a few values take)."""


def _compiled_exp():
    """A loop, compiled by Numba, that calls the C library's exp on every value of a
    flat float64 array into another (LLVM lowers `math.exp` to a call to the C
    library's `exp`; the same bits as `math.exp`, checked on a hundred thousand values
    by `tests/test_exact.py`), or None where Numba would hand it to Intel's SVML
    instead (another exp, other bits). Compiled on first use and cached on disk, as
    the rods' loop is: Numba is imported only by the processes that need it."""
    global _COMPILED
    if _COMPILED is None:
        import numba

        if numba.config.USING_SVML:
            _COMPILED = False
        else:
            @numba.njit(cache=True, nogil=True)
            def loop(flat, out):
                for i in range(flat.size):
                    out[i] = math.exp(flat[i])  # inf on overflow, as NumPy's

            _COMPILED = loop
    return _COMPILED or None


_COMPILED = None


def exp(values):
    """exp of every element (float64), by the C library's exp, not NumPy's AVX-512
    code (inf where it overflows, as NumPy's, without a warning). Where NumPy's exp is
    the C library's (`_FAST_EXP`), NumPy computes it, 10 times as fast on a few hundred
    values; elsewhere a loop compiled by Numba calls it (`_compiled_exp`, from
    `COMPILED_FROM` values), or Python's `math.exp`, one value at a time."""
    values = np.asarray(values, dtype=float)
    if _FAST_EXP:
        with np.errstate(over="ignore"):
            return np.exp(values)
    if values.size >= COMPILED_FROM:
        loop = _compiled_exp()
        if loop is not None:
            flat = np.ascontiguousarray(values).ravel()
            out = np.empty_like(flat)
            loop(flat, out)
            return out.reshape(values.shape)
    flat = values.ravel().tolist()
    return np.fromiter(map(_exp, flat), dtype=float, count=len(flat)).reshape(values.shape)


def matmul(a, b):
    """a @ b over the last two axes (leading axes broadcast), each sum of products
    added term by term in order: memory for the result only, however long the sums."""
    a, b = np.asarray(a, dtype=float), np.asarray(b, dtype=float)
    if a.ndim < 2 or b.ndim < 2 or a.shape[-1] != b.shape[-2] or a.shape[-1] == 0:
        raise ValueError(f"matmul needs a [..., n, k] and b [..., k, m] with k >= 1, got "
                         f"shapes {a.shape} and {b.shape}")
    out = a[..., :, 0, None] * b[..., 0, None, :]
    for i in range(1, a.shape[-1]):
        out = out + a[..., :, i, None] * b[..., i, None, :]
    return out


def matvec(a, v):
    """a @ v for a matrix a [..., n, k] and a vector v [..., k], as `matmul` adds."""
    return matmul(a, np.asarray(v, dtype=float)[..., None])[..., 0]


def norm(v):
    """The Euclidean length of a vector v [..., k] (NumPy's `linalg.norm` of one vector
    is a BLAS dot product)."""
    v = np.asarray(v, dtype=float)
    return np.sqrt((v * v).sum(axis=-1))


def solve(a, b):
    """x with a @ x = b, for symmetric positive definite a [..., n, n] and b
    [..., n, m]: Gaussian elimination without pivoting (stable for such matrices),
    then back substitution.

    Raises:
      ValueError: if a is not square, or b's rows are not a's.
    """
    a, b = np.array(a, dtype=float), np.array(b, dtype=float)  # copies, changed below
    n = a.shape[-1]
    if a.ndim < 2 or a.shape[-2] != n or b.ndim < 2 or b.shape[-2] != n:
        raise ValueError(f"solve needs a [..., n, n] and b [..., n, m], got shapes "
                         f"{a.shape} and {b.shape}")
    for c in range(n - 1):
        factor = a[..., c + 1:, c, None] / a[..., c, None, c, None]
        a[..., c + 1:, c:] -= factor * a[..., c, None, c:]
        b[..., c + 1:, :] -= factor * b[..., c, None, :]
    x = np.empty(np.broadcast_shapes(a.shape[:-2], b.shape[:-2]) + b.shape[-2:])
    for c in range(n - 1, -1, -1):
        known = (a[..., c, c + 1:, None] * x[..., c + 1:, :]).sum(axis=-2)
        x[..., c, :] = (b[..., c, :] - known) / a[..., c, c, None]
    return x
