"""Grades one submission with otter-grader, in a process of its own (started by
`icm.course.grade`, which sets its time and memory limits and kills it and everything
it started when it is done):

    python -m icm.course._worker AUTOGRADER_ZIP NOTEBOOK RESULT_JSON CELL_TIMEOUT \
        MEMORY_BYTES CPU_SECONDS

It first limits its own address space and CPU time (the kernel it starts inherits
both), and kills every process it started before it ends.

Otter executes the notebook in a Jupyter kernel (nbconvert's ExecutePreprocessor) and
runs the tests in it. Otter gives the executor no time limit per cell, so a cell that
never ends would hold the whole submission; here the executor is otter's own with a
limit per cell, after which the kernel is interrupted (KeyboardInterrupt in that
cell) and the next cells run, so that a loop in one exercise costs that exercise
only. Writes the results as JSON: {"tests": {name: {"score", "possible", "cases":
[{"name", "hidden", "points", "passed", "message"}]}}, "error": text or None}.

Both this process and the kernel go without jsonschema's IRI format checks
(`SKIP_SLOW_IMPORT`): 1.5 s of start-up each, for checks that nothing here uses.
"""

import json
import sys

from icm._book import SKIP_SLOW_IMPORT  # icm/_book.py says why


def _limited_executor(cell_timeout):
    """nbconvert's ExecutePreprocessor with a time limit per cell and an interrupt when
    it is reached."""
    import nbconvert.preprocessors
    import traitlets

    class LimitedExecutePreprocessor(nbconvert.preprocessors.ExecutePreprocessor):
        timeout = traitlets.Integer(cell_timeout, allow_none=True).tag(config=True)
        interrupt_on_timeout = traitlets.Bool(True).tag(config=True)
        # The kernel runs SKIP_SLOW_IMPORT as it starts, before the notebook's cells
        # (IPython's exec_lines: not a cell, not in the executed notebook).
        extra_arguments = traitlets.List(
            traitlets.Unicode(), [f"--IPKernelApp.exec_lines={SKIP_SLOW_IMPORT}"]
        ).tag(config=True)

    # otter.execute.grade_notebook imports it from here when it runs.
    nbconvert.preprocessors.ExecutePreprocessor = LimitedExecutePreprocessor


def summary(results):
    """Otter's `GradingResults` as plain data.

    Args:
      results: the results.

    Returns:
      A dict (see the module's docstring).
    """
    tests = {}
    for name, test_file in results.results.items():
        cases = []
        outcomes = list(test_file.test_case_results)
        for i, case in enumerate(test_file.test_cases):
            outcome = outcomes[i] if i < len(outcomes) else None
            cases.append({"name": case.name, "hidden": bool(case.hidden),
                          "points": float(case.points or 0),
                          "passed": bool(outcome is not None and outcome.passed),
                          "message": (outcome.message if outcome is not None else
                                      "this test did not run")})
        tests[name] = {"score": float(test_file.score), "possible": float(test_file.possible),
                       "cases": cases}
    error = results.catastrophic_error
    return {"tests": tests, "error": None if error is None else
            f"{type(error).__name__}: {error}"}


def limit(memory_bytes, cpu_seconds):
    """Limits this process's address space and CPU time, and those of the processes it
    starts (the kernel, and what the notebook starts)."""
    import resource

    resource.setrlimit(resource.RLIMIT_AS, (memory_bytes, memory_bytes))
    resource.setrlimit(resource.RLIMIT_CPU, (cpu_seconds, cpu_seconds + 5))
    resource.setrlimit(resource.RLIMIT_CORE, (0, 0))


def kill_descendants(pid=None):
    """Kills every process started by `pid` (default: this one), at any depth: a
    kernel runs in a session of its own, out of reach of its parent's group."""
    import psutil

    try:
        children = psutil.Process(pid).children(recursive=True)
    except psutil.Error:
        return
    for child in children:
        try:
            child.kill()
        except psutil.Error:
            pass


def main(argv=None):
    autograder, notebook, result, cell_timeout, memory, cpu = (argv or sys.argv[1:])[:6]
    exec(SKIP_SLOW_IMPORT)  # before anything imports jsonschema
    limit(int(memory), int(cpu))
    _limited_executor(int(float(cell_timeout)))
    try:
        from otter.api import grade_submission

        results = grade_submission(notebook, autograder, quiet=True)
        with open(result, "w") as file:
            json.dump(summary(results), file)
    finally:
        kill_descendants()
    return 0


if __name__ == "__main__":
    sys.exit(main())
