# pdrlearn — set-up, demo, tests, benchmarks. Every target creates .venv if missing and is idempotent.
PY ?= python3.11
VENV := .venv
BIN := $(VENV)/bin
STAMP := $(VENV)/.installed
export MPLBACKEND := Agg

.PHONY: venv demo test bench lint clean

venv: $(STAMP)

# torch is pinned to the local CPU wheel (an unpinned torch pulls gigabytes of CUDA); pyproject declares a range.
$(STAMP): pyproject.toml
	test -x $(BIN)/python || $(PY) -m venv $(VENV)
	$(BIN)/python -m pip install -q --upgrade pip
	$(BIN)/python -m pip install -q torch==2.13.0
	$(BIN)/python -m pip install -q -e '.[dev]'
	touch $(STAMP)

demo: $(STAMP)
	$(BIN)/python experiments/demo.py --out out

test: $(STAMP)
	$(BIN)/python -m pytest -q

bench: $(STAMP)
	$(BIN)/python -m pytest -q -m bench --benchmark-only --benchmark-enable tests/benchmarks
	$(BIN)/python experiments/bench.py

lint: $(STAMP)
	$(BIN)/ruff check pdrlearn tests experiments

clean:
	rm -rf out .pytest_cache
