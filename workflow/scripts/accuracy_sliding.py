"""results/accuracy/sliding.nc and its figure: what accuracy costs for a sliding asperity."""

from asperity.io.figures import save_figure
from asperity.io.joblog import job_log
from asperity.io.netcdf import read_dataset, write_dataset
from asperity.stages import accuracy

with job_log(snakemake.log[0], "accuracy study of a sliding asperity"):
    p = snakemake.params
    ds = accuracy.sliding_accuracy_dataset(dict(snakemake.input.items()), p.study)
    write_dataset(ds, snakemake.output.data, scene="accuracy",
                  title="what accuracy costs for a sliding asperity: each preset against the next finer",
                  config={"accuracy_sliding": p.study}, version=p.version)
    save_figure(accuracy.sliding_accuracy_figure(read_dataset(snakemake.output.data)), snakemake.output.figure,
                version=p.version)
