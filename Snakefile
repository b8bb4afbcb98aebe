# asperity: constitutive models of rough contact interfaces (Oden et al. 1993).
#
#   snakemake --cores 2            every scene of config/config.yaml
#   snakemake --cores 2 results/greenwood_williamson/interface.nc
#                                  a target of any scene file of config/scenes/,
#                                  listed in config/config.yaml or not
#   snakemake --report report.html every figure with its caption
#
# A run ends with the warnings of its jobs on the console, grouped, and the error of a
# failed job in one line (the job logs, results/<scene>/logs/<job>.log, keep all).
#
# The task graph is that of DESIGN.md: surface.nc -> (checkpoint) plan.nc ->
# one job per asperity sample -> asperities.nc -> interface.nc -> figures.
# Rules live in workflow/rules/, one file per stage (their functions in
# common.smk); scripts in workflow/scripts/ read snakemake.input/params and
# call asperity.stages. Every rule runs in the environment of
# workflow/envs/asperity.yaml (with --sdm conda); profiles/default/ holds the
# settings of a local run, which Snakemake reads without being asked.

import os

# one BLAS thread per job: jobs already run in parallel on the cores, and
# threads competing with each other slow the FE solves many-fold
for _var in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_var, "1")


configfile: "config/config.yaml"


report: "workflow/report/workflow.rst"


include: "workflow/rules/common.smk"
include: "workflow/rules/surface.smk"
include: "workflow/rules/population.smk"
include: "workflow/rules/homogenize.smk"
include: "workflow/rules/figures.smk"
include: "workflow/rules/friction.smk"
include: "workflow/rules/accuracy.smk"
include: "workflow/rules/studies.smk"
include: "workflow/rules/uniaxial.smk"
include: "workflow/rules/sliding.smk"
include: "workflow/rules/plane_strain.smk"
include: "workflow/rules/reference.smk"
include: "workflow/rules/routes.smk"


rule all:
    default_target: True
    input:
        [target for name in config["scenes"] for target in scene_targets(name)],
        # the accuracy studies, unless `studies: false` (one scene alone, benchmarks/scenes.py)
        [f"{RESULTS}/accuracy/hertz.nc", f"{RESULTS}/accuracy/bodner_partom.nc"]
        if config["studies"]
        else [],


onsuccess:
    tell_the_end(failed=False)


onerror:
    tell_the_end(failed=True)
