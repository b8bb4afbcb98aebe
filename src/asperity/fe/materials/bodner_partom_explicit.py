"""Explicit integration of the Bodner-Partom law: the report's Euler predictor /
trapezoidal corrector with its error indicator and per-point adaptive sub-steps, the
reference integrator (report 3.2.2, 3.6, eqs. 3.33-3.36).

The strain goes linearly from the state's strain to the given one over dt;
components under stress control (mixed control, which the uniaxial driver
uses) instead have their stress going linearly to a given value, and their
strain rates follow from sigma_dot = C (eps_dot - eps_n_dot): with a the
strain-controlled components and b the stress-controlled ones,

    eps_dot_b = C_bb^-1 (sigma_dot_b - C_ba eps_dot_a + (C eps_n_dot)_b).

The state is stacked into one array y of Mandel components (strain, stress,
eps_n, Z^I, beta, kappa, W_p), whose rates y_dot = f(y) are the law's
(`BodnerPartom.rates`).  Each point takes its own sub-steps h: the predictor
y_P = y + h y_dot (3.34), y_dot_P = f(y_P) (3.35), and the indicator (3.36)

    E = max |h (y_dot_P - y_dot)| / (2 (|y_P| + floor))

over the stress, Z^I, beta, w (the report's control variables) and the
inelastic strain, tensors by their norms (floors and scales:
`PredictorCorrector.explicit`).  E > tol rejects the sub-step and shrinks
it; otherwise the corrector y + h (y_dot + y_dot_P) / 2 is taken, with
rupture declared where kappa reaches kappa_r (the time interpolated within
the sub-step) or the inelastic strain rate passes ``rupture_strain_rate``;
the next sub-step is h 0.9 sqrt(tol / E) within [0.2 h, 2 h].
"""

from __future__ import annotations

import math

import numpy as np

from asperity.fe.materials.bodner_partom_state import BPState, quiet_underflow
from asperity.fe.materials.tensors import to_mandel


class PredictorCorrector:
    """The explicit integrator of `BodnerPartom` (module docstring), mixed into it:
    the methods use its constants, flags and rates."""

    @quiet_underflow
    def explicit(self, strain, state: BPState, dt, *, tol: float = 1e-4, stress=None,
                 stress_mask=None, max_substeps: int = 2_000_000):
        """Euler predictor / trapezoidal corrector with error indicator (3.33-3.36).

        The strain goes linearly from ``state.strain`` to `strain` over dt;
        components where ``stress_mask`` (4,) is True instead have their
        stress going linearly to `stress` (mixed control; those strains are
        found from sigma_dot = C (eps_dot - eps_n_dot)).  Each point takes its
        own sub-steps: the predictor y_P = y + h y_dot (3.34), y_dot_P =
        f(y_P) (3.35), and the indicator (3.36)

            E = max |h (y_dot_P - y_dot)| / (2 (|y_P| + floor))

        over the stress, Z^I, beta, w (the report's control variables) and
        the inelastic strain (so that stress-controlled creep is controlled
        too), tensors by their norms; Z^I and beta are measured relative to
        the hardness |Z^I| (beta starts from 0, and what matters is its share
        of Z), eps_n relative to the total strain, the stress and the strain
        with floors of 1e-3 Z0 and 1e-3 Z0 / E, w with a floor of 1e-4.
        E > tol rejects the step and shrinks it; otherwise the corrector
        y + h (y_dot + y_dot_P) / 2 is taken; the next step is
        h 0.9 sqrt(tol / E) within [0.2 h, 2 h].  ``tol = inf`` takes one
        Heun step per call; dt = 0 is an elastic jump.  Returns
        ``(stress, new_state, info)`` with info = dict(substeps, rejected)
        per point.
        """
        ctx, d, eps1, N, shape = self._context(strain, state, dt)
        dtv = ctx["dt"]
        nc = eps1.shape[0]
        mask = np.zeros(nc, bool) if stress_mask is None else np.asarray(stress_mask, bool)
        run = _Substeps(self, mask, stress, d, eps1, dtv, N)
        iE, iS, iN, iZ, iB, iK, iW = run.rows
        ruptured = d["ruptured"].copy()
        t_r = d["rupture_time"].copy()
        t = np.zeros(N)
        h = np.where(np.isfinite(d["dt_sub"]) & (d["dt_sub"] > 0), d["dt_sub"], dtv)
        h = np.minimum(h, dtv)
        nsub = np.zeros(N, int)
        nrej = np.zeros(N, int)
        conv = np.ones(N, bool)
        todo = np.nonzero(dtv > 0)[0]
        while todo.size:
            todo = run.substep(todo, tol, max_substeps, t, h, nsub, nrej, conv, ruptured, t_r)
        Y = run.Y
        w = self.damage_from_kappa(Y[iK]) if self.damage else d["damage"]
        new_flat = dict(strain=Y[iE], stress=Y[iS], inelastic_strain=Y[iN],
                        beta=Y[iB], plastic_work=Y[iW], hardness_iso=Y[iZ],
                        kappa=Y[iK], damage=w, time=d["time"] + dtv, ruptured=ruptured,
                        rupture_time=t_r, converged=conv, iterations=nsub, dt_sub=h)
        st = BPState.from_flat(new_flat, shape)
        return st.stress, st, dict(substeps=nsub.reshape(shape), rejected=nrej.reshape(shape))


