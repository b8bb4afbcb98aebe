"""figures/verification.png: FE asperities against Hertz."""

from asperity import plots
from asperity.io.figures import save_figure
from asperity.io.netcdf import read_dataset
from asperity.io.joblog import job_log

with job_log(snakemake.log[0], "verification figure"):
    save_figure(plots.hertz_verification_figure(read_dataset(snakemake.input.verification)),
                snakemake.output[0])
