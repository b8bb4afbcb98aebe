"""The state of Bodner-Partom material points (report 3.2.2), as both integrators of
`asperity.fe.materials.bodner_partom` read and write it.

Per point: the strain, stress, inelastic strain eps_n and directional
hardness beta (tensor components, ``(n, *shape)``, n = 4 or 6), the plastic
work W_p, the isotropic hardness Z^I, the rescaled damage kappa =
[ln(1/w)]^(-1/p) that is integrated and the damage w = exp(-kappa^(-p)), the
time, whether and when the point ruptured, and what the last local solve
did (converged, iterations, the explicit integrator's last sub-step).  The
integrators work on flat Mandel arrays (`BPState.flat`, `BPState.from_flat`;
`asperity.fe.materials.tensors`).
"""

from __future__ import annotations

from dataclasses import dataclass, fields

import numpy as np

from asperity.fe.materials.tensors import from_mandel, to_mandel


@dataclass
class BPState:
    """State of Bodner-Partom material points (arrays over the point shape).

    Vectors are (4, *shape) (or (6, *shape) in 3-D) tensor components;
    scalars (*shape).
    ``kappa`` = [ln(1/w)]^(-1/p) is the rescaled damage that is integrated,
    ``damage`` = w.  ``converged`` and ``iterations`` describe the last local
    solve, ``dt_sub`` the last explicit sub-step (reused by the next call).
    """

    strain: np.ndarray
    stress: np.ndarray
    inelastic_strain: np.ndarray
    beta: np.ndarray
    plastic_work: np.ndarray
    hardness_iso: np.ndarray
    kappa: np.ndarray
    damage: np.ndarray
    time: np.ndarray
    ruptured: np.ndarray
    rupture_time: np.ndarray
    converged: np.ndarray
    iterations: np.ndarray
    dt_sub: np.ndarray

    @property
    def shape(self) -> tuple:
        return self.plastic_work.shape

    @property
    def components(self) -> int:
        """Number of tensor components of the vectors (4 or 6)."""
        return int(np.shape(self.strain)[0])

    @property
    def hardness_dir(self) -> np.ndarray:
        """Z^D = beta : u with u = sigma / |sigma| (0 at zero stress)."""
        s = to_mandel(self.stress)
        b = to_mandel(self.beta)
        nrm = np.sqrt(np.sum(s * s, axis=0))
        with np.errstate(invalid="ignore", divide="ignore"):
            zd = np.sum(b * s, axis=0) / nrm
        return np.where(nrm > 0, zd, 0.0)

    @property
    def hardness(self) -> np.ndarray:
        """Z = Z^I + Z^D [Pa]."""
        return self.hardness_iso + self.hardness_dir

    def copy(self) -> "BPState":
        return BPState(**{f.name: np.array(getattr(self, f.name), copy=True) for f in fields(self)})

    def flat(self) -> dict:
        """Flattened Mandel arrays (internal)."""
        N = max(int(np.prod(self.shape)), 1)
        out = {}
        for f in fields(self):
            v = np.asarray(getattr(self, f.name))
            if f.name in _VECTOR_FIELDS:
                v = to_mandel(v.reshape(v.shape[0], N))
            else:
                v = v.reshape(N)
            out[f.name] = v
        return out

    @classmethod
    def from_flat(cls, d: dict, shape: tuple) -> "BPState":
        kw = {}
        for f in fields(cls):
            v = d[f.name]
            if f.name in _VECTOR_FIELDS:
                kw[f.name] = from_mandel(v).reshape((v.shape[0],) + shape)
            else:
                kw[f.name] = np.asarray(v).reshape(shape)
        return cls(**kw)


_VECTOR_FIELDS = ("strain", "stress", "inelastic_strain", "beta")


def quiet_underflow(fn):
    """Run fn with floating-point underflow ignored (it is benign here: tiny
    flow rates and damage round to 0); other numpy errors keep their setting."""
    import functools

    @functools.wraps(fn)
    def wrapper(*args, **kwargs):
        with np.errstate(under="ignore"):
            return fn(*args, **kwargs)

    return wrapper
