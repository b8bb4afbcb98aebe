"""From a measured height map to its interface law, with the library alone (no Snakemake).

    python docs/examples/map_to_interface.py [MAP FILE]

Reads an instrument file, removes its tilt, low-passes it at the default lateral
scale and finds its summits there; then the interface law of three routes on the
same prepared map (interacting Hertz asperities, Persson's theory and the boundary
elements), written to map_interface.nc beside a table of pressure and contact area.
"""

import sys

import numpy as np
import xarray as xr

from asperity.homogenize.interacting import interacting_interface
from asperity.io.netcdf import write_dataset
from asperity.io.topography import read_measurement
from asperity.references import persson
from asperity.references.boundary_element import solve_map
from asperity.references.hertz import plane_strain_modulus
from asperity.surface.form import remove_form
from asperity.surface.summits import default_scale, lowpass_map, map_summits

path = sys.argv[1] if len(sys.argv) > 1 else "data/topographies/di-3.di"
data = read_measurement(path, "map")                      # heights and spacing in metres
dx, dy = data.spacing
z, _ = remove_form(data.heights, "tilt", defined=data.defined)
scale, rule = default_scale(dx, dy, z)                    # the lateral scale of the asperities
summits = map_summits(z, dx, dy, scale)                   # found and fitted at that scale
smooth = lowpass_map(z, dx, dy, scale)                    # what every route sees
smooth -= np.nanmean(smooth)
sigma = float(np.nanstd(smooth))
print(f"{path}: {z.shape[1]} x {z.shape[0]} points, sigma {sigma:.3g} m; {rule}")

modulus = float(plane_strain_modulus(70e9, 0.33))        # aluminum against a rigid flat
h = np.linspace(0.5, 3.0, 11) * sigma                     # the flat above the mean plane
period = (z.shape[1] * dx, z.shape[0] * dy)
routes = {
    "interacting": interacting_interface(summits["x"].values, summits["y"].values,
                                         summits["height"].values, summits["curvature"].values,
                                         h, modulus, period),
    "persson": persson.persson_interface(*persson.isotropic_spectrum(smooth, dx, dy), modulus, h),
    "boundary_elements": solve_map(smooth, dx, dy, h, modulus),
}
keep = ["nominal_pressure", "contact_area_ratio"]
law = xr.concat([ds[keep] for ds in routes.values()], dim="route", combine_attrs="drop")
law = law.assign_coords(route=("route", list(routes), {"units": "1", "long_name": "route"}))
for name in keep:  # units and long names, which concat drops
    law[name].attrs = routes["boundary_elements"][name].attrs
write_dataset(law, "map_interface.nc", scene="example", title="interface law of a map by three routes",
              config={"file": path, "scale": scale})

print("h/sigma  " + "  ".join(f"{r:>26}" for r in routes))
for k, hk in enumerate(h):
    cells = [f"{ds.nominal_pressure.values[k]:10.3g} Pa {100 * ds.contact_area_ratio.values[k]:8.3g} %"
             for ds in routes.values()]
    print(f"{hk / sigma:7.2f}  " + "  ".join(f"{c:>26}" for c in cells))
