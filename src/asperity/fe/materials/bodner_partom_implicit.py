"""The backward-Euler update of the Bodner-Partom law and its consistent tangent, the
finite element integrator (report 3.2.2, 3.6).

Given the total strain eps at the end of the increment, the state at its start
and dt, the elastic trial stress has the pressure p = K tr(eps - eps_n) and the
deviator s_tr = 2 G dev(eps - eps_n), q_tr = sqrt(3/2 s_tr : s_tr).  The flow
rule is coaxial with the trial deviator, so with dp the equivalent inelastic
strain increment the stress at the end of the step is

    sigma = (q / q_tr) s_tr + p I,   q = q_tr - 3 G dp,

and the local problem reduces to one scalar unknown y = ln(c0 / dp),
dp = c0 exp(-y), c0 = (2/sqrt3) D0 dt.  In y the flow law
p_dot = (2/sqrt3) D0 exp[-1/2 (Z_eff / q)^(2n)] inverts to
q = Z_eff (2 y)^(-1/(2n)), and the reduced residual

    R(y) = q(y) - Z_eff(y) (2 y)^(-1/(2n))

is smooth and (for fixed Z) concave increasing even for the stiff n = 5.8,
D0 = 1e8 set.  Z^I and |beta| at the end of the step solve their own
monotone scalar backward-Euler equations of (3.13) and (3.14) for each y
(nested, `BackwardEuler._inner`; closed forms for r = 1, 2), with
W_p increment dW = q dp; the damage kappa is explicit in the end stress.
All points iterate together (safeguarded Newton with bisection, masked
convergence: `BackwardEuler._solve_flow`).  The consistent tangent is

    d sigma / d eps = partial_eps sigma - partial_y sigma (partial_eps R / partial_y R)

on the reduced residual R(y, eps), the partial derivatives by complex-step
differentiation (exact to rounding; W. Squire and G. Trapp, SIAM Rev. 40
(1998) 110).
"""

from __future__ import annotations

import numpy as np

from asperity.fe.materials.bodner_partom_state import BPState, quiet_underflow
from asperity.fe.materials.tensors import (from_mandel, identity_like, mandel_dot, signed_power,
                                           tangent_from_mandel)


