#!/usr/bin/env python3
"""Reference limit loads of a pinned shallow circular arch under a central point
load (tests/validation/val_path.c, arch cases; docs/path-following.md).

The arch: span L, rise h (a circular arc of radius R = (h^2 + L^2/4) / (2 h)),
pinned ends, bending stiffness EI and axial stiffness EA, a downward point load
P at the crown.  The reference is the *extensible* planar elastica (the
continuum limit of rodnet's discrete rod: curvature per rest length, bending
and stretching uncoupled, no shear), computed by shooting on the half arch:
s in [0, S] is the rest arclength from the crown to the right support
(S = R alpha, sin alpha = L / (2 R)); theta the tangent angle, rest curvature
-1/R; the internal force is constant, n = (-H, P/2) (thrust H, half the load
by symmetry), and

    x' = (1 + e) cos(theta),  y' = (1 + e) sin(theta),  e = n . t / EA,
    theta' = -1/R + m / EI,   m' = -(x' P/2 + y' H),

with x = y = theta = 0 and m = m0 at the crown (symmetry).  The crown
deflection delta is prescribed: the unknowns (H, m0, P) solve m(S) = 0 (pin),
x(S) = L/2, y(S) = delta - h by Newton (Jacobian by central differences of the
shooting).  Only symmetric states are traced.  The path P(delta) is followed
from delta = 0 past both limit points; the largest load (upper limit point) and
the smallest (lower limit point) are found by shrinking brackets of the
sampled path.  Integration: classical RK4 with N0, 2 N0 and 4 N0 steps on the
half arch (N0 = 200 by default): the observed order (about 4) and the change
between the last two bound the integration error.

Cross-check (model error stated in the output): shallow-arch (Marguerre)
theory, w(x) = sum of the odd sine modes (the symmetric ones), constant thrust
N = EA / (2 L) int (w0'^2 - w'^2) dx, each mode EI k^4 (a - b) - N k^2 a =
-(2 P / L) sin(k L / 2), solved with the crown deflection prescribed.  Its
error against the elastica is of relative order (h / L)^2.

Usage: arch_elastica.py [L h EI EA [N0]]   (default: 1 0.03 1 1e4 200, the
scene problems/scenes/path/shallow_arch.json; about 15 min of one core on a
loaded machine, numpy only)."""
import sys

import numpy as np


def shoot(H, m0, P, R, S, EI, EA, N):
    """Integrates the half arch; returns x(S), y(S), m(S) (arrays like H)."""
    x = np.zeros_like(H)
    y = np.zeros_like(H)
    th = np.zeros_like(H)
    m = np.array(m0, dtype=float)
    V = 0.5 * P
    ds = S / N

    def f(x, y, th, m):
        c, s = np.cos(th), np.sin(th)
        e = (-H * c + V * s) / EA
        xp = (1 + e) * c
        yp = (1 + e) * s
        return xp, yp, -1.0 / R + m / EI, -(xp * V + yp * H)

    for _ in range(N):
        k1 = f(x, y, th, m)
        k2 = f(*(u + 0.5 * ds * k for u, k in zip((x, y, th, m), k1)))
        k3 = f(*(u + 0.5 * ds * k for u, k in zip((x, y, th, m), k2)))
        k4 = f(*(u + ds * k for u, k in zip((x, y, th, m), k3)))
        x, y, th, m = (u + ds / 6 * (a + 2 * b + 2 * c + d)
                       for u, a, b, c, d in zip((x, y, th, m), k1, k2, k3, k4))
    return x, y, m


