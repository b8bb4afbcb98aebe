# A plane-strain asperity of 6061-T4 aluminum pressed by a rigid flat, elastic and
# viscoplastic, on a coarse and a refined mesh (report 6.3.2, Figs. 6.15-6.18; 6.3.3,
# Figs. 6.19-6.23).


rule plane_strain:
    """Force against interference of both bodies on each mesh, the largest nonelastic strain
    (a scene's `plane_strain` section with its material and effects, at the accuracy preset)."""
    input:
        made("plane_strain.nc"),
    output:
        f"{RESULTS}/{{scene}}/plane_strain.nc",
    log:
        f"{RESULTS}/{{scene}}/logs/plane_strain.log",
    conda:
        ENV
    params:
        version=code_version("plane_strain"),
        scene=lambda w: w.scene,
        title=scene_part("title"),
        report=scene_part("report"),
        units=scene_part("units"),
        plane_strain=scene_part("plane_strain"),
        material=scene_part("material"),
        effects=scene_part("effects"),
        accuracy=accuracy_of,
    script:
        "../scripts/plane_strain.py"


rule plane_strain_figure:
    """Figs. 6.17 and 6.22: force against interference, elastic and viscoplastic, both meshes."""
    input:
        made("figures/plane_strain.png"),
        plane_strain=f"{RESULTS}/{{scene}}/plane_strain.nc",
    output:
        report(
            f"{RESULTS}/{{scene}}/figures/plane_strain.png",
            category="{scene}",
            caption="../report/plane_strain.rst",
            labels={"scene": "{scene}", "figure": "plane-strain asperity"},
        ),
    log:
        f"{RESULTS}/{{scene}}/logs/plane_strain_figure.log",
    conda:
        ENV
    params:
        version=code_version("plane_strain_figure"),
        units=scene_part("units"),
    script:
        "../scripts/plane_strain_figure.py"


rule plane_strain_mesh_figure:
    """Figs. 6.15, 6.16, 6.19-6.21: each mesh, and the viscoplastic body on it at the end."""
    input:
        made("figures/plane_strain_meshes.png"),
        plane_strain=f"{RESULTS}/{{scene}}/plane_strain.nc",
    output:
        report(
            f"{RESULTS}/{{scene}}/figures/plane_strain_meshes.png",
            category="{scene}",
            caption="../report/plane_strain_meshes.rst",
            labels={"scene": "{scene}", "figure": "plane-strain meshes"},
        ),
    log:
        f"{RESULTS}/{{scene}}/logs/plane_strain_mesh_figure.log",
    conda:
        ENV
    params:
        version=code_version("plane_strain_mesh_figure"),
        units=scene_part("units"),
    script:
        "../scripts/plane_strain_mesh_figure.py"
