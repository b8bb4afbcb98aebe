"""results/accuracy/bodner_partom.nc and its figure: implicit against explicit integration."""

from asperity.io.figures import save_figure
from asperity.io.joblog import job_log
from asperity.io.netcdf import read_dataset, write_dataset
from asperity.stages import uniaxial

with job_log(snakemake.log[0], "accuracy study (Bodner-Partom material point)") as log:
    s = snakemake.params.study
    ds = uniaxial.accuracy_dataset(s)
    for name, r, m in zip(ds["test"].values, ds["steps_ratio_reference"].values,
                          ds["steps_ratio_matched"].values):
        log.info("%s: explicit/implicit steps %.1f (pairing), %.1f (matched accuracy)", name, r, m)
    write_dataset(ds, snakemake.output.data, scene="accuracy",
                  title="implicit against explicit integration of the Bodner-Partom material point",
                  config={"accuracy_bodner_partom": s}, version=snakemake.params.version)
    save_figure(uniaxial.accuracy_figure(read_dataset(snakemake.output.data)), snakemake.output.figure,
                version=snakemake.params.version)
