"""results/studies/adhesion_curves.nc and its figure: report 7.3, Fig. 7.6."""

from asperity.io.figures import save_figure
from asperity.io.joblog import job_log
from asperity.io.netcdf import write_dataset
from asperity.stages import studies

with job_log(snakemake.log[0], "study adhesion curves (Fig. 7.6)"):
    p = snakemake.params
    ds = studies.adhesion_curves_dataset(p.study)
    write_dataset(ds, snakemake.output.data, scene="studies",
                  title="load-deflection curves of smooth aluminum asperities with adhesion (Fig. 7.6)",
                  config={"adhesion_curves": p.study}, version=p.version)
    save_figure(studies.adhesion_curves_figure(ds), snakemake.output.figure, version=p.version)