class Arch:
    def __init__(self, L, h, EI, EA):
        self.L, self.h, self.EI, self.EA = L, h, EI, EA
        self.R = (h * h + 0.25 * L * L) / (2 * h)
        self.S = self.R * np.arcsin(0.5 * L / self.R)

    def residual(self, u, delta, N):
        """u: (3, B) unknowns (H, m0, P); delta: (B,)."""
        x, y, m = shoot(u[0], u[1], u[2], self.R, self.S, self.EI, self.EA, N)
        return np.array([m / self.EI * self.L, (x - 0.5 * self.L) / self.L,
                         (y - (delta - self.h)) / self.L])

    def solve(self, u, delta, N, tol=1e-13):
        """Newton on all the columns of u at once (each with its delta)."""
        u = np.array(u, dtype=float)
        B = u.shape[1]
        scale = np.array([self.EI / self.L, self.EI / self.L, self.EI / self.L**2])
        for it in range(30):
            hs = 1e-6 * scale
            cols = [u]
            for j in range(3):
                for sg in (1, -1):
                    v = u.copy()
                    v[j] += sg * hs[j]
                    cols.append(v)
            big = np.concatenate(cols, axis=1)
            r = self.residual(big, np.tile(delta, 7), N).reshape(3, 7, B)
            r0 = r[:, 0]
            J = np.empty((B, 3, 3))
            for j in range(3):
                J[:, :, j] = ((r[:, 1 + 2 * j] - r[:, 2 + 2 * j]) / (2 * hs[j])).T
            du = np.linalg.solve(J, -r0.T[..., None])[..., 0].T
            u = u + du
            if np.all(np.abs(du) <= tol * scale[:, None] * (1 + np.abs(u) / scale[:, None])):
                break
        r0 = self.residual(u, delta, N)
        if np.max(np.abs(r0)) > 1e-11:
            raise RuntimeError("shooting did not converge: residual %g" % np.max(np.abs(r0)))
        return u

    def path(self, N, dmax, steps):
        """Continuation in delta from 0 to dmax: (deltas, unknowns)."""
        ds = np.linspace(0, dmax, steps + 1)
        us = np.zeros((3, steps + 1))
        u = np.zeros((3, 1))
        for i, d in enumerate(ds):
            if i >= 2:
                u = (2 * us[:, i - 1] - us[:, i - 2])[:, None]
            u = self.solve(u, np.array([d]), N)
            us[:, i] = u[:, 0]
        return ds, us

    def extremum(self, ds, us, i, N, sign, rounds=7, width=21):
        """Refines the extremum of sign*P near sample i: brackets shrunk by 10 per
        round, each sampled and solved at once (guesses interpolated)."""
        lo, hi = ds[max(i - 1, 0)], ds[min(i + 1, len(ds) - 1)]
        for _ in range(rounds):
            d = np.linspace(lo, hi, width)
            guess = np.array([np.interp(d, ds, us[k]) for k in range(3)])
            u = self.solve(guess, d, N)
            ds = np.concatenate([ds, d])
            us = np.concatenate([us, u], axis=1)
            order = np.argsort(ds)
            ds, us = ds[order], us[:, order]
            j = int(np.argmax(sign * u[2]))
            step = (hi - lo) / (width - 1)
            lo, hi = d[j] - step, d[j] + step
        return d[j], u[:, j]


def shallow(L, h, EI, EA, delta, modes=2001):
    """Shallow-arch theory with the crown deflection prescribed: (P, N)."""
    R = (h * h + 0.25 * L * L) / (2 * h)
    n = np.arange(1, modes + 1, 2).astype(float)
    k = n * np.pi / L
    # Fourier sine coefficients of the circular rest shape (Gauss-Legendre)
    xg, wg = np.polynomial.legendre.leggauss(4000)
    x = 0.5 * L * (xg + 1)
    w0 = np.sqrt(R * R - (x - 0.5 * L) ** 2) - (R - h)
    b = np.array([2 / L * np.sum(0.5 * L * wg * w0 * np.sin(kk * x)) for kk in k])
    sn = np.sin(n * np.pi / 2)
    out = []
    Nth, P = 0.0, 0.0
    for d in delta:
        for _ in range(100):  # Newton on (N, P)
            def res(Nth, P):
                a = (EI * k**4 * b - 2 * P / L * sn) / (EI * k**4 - Nth * k**2)
                r1 = Nth - EA / 4 * np.sum(k**2 * (b * b - a * a))
                r2 = np.sum((b - a) * sn) - d
                return np.array([r1, r2])
            r = res(Nth, P)
            e1, e2 = 1e-7 * EI / L**2, 1e-7 * EI / L**2
            J = np.column_stack([(res(Nth + e1, P) - res(Nth - e1, P)) / (2 * e1),
                                 (res(Nth, P + e2) - res(Nth, P - e2)) / (2 * e2)])
            dx = np.linalg.solve(J, -r)
            Nth, P = Nth + dx[0], P + dx[1]
            if np.max(np.abs(dx)) < 1e-13 * (1 + abs(Nth) + abs(P)):
                break
        out.append((P, Nth))
    return np.array(out)


