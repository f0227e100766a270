# Everything runs inside .venv, created on first use from Python 3.11.
PYTHON ?= python3.11
VENV := .venv
BIN := $(VENV)/bin
STAMP := $(VENV)/.installed

.PHONY: book test lab bench clean

$(STAMP): requirements.txt pyproject.toml
	test -x $(BIN)/python || $(PYTHON) -m venv $(VENV)
	$(BIN)/python -m pip install --quiet --upgrade pip
	$(BIN)/python -m pip install --quiet -r requirements.txt
	$(BIN)/python -m pip install --quiet --no-deps -e .
	touch $(STAMP)

book: $(STAMP)  ## execute the notebooks (unless cached and the library unchanged), build _build/html
	$(BIN)/python book/_ext/execute_book.py
	$(BIN)/jupyter-book build . --keep-going
	@echo "Open the book: $(CURDIR)/_build/html/index.html"

test: $(STAMP)  ## unit tests, then a full book build with warnings and errors fatal
	$(BIN)/python -m pytest

lab: $(STAMP)  ## open the notebooks in JupyterLab
	$(BIN)/jupyter lab book/

bench: $(STAMP)  ## print benchmark figures
	$(BIN)/python benchmarks/bench.py

clean:
	rm -rf _build
