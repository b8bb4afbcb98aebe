# Stage 1-2: profile or map statistics (report 2.3, 2.4.3) -> surface.nc


rule synthetic_profile:
    """A synthetic profile of the report's examples (2.6.1), written as a text file."""
    output:
        f"{RESULTS}/{{scene}}/input/profile.txt",
    log:
        f"{RESULTS}/{{scene}}/logs/synthetic_profile.log",
    conda:
        ENV
    params:
        version=code_version("synthetic_profile"),
        generate=lambda w: SCENES[w.scene]["surface"]["profile"]["generate"],
        units=scene_part("units"),
    script:
        "../scripts/synthetic_profile.py"


rule synthetic_profiles:
    """Profiles of a synthetic anisotropic surface along the scene's directions (2.3.2)."""
    output:
        directory(f"{RESULTS}/{{scene}}/input/profiles"),
    log:
        f"{RESULTS}/{{scene}}/logs/synthetic_profiles.log",
    conda:
        ENV
    params:
        version=code_version("synthetic_profiles"),
        generate=lambda w: SCENES[w.scene]["surface"]["profiles"]["generate"],
        units=scene_part("units"),
    script:
        "../scripts/synthetic_profiles.py"


rule synthetic_map:
    """A synthetic Gaussian random height map, written as .npy."""
    output:
        f"{RESULTS}/{{scene}}/input/map.npy",
    log:
        f"{RESULTS}/{{scene}}/logs/synthetic_map.log",
    conda:
        ENV
    params:
        version=code_version("synthetic_map"),
        generate=lambda w: SCENES[w.scene]["surface"]["map"]["generate"],
    script:
        "../scripts/synthetic_map.py"


rule surface:
    """Surface statistics by sampling, counting and spectrum; or given statistics."""
    input:
        made("surface.nc"),
        unpack(surface_inputs),
    output:
        f"{RESULTS}/{{scene}}/surface.nc",
    log:
        f"{RESULTS}/{{scene}}/logs/surface.log",
    conda:
        ENV
    params:
        version=code_version("surface"),
        scene=lambda w: w.scene,
        surface=scene_part("surface"),
        units=scene_part("units"),
    script:
        "../scripts/surface.py"


rule convergence:
    """Sampled statistics of a synthetic series against its exact ones, versus spacing."""
    input:
        made("convergence.nc"),
    output:
        f"{RESULTS}/{{scene}}/convergence.nc",
    log:
        f"{RESULTS}/{{scene}}/logs/convergence.log",
    conda:
        ENV
    params:
        version=code_version("convergence"),
        scene=lambda w: w.scene,
        generate=lambda w: SCENES[w.scene]["surface"]["profile"]["generate"],
        units=scene_part("units"),
    script:
        "../scripts/convergence.py"