class BackwardEuler:
    """The backward-Euler update of `BodnerPartom` (module docstring), mixed into
    it: the methods use its constants, flags and rates."""

    def _trial(self, eps, ctx):
        ee = eps - ctx["epsn"]
        tr = ee[0] + ee[1] + ee[2]
        p = self.K * tr
        s_tr = 2.0 * self.G * (ee - tr / 3.0 * identity_like(ee))
        q_tr = np.sqrt(1.5 * mandel_dot(s_tr, s_tr))
        return p, s_tr, q_tr

    def _stress_of(self, y, eps, ctx):
        p, s_tr, q_tr = self._trial(eps, ctx)
        dp = ctx["c0"] * np.exp(-y)
        q = q_tr - 3.0 * self.G * dp
        ok = np.real(q_tr) > 0
        ratio = np.where(ok, q / np.where(ok, q_tr, 1.0), 1.0)
        sig = s_tr * ratio + p * identity_like(s_tr)
        return sig, q, dp, s_tr, q_tr

    def _direction(self, sig):
        nrm = np.sqrt(mandel_dot(sig, sig))
        ok = np.real(nrm) > 0
        return np.where(ok, sig / np.where(ok, nrm, 1.0), 0.0)

    def _inner(self, dW, u, ctx, tol=1e-14, maxit=60):
        """Z^I, |beta|, c and b at the end of the step for given dW and u.

        Backward Euler of (3.13) and of the beta equation: with
        b = beta_n + m2 Z3 dW u, beta = b / c, c = 1 + m2 dW + A2 dt
        Z1^(1 - r2) |beta|^(r2 - 1), so |beta| solves the scalar
        |beta| (1 + m2 dW) + A2 dt Z1^(1-r2) |beta|^r2 = |b|.  Closed forms
        for r = 1, 2; otherwise safeguarded Newton on the real parts and one
        complex Newton correction (exact complex-step derivatives).
        """
        cplx = np.iscomplexobj(dW) or (u is not None and np.iscomplexobj(u))
        dt = ctx["dt"]
        if self.isotropic_hardening:
            a = 1.0 + self.m1 * dW
            rhs = ctx["zi"] + self.m1 * self.Z1 * dW
        else:
            a = 1.0 + 0.0 * dW
            rhs = ctx["zi"] + 0.0 * dW
        zstar = rhs / a
        if self.recovery and self.A1 > 0:
            k = dt * self.A1 * self.Z1
            z1, z2, r1 = self.Z1, self.Z2, self.r1
            d = zstar - z2
            if r1 == 2.0:
                sd = np.sign(np.real(d))
                zi = z2 + 2.0 * d / (1.0 + np.sqrt(1.0 + 4.0 * k / z1**2 * (sd * d) / a))
            elif r1 == 1.0:
                zi = z2 + a * d / (a + k / z1)
            else:
                def fz(z, a=a, rhs=rhs):
                    x = (z - z2) / z1
                    s = np.sign(np.real(x))
                    return (a * z - rhs + k * signed_power(x, r1),
                            a + k * r1 * (s * x) ** (r1 - 1.0) / z1)

                ar, rr, zr = np.real(a), np.real(rhs), np.real(zstar)
                zi = _safe_newton(lambda z: fz(z, ar, rr), np.minimum(zr, z2),
                                  np.maximum(zr, z2), zr, tol * self.Z0, maxit)
                if cplx:
                    f, df = fz(zi.astype(complex))
                    zi = zi - f / df
        else:
            zi = zstar
        if not self.directional_hardening:
            return zi, 0.0 * dW, None, None
        b = ctx["beta"] + self.m2 * self.Z3 * dW * u
        bb = np.sqrt(mandel_dot(b, b))
        c1 = 1.0 + self.m2 * dW
        if self.recovery and self.A2 > 0:
            k2 = self.A2 * dt * self.Z1 ** (1.0 - self.r2)
            r2 = self.r2
            if r2 == 2.0:
                bn = 2.0 * bb / (c1 + np.sqrt(c1 * c1 + 4.0 * k2 * bb))
            elif r2 == 1.0:
                bn = bb / (c1 + k2)
            else:
                def fb(x, c1=c1, bb=bb):
                    return x * c1 + k2 * x**r2 - bb, c1 + k2 * r2 * x ** (r2 - 1.0)

                c1r, bbr = np.real(c1), np.real(bb)
                hi = bbr / c1r
                bn = _safe_newton(lambda x: fb(x, c1r, bbr), np.zeros_like(hi), hi, hi,
                                  tol * self.Z0, maxit)
                if cplx:
                    f, df = fb(bn.astype(complex))
                    bn = bn - f / df
            c = c1 + k2 * bn ** (r2 - 1.0)
        else:
            bn = bb / c1
            c = c1
        return zi, bn, c, b

    def _flow(self, y, eps, ctx):
        """Reduced flow residual R(y) = q - Z_eff (2 y)^(-1/(2n)) with the inner
        variables solved; complex-step safe.  Returns (R, sig, extras)."""
        sig, q, dp, s_tr, q_tr = self._stress_of(y, eps, ctx)
        dW = q * dp
        u = self._direction(sig) if self.directional_hardening else None
        zi, bn, c, b = self._inner(dW, u, ctx)
        Z = zi
        if self.directional_hardening:
            Z = Z + (mandel_dot(ctx["beta"], u) + self.m2 * self.Z3 * dW) / c
        kraw = None
        if self.damage:
            kraw = ctx["kappa"] + ctx["dt"] * self.kappa_rate(sig) * (~ctx["ruptured"])
            kr = self.kappa_rupture
            kap = np.where(np.real(kraw) > kr, kr, kraw)
            Z = Z * self._softening(self.damage_from_kappa(kap))
        g = (2.0 * y) ** (-0.5 / self.n)
        R = q - Z * g
        return R, sig, dict(q=q, dp=dp, s_tr=s_tr, q_tr=q_tr, dW=dW, zi=zi, bn=bn, c=c, b=b,
                            kraw=kraw, Zeff=Z)

    def _reduced(self, y, eps, ctx):
        """R(y) and dR/dy (total, inner variables following) by one complex step."""
        hy = 1e-20 * (1.0 + np.abs(y))
        R, _, _ = self._flow(y + 1j * hy, eps, ctx)
        return np.real(R), np.imag(R) / hy

    @quiet_underflow
    def update(self, strain, state: BPState, dt, *, tol: float = 1e-12, maxit: int = 80,
               tangent: bool = True):
        """Backward-Euler stress update.

        strain: total strain (4, *shape) (or (6, *shape) in 3-D, with a
        state of as many components) at the end of the increment; state:
        at its start; dt [s] (scalar or per point).  Returns
        ``(stress (n, *shape), tangent (n, n, *shape) or None, new_state)``;
        ``new_state.converged`` flags the points whose local Newton converged
        (``iterations`` counts its iterations).
        """
        ctx, d, eps, N, shape = self._context(strain, state, dt)
        p, s_tr, q_tr = self._trial(eps, ctx)
        active = (q_tr > 1e-14 * self.stress_scale) & (ctx["dt"] > 0)
        y = np.full(N, np.inf)
        conv = np.ones(N, bool)
        iters = np.zeros(N, int)
        ia = np.nonzero(active)[0]
        if ia.size:
            ya, ca, ita = self._solve_flow(eps[:, ia], _take(ctx, ia), q_tr[ia], tol, maxit)
            y[ia], conv[ia], iters[ia] = ya, ca, ita
        with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
            _, sig, x = self._flow(y, eps, ctx)
        dp, dW = x["dp"], x["dW"]
        nrm_s = np.where(q_tr > 0, 1.5 / np.where(q_tr > 0, q_tr, 1.0), 0.0)
        epsn = ctx["epsn"] + dp * nrm_s * s_tr
        if self.directional_hardening:
            beta = x["b"] / x["c"]
        else:
            beta = ctx["beta"]
        kappa, w = ctx["kappa"], d["damage"]
        ruptured, t_r = d["ruptured"].copy(), d["rupture_time"].copy()
        if self.damage:
            kraw = x["kraw"]
            kr = self.kappa_rupture
            new = (kraw >= kr) & ~ruptured
            with np.errstate(divide="ignore", invalid="ignore"):
                frac = np.clip((kr - ctx["kappa"]) / (kraw - ctx["kappa"]), 0.0, 1.0)
            t_r = np.where(new, d["time"] + frac * ctx["dt"], t_r)
            ruptured = ruptured | new
            # creep runaway: the inelastic strain rate passes rupture_strain_rate
            with np.errstate(divide="ignore", invalid="ignore"):
                lost = (dp >= self.rupture_strain_rate * ctx["dt"]) & (ctx["dt"] > 0) & ~ruptured
            t_r = np.where(lost, d["time"] + ctx["dt"], t_r)
            ruptured = ruptured | lost
            kappa = np.minimum(kraw, kr)
            w = self.damage_from_kappa(kappa)
        new_flat = dict(strain=eps, stress=sig, inelastic_strain=epsn, beta=beta,
                        plastic_work=d["plastic_work"] + dW, hardness_iso=x["zi"], kappa=kappa,
                        damage=w, time=d["time"] + ctx["dt"], ruptured=ruptured,
                        rupture_time=t_r, converged=conv, iterations=iters, dt_sub=d["dt_sub"])
        new_state = BPState.from_flat(new_flat, shape)
        nc = eps.shape[0]
        stress = from_mandel(sig).reshape((nc,) + shape)
        if not tangent:
            return stress, None, new_state
        C = self.elastic_mandel(nc)
        D = np.broadcast_to(C[:, :, None], (nc, nc, N)).copy()
        ip = np.nonzero(active & (dp > 0))[0]
        if ip.size:
            D[:, :, ip] = self._consistent(y[ip], eps[:, ip], _take(ctx, ip))
        D = tangent_from_mandel(D).reshape((nc, nc) + shape)
        return stress, D, new_state

    def _consistent(self, y, eps, ctx):
        """Consistent tangent (Mandel, (nc, nc, n)) at converged plastic points:
        d sigma / d eps = partial_eps sigma + partial_y sigma (x) d y / d eps,
        d y / d eps = -partial_eps R / partial_y R (R the reduced residual)."""
        n = y.shape[0]
        nc = eps.shape[0]
        with np.errstate(all="ignore"):
            hy = 1e-20 * (1.0 + np.abs(y))
            R, s, _ = self._flow(y + 1j * hy, eps, ctx)
            R_y = np.imag(R) / hy
            sig_y = np.imag(s) / hy
            R_e = np.empty((nc, n))
            sig_e = np.empty((nc, nc, n))
            he = 1e-20 * np.maximum(np.max(np.abs(eps), axis=0), 1e-3)
            for j in range(nc):
                e = eps.astype(complex)
                e[j] = e[j] + 1j * he
                R, s, _ = self._flow(y.astype(complex), e, ctx)
                R_e[j] = np.imag(R) / he
                sig_e[:, j] = np.imag(s) / he
        good = np.isfinite(R_y) & (R_y != 0)
        dy_de = np.where(good, -R_e / np.where(good, R_y, 1.0), 0.0)      # (nc, n)
        return sig_e + sig_y[:, None, :] * dy_de[None, :, :]

    def _solve_flow(self, eps, ctx, q_tr, tol, maxit):
        """Safeguarded Newton on y for the active points (vectorized, masked).

        R(y) is increasing, R -> -inf (or < 0) at the lower end of the domain
        y_dom (q = 0 or y = 0) and R -> q_tr > 0 as y -> inf; for fixed Z it
        is concave, so Newton from the left converges monotonically.  Steps
        leaving the bracket are replaced by bisection (or expansion).
        """
        n = q_tr.shape[0]
        c0 = ctx["c0"]
        G3 = 3.0 * self.G
        with np.errstate(divide="ignore"):
            ydom = np.maximum(np.log(G3 * c0 / q_tr), 0.0)
        # initial guess: flow at the trial stress with the old hardness (left of the root)
        Zest = ctx["zi"].copy()
        if self.directional_hardening:
            p, s_tr, _ = self._trial(eps, ctx)
            Zest = Zest + mandel_dot(ctx["beta"], self._direction(s_tr + p * identity_like(s_tr)))
        if self.damage:
            Zest = Zest * self._softening(self.damage_from_kappa(ctx["kappa"]))
        Zest = np.maximum(Zest, 1e-6 * self.stress_scale)
        with np.errstate(over="ignore", divide="ignore", invalid="ignore"):
            y0 = np.minimum(0.5 * (Zest / q_tr) ** (2.0 * self.n), 1e300)
            # better: the flow rate at the start of the step (small steps)
            sn = ctx["stress"]
            trn = sn[0] + sn[1] + sn[2]
            dn = sn - trn / 3.0 * identity_like(sn)
            qn = np.sqrt(1.5 * mandel_dot(dn, dn))
            Zn = ctx["zi"].copy()
            if self.directional_hardening:
                Zn = Zn + mandel_dot(ctx["beta"], self._direction(sn))
            if self.damage:
                Zn = Zn * self._softening(self.damage_from_kappa(ctx["kappa"]))
            yn = 0.5 * (np.maximum(Zn, 1e-6 * self.stress_scale) / qn) ** (2.0 * self.n)
        yd = ydom + np.maximum(1e-9 * ydom, 1e-12)
        y = np.where(np.isfinite(yn) & (yn > yd) & (qn > 0), yn, np.maximum(y0, yd))
        lo = ydom.copy()
        hi = np.full(n, np.inf)
        conv = np.zeros(n, bool)
        iters = np.zeros(n, int)
        todo = np.arange(n)
        for _ in range(maxit):
            c = _take(ctx, todo) if todo.size < n else ctx
            yt = y[todo]
            with np.errstate(all="ignore"):
                R, dR = self._reduced(yt, eps[:, todo], c)
            neg = R < 0
            l = np.where(neg, np.maximum(lo[todo], yt), lo[todo])
            hh = np.where(~neg, np.minimum(hi[todo], yt), hi[todo])
            lo[todo], hi[todo] = l, hh
            iters[todo] += 1
            done = (np.abs(R) <= tol * q_tr[todo]) | (hh - l <= 1e-15 * yt)
            conv[todo[done]] = True
            with np.errstate(all="ignore"):
                ynew = yt - R / dR
            bad = ~np.isfinite(ynew) | (ynew <= l) | (ynew >= hh) | ~(dR > 0)
            # a good Newton step this small leaves a residual ~ its square: done
            small = ~bad & (np.abs(ynew - yt) <= 1e-7 * np.abs(yt))
            conv[todo[small]] = True
            bis = np.where(np.isfinite(hh), 0.5 * (l + hh), 2.0 * yt + 1.0)
            y[todo] = np.where(done, yt, np.where(bad, bis, ynew))
            done = done | small
            todo = todo[~done]
            if todo.size == 0:
                break
        return y, conv, iters


