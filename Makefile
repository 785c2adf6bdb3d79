# Hertz penalty contact: setup, runs, studies, report, benchmark, tests.
PYTHON ?= python3
JOBS ?= $(shell nproc)

.PHONY: all setup run sweep rerun sweep-quick report bench test lint clean

all: setup sweep                  ## set up, run every study, write the report

setup:                            ## FreeFEM + MUMPS from Debian, path fix, Python packages
	bash driver/setup.sh

run:                              ## the seed case, P2, with files in results/default
	cd edp && FreeFem++ -nw -v 0 hertz.edp -kpen 1e5 -out ../results/default

sweep:                            ## every study (resumable), then the report
	$(PYTHON) -m driver sweep --all --jobs $(JOBS)
	$(PYTHON) -m driver report

rerun:                            ## every study recomputed from scratch (--force), then the report
	$(PYTHON) -m driver sweep --all --force --jobs $(JOBS)
	$(PYTHON) -m driver report

sweep-quick:                      ## the small subset used by the tests and CI
	$(PYTHON) -m driver sweep --all --quick --jobs $(JOBS)

report:                           ## charts and results/REPORT.md from results/*.csv
	$(PYTHON) -m driver report

bench:                            ## timings: medians of 5 runs, ratios
	$(PYTHON) -m driver bench

test:                             ## the test suite (runs the quick sweep if results are missing)
	$(PYTHON) -m pytest -q tests

lint:                             ## FreeFEM compile-only check
	cd edp && FreeFem++ -jc -nw -v 0 hertz.edp

clean:                            ## remove per-case work directories (keeps the study CSVs)
	rm -rf results/runs results/default
