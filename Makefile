# Everything runs inside .venv, created on first use from Python 3.11.
PYTHON ?= python3.11
SHELL := /bin/bash
.SHELLFLAGS := -o pipefail -c
VENV := .venv
BIN := $(VENV)/bin
STAMP := $(VENV)/.installed

.PHONY: book book-students pdf test test-quick lab lab-instructor bench mutants clean clean-lab check-system repository assignments slides

# Before anything slow: what the system must provide besides Python packages
# (icm/_system.py: Python 3.11+, Mesa's EGL on Linux), with the command that installs it.
check-system:
	@$(PYTHON) icm/_system.py

# The packages are installed by uv (pinned below, itself installed by pip): pip unpacks
# some 200 wheels one at a time, on one core (25 s from a warm pip cache on the 2-core
# machine of CONTRIBUTING.md, 2026-12-03), uv in parallel (6 s from an empty cache of
# its own, 2 s from a warm one; the same versions as pip's resolver picks, checked with
# `pip freeze`). It reads the system's certificates, as pip does here.
# uv compiles bytecode with every package's tests; compileall -j 0 leaves those out (the
# packages' own test suites, a quarter of the code, are never imported) and uses every
# core. Every module must be compiled ahead: processes that write no bytecode (loky's
# workers run python -B) would otherwise compile what they import each time they start.
UV_VERSION := 0.13.9
UV := $(BIN)/uv pip install --system-certs --python $(BIN)/python

$(STAMP): requirements.txt pyproject.toml
	@echo "[1/3] creating $(VENV) with $(PYTHON), and uv $(UV_VERSION) in it"
	@test -x $(BIN)/python || $(PYTHON) -m venv $(VENV)
	@$(BIN)/python -m pip install --quiet uv==$(UV_VERSION)
	@echo "[2/3] installing the pinned requirements (a few minutes the first time)"
	@$(UV) --upgrade-package pip pip -r requirements.txt 2>&1 | awk '!/^ ([-+~] |Downloaded )/'
	@echo "      compiling their bytecode on every core"
	@$(BIN)/python -m compileall -q -j 0 -x '/tests/' "$$($(BIN)/python -c 'import sysconfig; print(sysconfig.get_path("purelib"))')"
	@echo "[3/3] installing icm itself (editable)"
	@$(UV) --quiet --no-deps -e .
	@touch $(STAMP)

book: check-system $(STAMP)  ## execute the notebooks (unless cached and the library unchanged), build _build/html
	$(BIN)/python book/_ext/build_book.py

book-students: check-system $(STAMP)  ## the book without the exercises' solutions, into _build/students/_build/html
	$(BIN)/python book/_ext/student_edition.py

assignments: check-system $(STAMP)  ## each chapter's assignment (student's notebook, autograder) with otter, into _build/assignments
	$(BIN)/python -m icm.course assign _build/assignments

slides: book  ## one reveal.js deck per chapter from the built book, into _build/slides (open index.html)
	$(BIN)/python -m icm.course slides _build/html --out _build/slides

pdf: book  ## the book as one PDF (_build/pdf/book.pdf), printed offline by headless Chromium
	$(BIN)/python book/_ext/print_book.py --html _build/html --out _build/pdf/book.pdf

# The tests run on every core (pytest-xdist), a test module at a time, longest first
# (tests/conftest.py orders them); the book builds in the background meanwhile.
PYTEST := $(BIN)/python -m pytest -n auto --dist loadscope --no-loadscope-reorder

test: check-system $(STAMP)  ## every test, the whole book built with warnings and errors fatal
	$(PYTEST)

test-quick: $(STAMP)  ## the unit tests, often: no book, no browser, no fresh launch, none of minutes
	$(PYTEST) -m "not book and not browser and not launch and not slow"

# The chapters as their pages read, in JupyterLab (book/_ext/lab_edition.py): executed as
# `make book` executes them (the same cache: after a make book nothing runs again), their
# numbers written into the prose, in _build/lab/students without the exercises'
# solutions (lab-instructor: _build/lab/instructor, with them); never book/ itself. As
# root, with --allow-root. LAB_ARGS go to jupyter lab, e.g. LAB_ARGS="--ip=0.0.0.0
# --port 8890 --no-browser" in a container.
lab: check-system $(STAMP)  ## open the chapters in JupyterLab, with their numbers, without the solutions
	$(BIN)/python book/_ext/lab_edition.py $(LAB_ARGS)

lab-instructor: check-system $(STAMP)  ## the same, with the exercises' solutions
	$(BIN)/python book/_ext/lab_edition.py --instructor $(LAB_ARGS)

# Mutation testing (issue 48): mutmut changes the statistics, the grade sheet, the
# limits, the file writers and the records one line at a time and runs the fast tests
# that reach each change (pyproject.toml, [tool.mutmut]); a mutant no test fails on
# lives. Not part of make test: about an hour on 2 cores. mutmut is pinned in
# requirements-mutants.txt, installed on first use; its work is kept in mutants/ (a run
# after a change re-runs only what the change touched).
$(VENV)/.mutmut: requirements-mutants.txt $(STAMP)
	@$(UV) --quiet -r requirements-mutants.txt
	@touch $@

mutants: $(VENV)/.mutmut  ## mutation testing: the score (at least 90% killed) and every survivor
	$(BIN)/mutmut run --max-children 2
	$(BIN)/python benchmarks/mutation_score.py

bench: $(STAMP)  ## print benchmark figures
	$(BIN)/python benchmarks/bench.py

repository:  ## make repository URL=https://github.com/OWNER/NAME: the address, everywhere
	@test -n "$(URL)" || { echo "usage: make repository URL=https://github.com/OWNER/NAME"; exit 1; }
	$(PYTHON) book/_ext/set_repository.py $(URL)

# Everything under _build but the JupyterLab chapters (_build/lab), where a student's
# own work may be: `make clean-lab` removes those too.
clean:
	@mkdir -p _build
	find _build -mindepth 1 -maxdepth 1 ! -name lab -exec rm -rf {} +
	@if [ -d _build/lab ]; then echo "kept _build/lab (the chapters of make lab, with any work of yours); make clean-lab removes it"; fi

clean-lab:  ## remove the chapters make lab wrote, and any work in them
	rm -rf _build/lab