def _take(d: dict, idx) -> dict:
    return {k: (v[..., idx] if isinstance(v, np.ndarray) and v.ndim else v) for k, v in d.items()}


def _safe_newton(fun, lo, hi, x0, atol, maxit):
    """Vectorized Newton for an increasing f with f(lo) <= 0 <= f(hi).

    `fun` is elementwise (returns f, f' at all points); Newton steps that
    leave the bracket are replaced by bisection; masked convergence.
    """
    x = np.array(x0, float, copy=True)
    lo = np.array(lo, float, copy=True)
    hi = np.array(hi, float, copy=True)
    x = np.clip(x, lo, hi)
    todo = np.nonzero(hi > lo)[0]
    for _ in range(maxit):
        if todo.size == 0:
            break
        f, df = fun(x)
        f, df = f[todo], df[todo]
        xt = x[todo]
        neg = f < 0
        lo[todo] = np.where(neg, xt, lo[todo])
        hi[todo] = np.where(neg, hi[todo], xt)
        with np.errstate(all="ignore"):
            xn = xt - f / df
        bad = ~np.isfinite(xn) | (xn < lo[todo]) | (xn > hi[todo])
        xn = np.where(bad, 0.5 * (lo[todo] + hi[todo]), xn)
        done = (np.abs(xn - xt) <= atol) | (f == 0) | (hi[todo] - lo[todo] <= atol)
        x[todo] = xn
        todo = todo[~done]
    return x