def main():
    a = [float(v) for v in sys.argv[1:5]] if len(sys.argv) >= 5 else [1.0, 0.03, 1.0, 1e4]
    L, h, EI, EA = a
    n0 = int(sys.argv[5]) if len(sys.argv) >= 6 else 200
    steps = (n0, 2 * n0, 4 * n0)
    arch = Arch(L, h, EI, EA)
    r = np.sqrt(EI / EA)
    print("pinned circular arch: L %g, h %g (h/L %.4g), EI %g, EA %g, radius of gyration "
          "r = %.6g, rise parameter h/r = %.4f" % (L, h, h / L, EI, EA, r, h / r))
    res = {}
    for N in steps:
        ds, us = arch.path(N, 2.2 * h, 110)
        P = us[2]
        imax = next(i for i in range(1, len(P) - 1) if P[i + 1] < P[i])  # first maximum
        imin = next(i for i in range(imax + 1, len(P) - 1) if P[i + 1] > P[i])
        dmax, umax = arch.extremum(ds, us, imax, N, +1)
        dmin, umin = arch.extremum(ds, us, imin, N, -1)
        res[N] = (umax[2], dmax, umax[0], umin[2], dmin, umin[0])
        print("RK4 N = %4d: upper limit P = %.12f at delta = %.8f (thrust %.8f); lower "
              "limit P = %.12f at delta = %.8f (thrust %.8f)" % ((N,) + res[N]))
    p = [res[N][0] for N in steps]
    q = [res[N][3] for N in steps]
    for name, v in (("upper", p), ("lower", q)):
        order = np.log2(abs(v[1] - v[0]) / max(abs(v[2] - v[1]), 1e-300))
        print("  %s limit: change %.2e then %.2e (order %.2f): integration error below "
              "%.1e" % (name, v[1] - v[0], v[2] - v[1], order, abs(v[2] - v[1])))
    Pmax, dmax, Hmax, Pmin, dmin, Hmin = res[steps[2]]
    PE2 = 4 * np.pi**2 * EI / L**2
    print("reference (extensible elastica): P_upper = %.10f  P_lower = %.10f  (EI/L^2 units "
          "%.10f, %.10f)" % (Pmax, Pmin, Pmax * L**2 / EI, Pmin * L**2 / EI))
    print("thrust at the upper limit %.6f = %.4f of the antisymmetric (n = 2) buckling "
          "thrust 4 pi^2 EI / L^2 of shallow theory" % (Hmax, Hmax / PE2))
    # shallow-arch cross-check
    dd = np.linspace(0, 2.2 * h, 221)
    sp = shallow(L, h, EI, EA, dd)
    i = int(np.argmax(sp[:110, 0]))
    lo, hi = dd[i - 1], dd[i + 1]
    for _ in range(6):
        d = np.linspace(lo, hi, 21)
        v = shallow(L, h, EI, EA, d)
        j = int(np.argmax(v[:, 0]))
        st = (hi - lo) / 20
        lo, hi = d[j] - st, d[j] + st
    Ps = v[j, 0]
    print("shallow-arch theory (Marguerre, symmetric modes): P_upper = %.8f at delta %.6f, "
          "relative difference to the elastica %.3e ((h/L)^2 = %.1e)"
          % (Ps, d[j], Ps / Pmax - 1, (h / L) ** 2))


if __name__ == "__main__":
    main()
