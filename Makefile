# Set-up and the commands of the README. Needs only Python 3.11 and make.
PYTHON ?= python3.11
VENV := .venv
BIN := $(VENV)/bin
STAMP := $(VENV)/.installed-stamp
CORES ?= 2
# one BLAS thread per process: parallel jobs and tests share the cores
export OPENBLAS_NUM_THREADS = 1
export OMP_NUM_THREADS = 1

.PHONY: all reproduce test test-fast docs bench time-scenes time-jobs time-adhesion time-plane-strain time-reference time-surface time-sliding time-remesh time-edge-band time-finite-strain compare-results figures clean-results

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
# longest first (the order of tests/conftest.py, not xdist's by test count).
PYTEST := $(BIN)/python -m pytest -q -n $(CORES) --dist loadfile --no-loadscope-reorder

# The whole test suite (what CI runs).
test: $(STAMP)
	$(PYTEST)

# Everything but the tests marked slow.
test-fast: $(STAMP)
	$(PYTEST) -m "not slow"

# The documentation site in site/: the reference and verification pages generated from
# config/schema.yaml, the command line and benchmarks/results/ (docs/generate.py), then
# built with warnings as errors.
docs: export NO_MKDOCS_2_WARNING = 1
docs: $(STAMP)
	$(BIN)/python docs/generate.py
	$(BIN)/mkdocs build --strict --quiet

# Speed measurements; writes benchmarks/out/results.json and prints a table.
bench: $(STAMP)
	$(BIN)/python benchmarks/run.py

# Wall time of each scene from an empty copy, then of the whole default run
# (the README's scene times); writes benchmarks/results/scenes-$(ACCURACY).json.
# A subset: make time-scenes ACCURACY=draft SCENES="profile_cosine hertz" FULL=
ACCURACY ?= standard
SCENES ?=
FULL ?= --full
time-scenes: $(STAMP)
	$(BIN)/python benchmarks/scenes.py --accuracy $(ACCURACY) --cores $(CORES) $(if $(SCENES),--scenes $(SCENES)) $(FULL)

# What a job pays before it computes: Snakemake per script job, and each
# script's imports; writes benchmarks/results/job-overhead.json.
time-jobs: $(STAMP)
	$(BIN)/python benchmarks/job_overhead.py --cores $(CORES)

# CPU time of the adhesive jobs (the adhesion scene at draft and standard, R = 100 um,
# Fig. 7.6's curves); writes benchmarks/results/adhesion-cost.json.
time-adhesion: $(STAMP)
	$(BIN)/python benchmarks/adhesion_cost.py

# Numbers and CPU time of the plane-strain scenes (aluminum_cylinder, truncated_v) at
# draft, standard and fine, at draft with the dimension the report does not give doubled,
# with finite strain and with unloading; writes benchmarks/results/plane-strain.json.
time-plane-strain: $(STAMP)
	$(BIN)/python benchmarks/plane_strain.py --sensitivity --finite-strain --unloading

# The deterministic_reference scene at draft: its wall time and each route's, and the
# routes' errors against the boundary-element solution; writes
# benchmarks/results/reference-draft.json.
time-reference: $(STAMP)
	$(BIN)/python benchmarks/reference_cost.py --accuracy draft --cores $(CORES)

# The sliding study (asperity_sliding, report 9.2) at draft, standard and fine, one core
# each (fine alone takes hours): force histories compared between presets, the mean
# tangential traction; writes benchmarks/results/sliding-convergence.json.
# Fewer presets or a time limit: make time-sliding SLIDING_ARGS="--presets draft standard"
SLIDING_ARGS ?=
time-sliding: $(STAMP)
	$(BIN)/python benchmarks/sliding_convergence.py $(SLIDING_ARGS)

# Inelastic histories on meshes that follow the contact (issue #14): the J2 sphere to
# 50 times its critical interference at standard and fine, the viscoplastic hill of
# make bench, each with remeshing on and off (CPU time, areas, forces, steps); fine
# takes minutes. Writes benchmarks/results/remesh.json.
# A subset: make time-remesh REMESH_ARGS="--cases j2_sphere --presets standard"
REMESH_ARGS ?= --remesh on off
time-remesh: $(STAMP)
	$(BIN)/python benchmarks/remesh.py $(REMESH_ARGS)

# A scene's FE jobs without and with the band the plastic contact edge sweeps
# (asperity.edge_band): kinks of force and area, CPU. About 20 minutes at standard.
# Writes benchmarks/results/edge-band-<scene>-<preset>.json and its figure.
EDGE_BAND_ARGS ?= --scene steel_glass_bead --accuracy standard
time-edge-band: $(STAMP)
	$(BIN)/python benchmarks/edge_band_scene.py $(EDGE_BAND_ARGS)

# Finite against small strain (a J2 sphere at 2 % strain, the steepest coupled steel
# hill pressed to its amplitude) at draft and standard: CPU, force, area, strain.
# Writes benchmarks/results/finite-strain.json.
time-finite-strain: $(STAMP)
	$(BIN)/python benchmarks/finite_strain.py

# Form removal, statistics and peaks of a 2048 x 2048 map with 10 % undefined points,
# beside SurfaceTopography's rms height, gradient and curvature of the same map;
# writes benchmarks/results/surface-speed.json.
time-surface: $(STAMP)
	$(BIN)/python benchmarks/surface_speed.py

# results/ against another results tree REFERENCE, bit for bit, timings aside: what a
# change that computes nothing new must leave alone, e.g. after an upgrade
#   make compare-results REFERENCE=../asperity-before/results
compare-results: $(STAMP)
	@test -n "$(REFERENCE)" || { echo "make compare-results REFERENCE=<results folder>"; exit 2; }
	$(BIN)/python benchmarks/compare_results.py results $(REFERENCE)

# The figures shown in the README, copied from a full run.
README_FIGURES := steel_glass_bead/figures/interface.png profile_quasirandom/figures/surface.png expectation_unit/figures/expectation.png \
	greenwood_williamson/figures/interface.png map_hertz/figures/surface.png steel_hertz/figures/interface.png \
	profiles_anisotropic/figures/surface.png hertz/figures/verification.png \
	asperity_shape/figures/interface.png asperity_shape/figures/asperities.png \
	smooth_aluminum_adhesion/figures/adhesion.png truncated_v/figures/plane_strain_meshes.png
figures: reproduce
	mkdir -p docs/figures
	for f in $(README_FIGURES); do cp results/$$f docs/figures/$$(echo $$f | sed 's|/figures/|_|'); done
	cp results/accuracy/hertz.png docs/figures/accuracy_hertz.png

clean-results:
	rm -rf results .snakemake