def _norms(x):
    """The Euclidean norms of the columns of x."""
    return np.sqrt(np.sum(x * x, axis=0))


class _Substeps:
    """The sub-steps of one call of `PredictorCorrector.explicit` (module docstring).

    ``Y`` is the stacked state (Mandel components), its rows ``rows`` = (eps,
    sigma, eps_n, Z^I, beta, kappa, W_p): for nc = 4 the slices 0:4, 4:8,
    8:12, the row 12, the slice 13:17 and the rows 17, 18.  The strain rates
    are constant over the call; under mixed control the stress rates of the
    components ``b`` too, and their strain rates follow from the inelastic
    rate (``G1`` + ``Cb_n`` eps_n_dot).  A point with dt = 0 jumps elastically
    to the prescribed values at once.
    """

    def __init__(self, material, mask: np.ndarray, stress, d: dict, eps1: np.ndarray,
                 dtv: np.ndarray, N: int):
        self.material, self.d, self.dtv, self.N = material, d, dtv, N
        nc = eps1.shape[0]
        C = material.elastic_mandel(nc)
        # slices of the stacked state (for nc = 4: 0:4, 4:8, 8:12, 12, 13:17, 17, 18)
        iE, iS, iN = slice(0, nc), slice(nc, 2 * nc), slice(2 * nc, 3 * nc)
        iZ, iB, iK, iW = 3 * nc, slice(3 * nc + 1, 4 * nc + 1), 4 * nc + 1, 4 * nc + 2
        a, b = ~mask, mask
        mixed = bool(b.any())
        # stacked state: eps iE, sig iS, eps_n iN, Z^I iZ, beta iB, kappa iK, W_p iW
        Y = np.concatenate([d["strain"], d["stress"], d["inelastic_strain"],
                            d["hardness_iso"][None], d["beta"], d["kappa"][None],
                            d["plastic_work"][None]])
        pos = dtv > 0
        inv_dt = np.where(pos, 1.0 / np.where(pos, dtv, 1.0), 0.0)
        rate_eps = (eps1 - Y[iE]) * inv_dt
        G1 = Cb_n = None
        if mixed:
            sig1 = to_mandel(np.asarray(stress, float).reshape(nc, N))
            rate_sig = (sig1 - Y[iS]) * inv_dt
            Cbb_inv = np.linalg.inv(C[np.ix_(b, b)])
            Cba = C[np.ix_(b, a)]
            # eps_dot_b = Cbb^-1 (sig_dot_b - Cba eps_dot_a + (C eps_n_dot)_b)
            G1 = Cbb_inv @ (rate_sig[b] - Cba @ rate_eps[a])
            Cb_n = Cbb_inv @ C[b]                      # acting on eps_n_dot
        else:
            rate_sig = None
        if not pos.all():
            # dt = 0: an instantaneous, elastic jump to the prescribed values
            z = ~pos
            e_new = eps1[:, z].copy()
            if mixed:
                s1 = sig1[:, z]
                en = Y[iN][:, z]
                e_new[b] = Cbb_inv @ (s1[b] - Cba @ e_new[a] + (C @ en)[b])
            Y[iE, z] = e_new
            Y[iS, z] = C @ (e_new - Y[iN][:, z])
        self.rows = (iE, iS, iN, iZ, iB, iK, iW)
        self.C, self.b, self.mixed, self.Y = C, b, mixed, Y
        self.rate_eps, self.rate_sig, self.G1, self.Cb_n = rate_eps, rate_sig, G1, Cb_n
        self.fs = 1e-3 * material.stress_scale
        self.fe = self.fs / material.E
        self.hard = material.isotropic_hardening or material.recovery
        self.kr = material.kappa_rupture if material.damage else math.inf

    def rates(self, Yv, re, g1, rup, idx, full):
        """(y_dot, w) at the stacked states Yv of the points idx (all if full), with
        their strain rates re (and g1 under mixed control) and rupture flags rup."""
        iE, iS, iN, iZ, iB, iK, iW = self.rows
        b, C, mixed = self.b, self.C, self.mixed
        r = self.material._rates(Yv[iS], Yv[iZ], Yv[iB], Yv[iK], rup)
        en = r["epsn"]
        if mixed:
            epsd = re.copy()
            epsd[b] = g1 + self.Cb_n @ en
            sigd = C @ (epsd - en)
        else:
            epsd = re
            sigd = C @ (re - en)
        F = np.concatenate([epsd, sigd, en, r["zi"][None], r["beta"], r["kappa"][None],
                            r["wp"][None]])
        if mixed:
            F[iS][b] = self.rate_sig[b][:, idx] if not full else self.rate_sig[b]
        return F, r["damage"]

    def indicator(self, Yt, YP, F0, FP, w0, wP, hh):
        """The error indicator (3.36) of the sub-steps hh from Yt (module docstring):
        the stress relative to its norm (floor 1e-3 Z0), eps_n to the total strain
        (floor 1e-3 Z0 / E), Z^I and beta to |Z^I|, w with a floor of 1e-4."""
        m = self.material
        iE, iS, iN, iZ, iB, iK, iW = self.rows
        fs, fe = self.fs, self.fe
        dF = hh * (FP - F0)
        E = _norms(dF[iS]) / (2.0 * (_norms(YP[iS]) + fs))
        E = np.maximum(E, _norms(dF[iN]) / (2.0 * (_norms(YP[iE]) + fe)))
        zs = 2.0 * (np.abs(YP[iZ]) + fs)
        if self.hard:
            E = np.maximum(E, np.abs(dF[iZ]) / zs)
        if m.directional_hardening:
            E = np.maximum(E, _norms(dF[iB]) / zs)
        if m.damage:
            wd0 = m._damage_rate(Yt[iK], w0, F0[iK])
            wdP = m._damage_rate(YP[iK], wP, FP[iK])
            Ew = np.abs(hh * (wdP - wd0)) / (2.0 * (np.abs(wP) + 1e-4))
            E = np.maximum(E, Ew)
        return np.where(np.isfinite(E), E, np.inf)

    def rupture(self, acc, ia, Yt, Yc, hh, t, ruptured, t_r):
        """Rupture of the accepted points ia (``acc`` of the sub-step): kappa reached
        kappa_r (the time interpolated within the sub-step; kappa capped there) or
        the inelastic strain rate passed ``rupture_strain_rate``."""
        iE, iS, iN, iZ, iB, iK, iW = self.rows
        d, kr = self.d, self.kr
        kold, knew = Yt[iK][acc], Yc[iK][acc]
        new = (knew >= kr) & ~ruptured[ia]
        with np.errstate(divide="ignore", invalid="ignore"):
            frac = np.clip((kr - kold) / (knew - kold), 0.0, 1.0)
        t_r[ia] = np.where(new, d["time"][ia] + t[ia] + frac * hh[acc], t_r[ia])
        ruptured[ia] |= new
        Yc[iK] = np.minimum(Yc[iK], kr)
        lost = self.material._runaway(Yc[iS][:, acc], Yc[iZ][acc], Yc[iB][:, acc],
                                      Yc[iK][acc]) & ~ruptured[ia]
        t_r[ia] = np.where(lost, d["time"][ia] + t[ia] + hh[acc], t_r[ia])
        ruptured[ia] |= lost

    def substep(self, todo, tol, max_substeps, t, h, nsub, nrej, conv, ruptured, t_r):
        """One sub-step of the points `todo`, tried and accepted or rejected; the
        arrays t (time reached), h (next sub-step), nsub, nrej, conv, ruptured and
        t_r are updated in place.  Returns the points still short of dt."""
        m, dtv, N, Y = self.material, self.dtv, self.N, self.Y
        iE, iS, iN, iZ, iB, iK, iW = self.rows
        kr = self.kr
        full = todo.size == N
        idx = todo
        Yt = Y if full else Y[:, todo]
        re = self.rate_eps if full else self.rate_eps[:, todo]
        g1 = (self.G1 if full else self.G1[:, todo]) if self.mixed else None
        rup = ruptured if full else ruptured[todo]
        tt = t if full else t[todo]
        rem = dtv if full else dtv[todo]
        hh = np.minimum(h if full else h[todo], rem - tt)
        F0, w0 = self.rates(Yt, re, g1, rup, idx, full)
        YP = Yt + hh * F0
        if m.damage:
            YP[iK] = np.minimum(YP[iK], kr)
        FP, wP = self.rates(YP, re, g1, rup, idx, full)
        E = self.indicator(Yt, YP, F0, FP, w0, wP, hh)
        acc = (E <= tol) | (not np.isfinite(tol))
        Yc = Yt + 0.5 * hh * (F0 + FP)
        ia = todo[acc]
        if m.damage and ia.size:
            self.rupture(acc, ia, Yt, Yc, hh, t, ruptured, t_r)
        Y[:, ia] = Yc[:, acc]
        t[ia] += hh[acc]
        nsub[ia] += 1
        nrej[todo[~acc]] += 1
        with np.errstate(divide="ignore", invalid="ignore"):
            fac = np.where(E > 0, 0.9 * np.sqrt(tol / np.where(E > 0, E, 1.0)), 2.0)
        fac = np.clip(np.where(np.isnan(fac), 2.0, fac), 0.2, 2.0)
        hold = h[todo]
        # an accepted step cut short by the end of the increment keeps h
        keep = acc & (hh < hold) & (t[todo] >= dtv[todo] * (1.0 - 1e-14))
        h[todo] = np.where(keep, hold, hh * fac)
        left = t[todo] < dtv[todo] * (1.0 - 1e-14)
        over = nsub[todo] + nrej[todo] >= max_substeps
        conv[todo[over & left]] = False
        return todo[left & ~over]
