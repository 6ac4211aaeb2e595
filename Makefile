# seahelm — the two commands: `make demo` and `make test` (and `make test-fast`, the unit tier).
#
# Dependencies resolve to the newest versions pyproject.toml allows (so new-version breakage is
# caught). For the exact versions the suite was last tested with, opt in to the lock file:
#     make test CONSTRAINTS=constraints.txt        (`make lock` rewrites it from a fresh venv)
PYTHON ?= python3
VENV   ?= .venv
BIN    := $(VENV)/bin
CONSTRAINTS ?=
PIP_CONSTRAINT_ARGS := $(if $(CONSTRAINTS),-c $(CONSTRAINTS),)
STAMP_RUN  := $(VENV)/.installed-run$(if $(CONSTRAINTS),-locked,)
STAMP_TEST := $(VENV)/.installed-test$(if $(CONSTRAINTS),-locked,)
STAMP_DOCS := $(VENV)/.installed-docs$(if $(CONSTRAINTS),-locked,)

.PHONY: demo test test-fast docs bench lock versions clean

$(BIN)/python:
	$(PYTHON) -m venv $(VENV)
	$(BIN)/python -m pip install --quiet --upgrade pip

$(STAMP_RUN): $(BIN)/python pyproject.toml $(CONSTRAINTS)
	$(BIN)/python -m pip install --quiet $(PIP_CONSTRAINT_ARGS) -e .
	touch $@

$(STAMP_TEST): $(BIN)/python pyproject.toml $(CONSTRAINTS)
	$(BIN)/python -m pip install --quiet $(PIP_CONSTRAINT_ARGS) -e ".[test]"
	touch $@ $(STAMP_RUN)

$(STAMP_DOCS): $(BIN)/python pyproject.toml $(CONSTRAINTS)
	$(BIN)/python -m pip install --quiet $(PIP_CONSTRAINT_ARGS) -e ".[docs]"
	touch $@ $(STAMP_RUN)

demo: $(STAMP_RUN)
	MPLBACKEND=Agg $(BIN)/seahelm demo --out seahelm-out

versions: $(STAMP_RUN)
	@$(BIN)/python -m seahelm.versions

test: $(STAMP_TEST)
	@echo "tested with: $$($(BIN)/python -m seahelm.versions)"
	@echo "kernel cache: $${SEAHELM_CACHE_DIR:-default (~/.cache/seahelm/kernels)}"
	MPLBACKEND=Agg $(BIN)/python -m pytest -n 2 --dist worksteal -q

# The unit tier, for the inner loop (a few minutes on a fresh clone): every test not marked
# `slow`, i.e. the modules in tests/conftest.py's UNIT_MODULES (no kernel compiles, no seahelm
# subprocesses). `make test` runs everything.
test-fast: $(STAMP_TEST)
	MPLBACKEND=Agg $(BIN)/python -m pytest -n 2 --dist worksteal -q -m "not slow"

# The documentation site (Sphinx): examples run, scenario reference generated from the schema,
# warnings are errors. Open docs/_build/html/index.html.
docs: $(STAMP_DOCS)
	MPLBACKEND=Agg $(BIN)/python -m sphinx -W --keep-going -q -b html docs docs/_build/html

bench: $(STAMP_RUN)
	for f in benchmarks/bench_*.py; do $(BIN)/python $$f || exit 1; done

# Rewrite constraints.txt with the versions a fresh venv resolves today (then run make test).
lock:
	rm -rf .venv-lock
	$(PYTHON) -m venv .venv-lock
	.venv-lock/bin/python -m pip install --quiet --upgrade pip
	.venv-lock/bin/python -m pip install --quiet -e ".[test]"
	{ echo "# Versions seahelm's suite passed with (make lock; opt in: make test CONSTRAINTS=constraints.txt)."; \
	  echo "# Python $$(.venv-lock/bin/python -c 'import platform; print(platform.python_version())')"; \
	  .venv-lock/bin/python -m pip freeze --exclude-editable | grep -v '^-e ' | sort -f; } > constraints.txt
	rm -rf .venv-lock

clean:
	rm -rf $(VENV) seahelm-out .pytest_cache build *.egg-info src/*.egg-info \
	  docs/_build docs/generated docs/auto_examples docs/scenario-reference.rst
