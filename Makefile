# pdrlearn — set-up, demo, tests, benchmarks. Every target creates .venv if missing and is idempotent.
PY ?= python3.11
VENV := .venv
BIN := $(VENV)/bin
STAMP := $(VENV)/.installed
export MPLBACKEND := Agg
# Bytecode caches on: some machines (this one) set PYTHONDONTWRITEBYTECODE=1, and then every test worker and every CLI
# subprocess re-compiles pdrlearn and pytest re-rewrites ~1000 test files on every run (docs/testing.md, session 47).
unexport PYTHONDONTWRITEBYTECODE

.PHONY: venv demo test test-all coverage bench lint clean browser external hapt peers

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

# The report's browser test needs Debian's chromium; install it when missing and possible (root + apt).
browser:
	@command -v chromium >/dev/null 2>&1 || { \
	  if [ "$$(id -u)" = 0 ] && command -v apt-get >/dev/null 2>&1; then \
	    echo "installing chromium for the report browser test (Debian package)"; \
	    (apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq chromium chromium-driver >/dev/null) \
	      || echo "chromium could not be installed: the browser test will be skipped"; \
	  else echo "chromium missing and not installable here: the browser test will be skipped"; fi; }

# Both cores (pytest-xdist): one test file per worker at a time (--dist loadfile keeps a file's module fixtures in
# one process), so the suite takes about half the serial time on a 2-core machine (docs/testing.md).
# The tests marked `extended` (costly equivalences whose mechanism a default test still exercises: --jobs / Dask / any
# clock origin / more chunkings equal the serial or one-push result; docs/testing.md D57) run in `make test-all` only.
test: $(STAMP) browser
	$(BIN)/python -m pytest -q -n 2 --dist loadfile -m "not extended"

test-all: $(STAMP) browser
	$(BIN)/python -m pytest -q -n 2 --dist loadfile

# Line + branch coverage of pdrlearn over the default suite (config: [tool.coverage.*] in pyproject; docs/testing.md).
# Serial (no -n): ~11 min of CPU on one core. HTML in out/coverage/index.html; the summary lists the modules that are
# not fully covered, the most missed statements first.
coverage: $(STAMP) browser
	mkdir -p out
	rm -f out/.coverage out/.coverage.*
	$(BIN)/python -m coverage run -m pytest -q
	$(BIN)/python -m coverage combine -q
	$(BIN)/python -m coverage html -q
	$(BIN)/python -m coverage report --skip-covered --sort=-miss

# Benchmarks are kept out of the test run (pytest-benchmark's --benchmark-skip in pyproject addopts).
bench: $(STAMP)
	mkdir -p out
	$(BIN)/python -m pytest -q -m bench --benchmark-only --benchmark-enable --benchmark-json out/bench.json \
	  --benchmark-columns=min,median,max,rounds tests/benchmarks

# Public example data of gaitmap and mobgap (pinned PyPI sdists, sha256-checked) -> datasets/external (needs the network once).
external: $(STAMP)
	$(BIN)/pdrlearn fetch mobgap --out datasets/external
	$(BIN)/pdrlearn fetch gaitmap --out datasets/external

# UCI HAPT (61 waist-phone sessions, 85 MB, about 20 s to convert; docs/external-data.md, HAPT H1-H7) in a folder of
# its own, so the sweeps over datasets/external keep their documented sets (H7).
hapt: $(STAMP)
	$(BIN)/pdrlearn fetch hapt --out datasets/hapt

# The peer tools (experiments/peers.py) in their own venv: mobgap and gaitmap pin numpy/pandas versions of their
# own, so they are no dependency of pdrlearn. scikit-learn 1.6.1: the version mobgap 1.2.0 pickled its laterality
# model with (a newer one warns "InconsistentVersionWarning ... invalid results"). pdrlearn is imported from the
# source tree (PYTHONPATH=.), not installed there. Needs datasets/external (make external) and the network once.
PEERS := .venv-peers
PEERS_STAMP := $(PEERS)/.installed

$(PEERS_STAMP):
	test -x $(PEERS)/bin/python || $(PY) -m venv $(PEERS)
	$(PEERS)/bin/python -m pip install -q --upgrade pip
	$(PEERS)/bin/python -m pip install -q mobgap==1.2.0 gaitmap==2.6.0 gaitmap-mad==2.6.0 scikit-learn==1.6.1 tabulate
	touch $(PEERS_STAMP)

peers: $(PEERS_STAMP) external
	PYTHONPATH=. $(PEERS)/bin/python experiments/peers.py

lint: $(STAMP)
	$(BIN)/ruff check pdrlearn tests experiments

clean:
	rm -rf out .pytest_cache
