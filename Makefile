# Hertz contact: setup, runs, studies, report, benchmark, tests. `make help` lists the targets.
PYTHON ?= python3
JOBS ?= $(shell nproc)

.PHONY: all help setup run sweep rerun sweep-quick report bench test test-fast audit lint mutate clean

all: setup sweep                  ## set up, run every study, write the report

help:                             ## this list
	@grep -E '^[a-z-]+:.*## ' $(firstword $(MAKEFILE_LIST)) | sed -E 's/^([a-z-]+):.*## /\1\t/' | expand -t 14

setup:                            ## FreeFEM + MUMPS from Debian, path fix, the Python package (pip install -e .)
	bash driver/setup.sh

run:                              ## the seed case, with its files in results/local/default
	cd edp && FreeFem++ -nw -v 0 hertz.edp -kpen 1e5 -out ../results/local/default

sweep:                            ## every study (resumable: only missing or stale rows run), then the report and the field picture
	$(PYTHON) -m driver sweep --all --jobs $(JOBS)
	$(PYTHON) -m driver report
	$(PYTHON) -m driver field

rerun:                            ## every study recomputed from scratch, then the report
	$(PYTHON) -m driver sweep --all --force --jobs $(JOBS)
	$(PYTHON) -m driver report
	$(PYTHON) -m driver field

sweep-quick:                      ## the quick subsets, into results/local/quick (not tracked)
	$(PYTHON) -m driver sweep --all --quick --jobs $(JOBS) --results results/local/quick

report:                           ## charts and results/REPORT.md from results/*.csv (no FreeFEM needed)
	$(PYTHON) -m driver report

bench:                            ## timings: medians of interleaved runs, peers included (results/local/bench.csv)
	bash driver/setup.sh --peers
	$(PYTHON) -m driver bench

# one pytest worker a core, each taking whole test files: a file's shared runs and clones stay in one worker
TEST_WORKERS = -n $(JOBS) --dist loadfile

test:                             ## the whole test suite, as CI runs it (about 10.5 minutes on 2 cores; writes nothing tracked)
	$(PYTHON) -m pytest -q $(TEST_WORKERS) tests

test-fast:                        ## the quick tier for the edit-run loop: every test not marked slow
	$(PYTHON) -m pytest -q $(TEST_WORKERS) -m "not slow" tests

audit:                            ## the promise against the truth: 500 random 2D scenes and 10 in 3D (results/local/audit.csv)
	$(PYTHON) tests/audit.py --jobs $(JOBS)

lint:                             ## FreeFEM compiles (every branch: dimension, order, formulation), ruff and mypy are clean
	cd edp && for branch in "" "-DDIM=2 -DORDER=1" "-DDIM=2 -DMIXED=1" "-DDIM=2 -DMIXED=2" "-DDIM=2 -DBODIES=2" "-DDIM=2 -DORDER=1 -DBODIES=2" "-DDIM=2 -DPLASTIC=1" "-DDIM=2 -DORDER=1 -DPLASTIC=1" "-DDIM=3" "-DDIM=3 -DBODIES=2" "-DDIM=3 -DORDER=1" "-DDIM=3 -DMIXED=1" "-DDIM=3 -DMIXED=2"; do \
	  FreeFem++ -jc -nw -v 0 hertz.edp $$branch > /dev/null || { echo "hertz.edp $$branch does not compile"; exit 1; }; done
	FreeFem++ -jc -nw -v 0 tests/edp/thick_cylinder.edp > /dev/null || { echo "tests/edp/thick_cylinder.edp does not compile"; exit 1; }
	$(PYTHON) -m ruff check driver tests bench setup.py
	$(PYTHON) -m mypy driver

mutate:                           ## break the guarded code on purpose, one mutation at a time; each must fail a test
	$(PYTHON) tests/mutations.py

clean:                            ## remove per-case work folders and local outputs (keeps the study tables)
	rm -rf results/runs results/local
