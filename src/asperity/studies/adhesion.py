"""Load-deflection curves of smooth elastic aluminum asperities with adhesion (report
7.3, Fig. 7.6).

Report 7.3 presses very smooth 6061-T4 aluminum asperities (tip radii 15 to
300 um) elastically with a rigid flat carrying a Lennard-Jones adhesion
(dgamma = 1 J/m^2, equilibrium separation d = 0.3-0.5 nm), approach and
retraction, and compares the pull-off with the closed forms of Derjaguin,
Muller and Toporov (DMT, 2 pi R W) and of Johnson, Kendall and Roberts (JKR,
3/2 pi R W).  `smooth_aluminum_curves` runs the adhesive driver
(`asperity.fe.solve_asperity_adhesive`) at each radius and stacks the runs
(`asperity.fe.drivers.adhesive.stack_runs`).
"""

from __future__ import annotations

import numpy as np
import xarray as xr

from asperity.fe import (BodnerPartom, LennardJones, LinearElastic, Paraboloid,
                         solve_asperity_adhesive)
from asperity.fe.drivers.adhesive import stack_runs
from asperity.fe.outputs import accuracy_attrs, describe


def smooth_aluminum_curves(radii=(15.4e-6, 30e-6, 60e-6), d: float = 0.3e-9,
                           dgamma: float = 1.0, E: float | None = None, nu: float | None = None,
                           w_max: float = 10e-9, accuracy="draft",
                           cutoff: float | None = None) -> xr.Dataset:
    """Load-deflection curves of elastic aluminum asperities with adhesion (Fig. 7.6).

    Report 7.3: very smooth 6061-T4 aluminum (E and nu of
    `BodnerPartom.aluminum_6061_t4`, 6.3.1, unless given), asperity tip radii 15 to 300 um, dgamma =
    1 J/m^2 (DESIGN errata), d = 0.3-0.5 nm, elastic.  Each radius is a
    shallow paraboloid (`Paraboloid`: the half space with a paraboloidal
    gap; the contact radius stays below 3 % of R here, where sphere and
    paraboloid differ by well under 1 %), approached from the cut-off to
    `w_max` and retracted until it lets go.  Returns a Dataset on dims
    (radius, step) (`stack_runs`) with, per radius, the pull-off force,
    the Tabor parameter and the jump interferences, and the DMT and JKR
    pull-off forces 2 pi R W_c and 3/2 pi R W_c for comparison.

    Cost grows with the Tabor parameter (R^(1/3) / d): with d = 0.3 nm,
    mu = 4.7, 5.9, 7.5 at 15.4, 30, 60 um, and 10, 13 at 150 and 300 um
    (the flat end of 7.3's range), whose mesh follows the contact edge
    (`asperity.fe.drivers.adhesive_model`, "Mesh").  The report's Fig. 7.6 shows R = 15.4 um
    only; the default adds two flatter radii (their measured costs: docs,
    changelog, 'Adhesion').  With d = 0.5 nm, mu is 0.6 times smaller.
    """
    alloy = BodnerPartom.aluminum_6061_t4()
    mat = LinearElastic(alloy.E if E is None else E, alloy.nu if nu is None else nu)
    law = LennardJones(dgamma, d) if cutoff is None else LennardJones(dgamma, d, cutoff)
    radii = np.asarray(radii, dtype=float)
    runs = [solve_asperity_adhesive(Paraboloid(float(R)), mat, law, w_max=w_max,
                                    accuracy=accuracy, label=f"R = {R * 1e6:.4g} um")
            for R in radii]
    ds = stack_runs(runs, "radius", radii, dict(units="m", long_name="asperity tip radius"))
    W = law.work_of_adhesion
    ds["pull_off_force_dmt"] = ("radius", 2 * np.pi * radii * W,
                                dict(units="N", long_name="DMT pull-off 2 pi R W_c(d)"))
    ds["pull_off_force_jkr"] = ("radius", 1.5 * np.pi * radii * W,
                                dict(units="N", long_name="JKR pull-off 3/2 pi R W_c(d)"))
    ds.attrs.update(material=describe(mat), adhesion=describe(law), report="7.3, Fig. 7.6",
                    geometry="Paraboloid (shallow: half space with a paraboloidal gap)",
                    **accuracy_attrs(accuracy),
                    w_max=float(w_max),
                    sign_convention="force compressive positive; adhesion (attraction) negative")
    return ds
