"""results/accuracy/hertz.nc and its figure: what accuracy costs in time."""

from asperity.io.figures import save_figure
from asperity.io.joblog import job_log
from asperity.io.netcdf import write_dataset
from asperity.stages import accuracy

with job_log(snakemake.log[0], "accuracy study (Hertz)"):
    p = snakemake.params
    ds = accuracy.hertz_accuracy_dataset(p.study)
    write_dataset(ds, snakemake.output.data, scene="accuracy", title="accuracy study on the Hertz problem",
                  config={"accuracy_study": p.study}, version=p.version)
    save_figure(accuracy.hertz_accuracy_figure(ds), snakemake.output.figure, version=p.version)
