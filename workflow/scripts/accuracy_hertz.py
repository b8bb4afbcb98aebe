"""results/accuracy/hertz.nc and its figure: what accuracy costs in time."""

from asperity.studies.hertz import hertz_accuracy_study
from asperity.plots.accuracy_hertz import accuracy_figure
from asperity.io.figures import save_figure
from asperity.io.netcdf import write_dataset
from asperity.io.joblog import job_log

with job_log(snakemake.log[0], "accuracy study (Hertz)"):
    s = snakemake.params.study
    ds = hertz_accuracy_study(radius=s["radius"], youngs_modulus=s["youngs_modulus"], poisson=s["poisson"],
                              interferences=tuple(s["interferences"]),
                              penalty_factors=tuple(s["penalty_factors"]))
    write_dataset(ds, snakemake.output.data, scene="accuracy", title="accuracy study on the Hertz problem",
                  config={"accuracy_study": s})
    save_figure(accuracy_figure(ds), snakemake.output.figure)
