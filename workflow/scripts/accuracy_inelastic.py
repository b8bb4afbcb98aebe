"""results/accuracy/inelastic_<case>.nc and its figure: what accuracy costs for an inelastic
asperity."""

from asperity.io.figures import save_figure
from asperity.io.joblog import job_log
from asperity.io.netcdf import read_dataset, write_dataset
from asperity.stages import accuracy

with job_log(snakemake.log[0], f"accuracy study of an inelastic asperity: {snakemake.params.case}") as log:
    p = snakemake.params
    ds = accuracy.inelastic_accuracy_dataset(p.case, p.study, progress=log.info)
    write_dataset(ds, snakemake.output.data, scene="accuracy",
                  title=f"what accuracy costs for an inelastic asperity: {p.case}",
                  config={"accuracy_inelastic": p.study}, version=p.version)
    save_figure(accuracy.inelastic_accuracy_figure(read_dataset(snakemake.output.data)), snakemake.output.figure,
                version=p.version)
