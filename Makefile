# Set-up and the commands of the README. Needs only Python 3.11 and make.
PYTHON ?= python3.11
VENV := .venv
BIN := $(VENV)/bin
STAMP := $(VENV)/.installed-stamp
CORES ?= 2

.PHONY: all reproduce test test-fast bench clean-results

all: reproduce

# The virtual environment, with the versions that were tested (constraints.txt).
$(STAMP): pyproject.toml constraints.txt
	test -x $(BIN)/python || $(PYTHON) -m venv $(VENV)
	$(BIN)/python -m pip install --quiet --upgrade pip
	$(BIN)/python -m pip install --quiet -c constraints.txt -e ".[test]"
	touch $(STAMP)

# Run every scene of config/config.yaml.
reproduce: $(STAMP)
	$(BIN)/snakemake --cores $(CORES)

# The whole test suite (what CI runs).
test: $(STAMP)
	$(BIN)/python -m pytest -q

# Everything but the tests marked slow.
test-fast: $(STAMP)
	$(BIN)/python -m pytest -q -m "not slow"

# Speed measurements; writes benchmarks/out/results.json and prints a table.
bench: $(STAMP)
	$(BIN)/python benchmarks/run.py

clean-results:
	rm -rf results .snakemake
