"""icm._exact: arithmetic that rounds the same way on every processor, and runs that
are the same whichever kernels NumPy's BLAS picks."""

import json
import math
import os
import subprocess
import sys

import numpy as np
import pytest

from icm import _exact


def test_the_functions_agree_with_numpy_up_to_rounding():
    rng = np.random.default_rng(5)
    m = rng.normal(size=(4, 12, 8))
    a = m.transpose(0, 2, 1) @ m + 1e-4 * np.eye(8)
    b = rng.normal(size=(4, 8, 3))
    np.testing.assert_allclose(_exact.matmul(m.transpose(0, 2, 1), m), a - 1e-4 * np.eye(8),
                               rtol=0, atol=1e-12)
    np.testing.assert_allclose(_exact.solve(a, b), np.linalg.solve(a, b), rtol=1e-9, atol=1e-9)
    w = rng.normal(size=(4, 8))
    np.testing.assert_allclose(_exact.matvec(m, w), np.einsum("rkj,rj->rk", m, w),
                               rtol=0, atol=1e-12)
    v = rng.normal(size=(6, 3))
    np.testing.assert_allclose(_exact.norm(v), np.linalg.norm(v, axis=1), rtol=1e-15)
    x = rng.normal(scale=10, size=(3, 5))
    assert _exact.exp(x).tolist() == [[math.exp(e) for e in row] for row in x.tolist()]
    # Overflow gives inf, as NumPy's exp, not math.exp's OverflowError.
    assert _exact.exp([800.0, -np.inf, 0.0]).tolist() == [math.inf, 0.0, 1.0]


@pytest.mark.parametrize("path", ["numpy", "compiled", "python"])
def test_exp_is_the_c_librarys_on_every_path(path, monkeypatch):
    # Each path (NumPy's exp, where it is the C library's; the loop compiled by Numba;
    # Python's math.exp one value at a time) gives math.exp's bits on a hundred
    # thousand values of the softmax's and LWLR's range, in a 2-D array, strided too.
    if path == "numpy" and not _exact._FAST_EXP:
        pytest.skip("NumPy's exp is not the C library's on this processor")
    if path == "compiled" and _exact._compiled_exp() is None:
        pytest.skip("Numba would use Intel's SVML here: the compiled loop is not used")
    monkeypatch.setattr(_exact, "_FAST_EXP", path == "numpy")
    monkeypatch.setattr(_exact, "COMPILED_FROM", 1 if path == "compiled" else 10 ** 9)
    x = np.random.default_rng(8).uniform(-60.0, 5.0, size=(500, 200))
    for values in (x, x[:, ::3], x.T):
        assert _exact.exp(values).tolist() == [[math.exp(v) for v in row]
                                               for row in values.tolist()]
    edges = np.array([[800.0, -np.inf], [0.0, -800.0]])
    assert _exact.exp(edges).tolist() == [[math.inf, 0.0], [1.0, 0.0]]
    assert np.isnan(_exact.exp([np.nan])).all()


def test_the_sums_are_added_in_order():
    # 1e16 + 1 + 1 - 1e16 is 0 added left to right, 2 added pairwise: matmul adds the
    # products term by term, in order.
    a = np.array([[1e16, 1.0, 1.0, -1e16]])
    assert _exact.matmul(a, np.ones((4, 1)))[0, 0] == ((1e16 + 1.0) + 1.0) - 1e16


def test_bad_shapes_are_refused():
    with pytest.raises(ValueError, match="matmul needs"):
        _exact.matmul(np.ones((2, 3)), np.ones((2, 3)))
    with pytest.raises(ValueError, match="solve needs"):
        _exact.solve(np.ones((2, 3)), np.ones((2, 1)))
    with pytest.raises(ValueError, match="solve needs"):
        _exact.solve(np.eye(2), np.ones((3, 1)))


# A small run of each learner that the stored studies pin, the bands and p-values
# the chapters print, and a raw BLAS product as the control: printed as hashes.
RUNS = r"""
import hashlib, json
import numpy as np
from icm import stats
from icm.experiments import goal_babbling

def digest(*arrays):
    h = hashlib.sha256()
    for a in arrays:
        h.update(np.ascontiguousarray(a, dtype=float).tobytes())
    return h.hexdigest()[:16]

out = {}
m = np.random.default_rng(0).normal(size=(64, 64))
out["control: numpy's own product"] = digest(m @ m)
for strategy, model in (("learning_progress", "nearest_neighbour"), ("random_goal", "lwlr")):
    r = goal_babbling.run_goal_babbling(strategy, n_seeds=2, n_rollouts=150, seed=4,
                                        inverse_model=model, progress=False)
    out[f"{strategy}, {model}"] = digest(r.test_error, r.movements, r.press_outcomes)
values = np.random.default_rng(1).random((40, 30))
out["band"] = digest(*stats.bootstrap_band(values, seed=2))
out["p-value"] = digest([stats.paired_p_value(values[:, 0] - values[:, 1], seed=3)])
print(json.dumps(out))
"""


def _hashes(coretype):
    env = dict(os.environ)
    env.pop("OPENBLAS_CORETYPE", None)
    if coretype:
        env["OPENBLAS_CORETYPE"] = coretype  # read by OpenBLAS when NumPy loads it
    done = subprocess.run([sys.executable, "-c", RUNS], env=env, capture_output=True,
                          text=True, timeout=600)
    assert done.returncode == 0, done.stderr[-3000:]
    return json.loads(done.stdout.strip().splitlines()[-1])


def test_runs_are_the_same_whichever_kernels_blas_picks():
    # OpenBLAS picks its kernels by the processor (Haswell's, SkylakeX's, ...); here the
    # same machine is made to take older ones, as another processor would take others.
    # The learners' runs, the bands and the p-values must not change by a bit.
    found = {kind: _hashes(kind) for kind in (None, "Prescott", "Sandybridge")}
    control = "control: numpy's own product"
    if len({h[control] for h in found.values()}) == 1:
        pytest.skip("OPENBLAS_CORETYPE changed nothing here (NumPy without OpenBLAS's "
                    "dynamic kernels?): this check cannot tell")
    for kind, hashes in found.items():
        for name, value in hashes.items():
            if name != control:
                assert value == found[None][name], (name, kind)
