# Set-up and the commands of the README. Needs only Python 3.11 and make.
PYTHON ?= python3.11
VENV := .venv
BIN := $(VENV)/bin
STAMP := $(VENV)/.installed-stamp
CORES ?= 2
# one BLAS thread per process: parallel jobs and tests share the cores
export OPENBLAS_NUM_THREADS = 1
export OMP_NUM_THREADS = 1

.PHONY: all reproduce test test-fast docs bench compare-results figures clean-results

all: reproduce

# The virtual environment, with the versions that were tested (constraints.txt).
$(STAMP): pyproject.toml constraints.txt
	test -x $(BIN)/python || $(PYTHON) -m venv $(VENV)
	$(BIN)/python -m pip install --quiet --upgrade pip
	$(BIN)/python -m pip install --quiet -c constraints.txt -e ".[test,docs]"
	touch $(STAMP)

# Run every scene of config/config.yaml.
reproduce: $(STAMP)
	$(BIN)/snakemake --cores $(CORES)

# One pytest-xdist worker per core; a test file stays on one worker, so its
# module fixtures (the workflow runs) are computed once; files are handed out
# longest first (the order of tests/conftest.py, not xdist's by test count). The 25
# slowest tests are listed at the end (where the suite's time goes).
PYTEST := $(BIN)/python -m pytest -q -n $(CORES) --dist loadfile --no-loadscope-reorder \
	--durations=25

# The whole test suite (what CI runs).
test: $(STAMP)
	$(PYTEST)

# Everything but the tests marked slow.
test-fast: $(STAMP)
	$(PYTEST) -m "not slow"

# The documentation site in site/: the reference and verification pages generated from
# config/schema.yaml, the command line, the workflow's studies in results/studies/ and the
# benchmark outputs in benchmarks/results/ (docs/generate.py; a section whose source is
# not there is kept as last written), then built with warnings as errors.
docs: export NO_MKDOCS_2_WARNING = 1
docs: $(STAMP)
	$(BIN)/python docs/generate.py
	$(BIN)/mkdocs build --strict --quiet

# Speed and cost measurements, one entry point (benchmarks/run.py): CASE=kernels (the
# default) times the kernels against the issues' targets (benchmarks/results/kernels.json);
# CASE=list names the others (scenes, reference, adhesion, sliding, ...), each writing its
# JSON to benchmarks/results/ (not tracked: `make docs` writes the docs' tables from it,
# and those are). ARGS replaces a case's default arguments, e.g.
#   make bench CASE=scenes ARGS="--accuracy draft --scenes profile_cosine hertz"
# CASE=short (what CI runs) runs a small case of every kernel and every other case, one
# after the other, so that each keeps working: their times go to benchmarks/out/short.json,
# held against no target; it fails if a case fails (ARGS: only the cases named).
CASE ?= kernels
ARGS ?=
export CORES
bench: $(STAMP)
	$(BIN)/python benchmarks/run.py $(CASE) $(ARGS)

# results/ against another results tree REFERENCE, bit for bit, timings aside: what a
# change that computes nothing new must leave alone, e.g. after an upgrade
#   make compare-results REFERENCE=../asperity-before/results
compare-results: $(STAMP)
	@test -n "$(REFERENCE)" || { echo "make compare-results REFERENCE=<results folder>"; exit 2; }
	$(BIN)/python benchmarks/compare_results.py results $(REFERENCE)

# The figures shown in the README and the docs, copied from a full run (and the unloaded
# ridge, a scene of the plane-strain table).
README_FIGURES := steel_glass_bead/figures/interface.png profile_quasirandom/figures/surface.png expectation_unit/figures/expectation.png \
	greenwood_williamson/figures/interface.png map_hertz/figures/surface.png steel_hertz/figures/interface.png \
	profiles_anisotropic/figures/surface.png hertz/figures/verification.png \
	asperity_shape/figures/interface.png asperity_shape/figures/asperities.png \
	smooth_aluminum_adhesion/figures/adhesion.png truncated_v/figures/plane_strain_meshes.png \
	truncated_v_unloading/figures/plane_strain.png
figures: reproduce
	$(BIN)/snakemake --cores $(CORES) results/truncated_v_unloading/figures/plane_strain.png
	mkdir -p docs/figures
	for f in $(README_FIGURES); do cp results/$$f docs/figures/$$(echo $$f | sed 's|/figures/|_|'); done
	cp results/accuracy/hertz.png docs/figures/accuracy_hertz.png

clean-results:
	rm -rf results .snakemake
