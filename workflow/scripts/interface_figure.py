"""figures/interface.png from interface.nc (and verification.nc)."""

from asperity import plots
from asperity.io.figures import save_figure
from asperity.io.netcdf import read_dataset
from asperity.joblog import job_log

with job_log(snakemake.log[0], "interface figure"):
    i, u = snakemake.input, snakemake.params.units
    ver = read_dataset(i.verification) if "verification" in i.keys() else None
    fig = plots.interface_figure(read_dataset(i.interface), ver, length_unit=u["length"],
                                 pressure_unit=u.get("pressure", "Pa"))
    save_figure(fig, snakemake.output[0])
