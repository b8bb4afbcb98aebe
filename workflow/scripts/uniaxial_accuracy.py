"""results/accuracy/bodner_partom.nc and its figure: implicit against explicit integration."""

from asperity.io.figures import save_figure
from asperity.io.netcdf import read_dataset, write_dataset
from asperity.io.joblog import job_log
from asperity.plots.uniaxial import uniaxial_accuracy_figure
from asperity.uniaxial.scene import accuracy_study

with job_log(snakemake.log[0], "accuracy study (Bodner-Partom material point)") as log:
    s = snakemake.params.study
    if not s.get("tests"):
        raise ValueError("config/config.yaml: key accuracy_bodner_partom.tests: no tests given")
    reference = s.get("reference", {})
    ds = accuracy_study(s["tests"], s.get("units", {}), tolerances=s.get("tolerances"),
                        pairing=s.get("pairing"), implicit_outputs=s.get("implicit_outputs", 100),
                        explicit_outputs=s.get("explicit_outputs", 20),
                        target=s.get("target", 0.01), reference_rtol=reference.get("rtol", 1e-10),
                        reference_method=reference.get("method", "LSODA"))
    for name, r, m in zip(ds["test"].values, ds["steps_ratio_reference"].values,
                          ds["steps_ratio_matched"].values):
        log.info("%s: explicit/implicit steps %.1f (pairing), %.1f (matched accuracy)", name, r, m)
    write_dataset(ds, snakemake.output.data, scene="accuracy",
                  title="implicit against explicit integration of the Bodner-Partom material point",
                  config={"accuracy_bodner_partom": s})
    save_figure(uniaxial_accuracy_figure(read_dataset(snakemake.output.data)),
                snakemake.output.figure)
