"""Effective stiffness of a square lattice cell against the strut radius
(docs/python.md, docs/homogenization.md).

    PYTHONPATH=build/python /usr/bin/python3 examples/python/homogenization_sweep.py [OUT.png]

The periodic cell of a square lattice (one rod along x to its image, one along y,
a rigid joint), built from numpy arrays and homogenised for several strut radii
r: C11 against the stretching closed form E A / a (exact for this cell: the
struts along x carry the load in pure tension), and the shear stiffness C33,
which comes from strut bending and so grows like r^4 (E I / a^3 scaling), with
the relative density.  Then the first instability under equibiaxial
compression of the thinnest cell by rodnet.homogenize(path=...): the long-wave
shear mode, at a compressive stress of about C33.
"""
import math
import sys

import numpy as np

import rodnet

E, a, edges = 1.0, 1.0, 8


def cell(r):
    c = rodnet.Network(periodic=[[a, 0, 0], [0, a, 0]])
    rx = c.add_rod(np.linspace([0, 0, 0], [a, 0, 0], edges + 1), E=E, nu=0.3, radius=r)
    ry = c.add_rod(np.linspace([0, 0, 0], [0, a, 0], edges + 1), E=E, nu=0.3, radius=r)
    c.add_joint([(rx, "start"), (rx, "end"), (ry, "start"), (ry, "end")], model="rigid",
                images=[[0, 0, 0], [1, 0, 0], [0, 0, 0], [0, 1, 0]])
    return c.finalize()


radii = [0.005, 0.01, 0.02, 0.04]
rows = []
print("%8s %10s %14s %14s %10s %14s" % ("r", "rho", "C11", "E A / a", "C12", "C33"))
for r in radii:
    h = rodnet.homogenize(cell(r))
    C = h["C"]
    ea = E * math.pi * r * r / a
    rows.append((r, h["relative_density"], C[0, 0], ea, C[0, 1], C[2, 2]))
    print("%8.3g %10.4g %14.8g %14.8g %10.3g %14.6g" % rows[-1])
    if abs(C[0, 0] / ea - 1) > 1e-9:
        sys.exit("homogenization_sweep.py: C11 differs from E A / a")
# C33 from bending: the ratio of successive radii is 2, so C33 grows by 2^4
slopes = [math.log(rows[k + 1][5] / rows[k][5], 2) for k in range(len(rows) - 1)]
print("log2 growth of C33 per doubling of r:", np.round(slopes, 3), "(bending: 4)")

h = rodnet.homogenize(cell(radii[0]), path=[-0.002, -0.002, 0], steps=10,
                      modes="in-plane", bloch_grid=8)
inst = h["instability"]
r0 = radii[0]
if inst:
    print("equibiaxial compression of r = %g: first instability at strain %.4g (%s, "
          "wave vector %s)" % (radii[0], inst["strain"][0], inst["kind"], inst["wave_vector"]))
    # In a square lattice the long-wave (macroscopic) shear mode comes before the
    # struts' Euler buckling: rank-one convexity is lost when the compressive
    # stress is about the shear stiffness C33 (the stress term of the acoustic
    # tensor against the bending-dominated shear stiffness).
    c33 = rows[0][5]
    print("  stress there %.4g = %.3f C33 (C33 = %.4g); Euler strain of a pinned strut "
          "%.4g" % (inst["stress"][0], inst["stress"][0] / c33, c33,
                    math.pi ** 2 * (r0 * r0 / 4) / a ** 2))
else:
    print("no instability on the path")

if len(sys.argv) > 1:
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    rho = [x[1] for x in rows]
    fig, ax = plt.subplots(figsize=(5, 4))
    ax.loglog(rho, [x[2] for x in rows], "o-", label="C11 (rodnet)")
    ax.loglog(rho, [x[3] for x in rows], "k:", label="E A / a")
    ax.loglog(rho, [x[5] for x in rows], "s-", label="C33 (shear)")
    ax.set_xlabel("relative density")
    ax.set_ylabel("stiffness (force per length)")
    ax.legend()
    fig.tight_layout()
    fig.savefig(sys.argv[1])
    print("wrote", sys.argv[1])
