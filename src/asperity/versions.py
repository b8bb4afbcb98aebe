"""The version of the code behind each stage's results.

Every rule of the workflow passes the version of the code that computes its outputs
through ``params:`` (`code_version`), so that Snakemake reruns a stage when its version
changes, and the result files carry it (netCDF attribute ``code_version``, PNG text
``asperity code_version``). `asperity show` flags a file written by another version.

Bump a stage's number in `VERSIONS` in the commit that changes what the stage computes
(its numbers, its variables, its figures), and nothing else: after an upgrade exactly
the stages whose code changed are computed again, with what depends on their files. A
sample job's version is that of its asperity kind (``sample:<kind>``,
`asperity.population.kinds`): bumping one kind reruns its FE samples only.
"""

from __future__ import annotations

#: stage (a rule of the workflow, or ``sample:<kind>``) -> version of the code behind its outputs
VERSIONS: dict[str, int] = {
    # surface (workflow/rules/surface.smk)
    "synthetic_profile": 1,
    "synthetic_profiles": 1,
    "synthetic_map": 1,
    "surface": 3,
    "convergence": 1,
    # population (workflow/rules/population.smk): the plan, the samples by kind, the gather
    "plan": 3,
    "sample:hertz": 1,
    "sample:elastic": 1,
    "sample:inelastic": 4,
    "sample:adhesive": 6,
    "sample:elliptic": 4,
    "asperities": 4,
    # homogenize (workflow/rules/homogenize.smk)
    "expectation": 1,
    "unloading": 1,
    "interface": 3,
    "route_interface": 5,
    "verification": 1,
    # friction (workflow/rules/friction.smk)
    "friction": 2,
    "laws": 1,
    # uniaxial, sliding, plane strain, accuracy, the studies of workflow/rules/studies.smk
    "uniaxial": 1,
    "accuracy_bodner_partom": 2,
    "sliding": 12,
    "plane_strain": 3,
    "accuracy_hertz": 1,
    "accuracy_scenes": 1,
    "accuracy_sliding": 1,
    "accuracy_inelastic_case": 1,
    "adhesion_curves": 1,
    "route_errors": 1,
    "scale_study": 1,
    "j2_sphere": 1,
    "validity_summary": 1,
    "friction_report": 1,
    "adhesion_report": 1,
    "plane_strain_table": 1,
    # the deterministic reference (workflow/rules/reference.smk)
    "reference": 3,
    "reference_comparison": 4,
    # figures (workflow/rules/figures.smk and the figures of the rules above)
    "surface_figure": 1,
    "expectation_figure": 1,
    "interface_figure": 1,
    "adhesion_figure": 1,
    "asperities_figure": 2,
    "verification_figure": 1,
    "unloading_figure": 1,
    "friction_figure": 1,
    "laws_figure": 1,
    "uniaxial_figure": 1,
    "sliding_figure": 3,
    "plane_strain_figure": 1,
    "plane_strain_mesh_figure": 1,
    "reference_figure": 1,
}

#: the netCDF attribute (and PNG text key) that holds a file's code version
ATTRIBUTE = "code_version"


def code_version(stage: str) -> str:
    """``"<stage> <version>"``: what a rule's ``params: version`` and its files carry."""
    try:
        return f"{stage} {VERSIONS[stage]}"
    except KeyError:
        raise KeyError(f"no code version for stage {stage!r} in asperity.versions.VERSIONS") from None


def sample_version(kind: str) -> str:
    """The code version of a sample job of asperity kind `kind`."""
    return code_version(f"sample:{kind}")


def stale(written: str | None) -> str | None:
    """Why a file whose ``code_version`` is `written` is out of date (None: it is not,
    or it names no stage of this version of the code)."""
    if not written:
        return None
    stage, _, number = written.rpartition(" ")
    if stage not in VERSIONS:
        return None
    current = str(VERSIONS[stage])
    if number == current:
        return None
    return f"written by {stage} version {number}; this code computes version {current}"
