"""A square lattice of rods built from numpy arrays, solved and drawn with
matplotlib (docs/python.md).

    PYTHONPATH=build/python /usr/bin/python3 examples/python/lattice.py [OUT.png] [N]

An N x N grid of square cells (N + 1 horizontal and vertical rods of 8 edges per
cell side), rigid joints at the crossings, the bottom row of joints clamped and a
downward and sideways load on the top row: the deformed lattice (colour: the
axial force) against the undeformed one.
"""
import sys

import numpy as np

import rodnet

out = sys.argv[1] if len(sys.argv) > 1 else "lattice.png"
N = int(sys.argv[2]) if len(sys.argv) > 2 else 4
a, per = 1.0, 8  # cell size, edges per cell side
net = rodnet.Network()
ends = {}  # joint (i, j) -> rod ends that meet there


def add(points, key_of_vertex):
    rod = net.add_rod(points, E=1e6, nu=0.3, radius=0.02, d1=[0, 0, 1])
    for v, key in key_of_vertex.items():
        ends.setdefault(key, []).append((rod, v))
    return rod


# each rod runs between neighbouring crossings (one cell side)
for j in range(N + 1):
    for i in range(N):
        p0, p1 = np.array([i * a, j * a, 0.0]), np.array([(i + 1) * a, j * a, 0.0])
        add(np.linspace(p0, p1, per + 1), {"start": (i, j), "end": (i + 1, j)})
for i in range(N + 1):
    for j in range(N):
        p0, p1 = np.array([i * a, j * a, 0.0]), np.array([i * a, (j + 1) * a, 0.0])
        add(np.linspace(p0, p1, per + 1), {"start": (i, j), "end": (i, j + 1)})
joint = {key: net.add_joint(e, model="rigid", name="J%d_%d" % key) for key, e in ends.items()}
for i in range(N + 1):
    net.clamp_joint(joint[(i, 0)])
    net.add_joint_force(joint[(i, N)], [2e-3, -4e-3, 0.0])
net.finalize()
print("lattice: %d rods, %d joints, %d DOFs" % (net.num_rods, net.num_joints, net.num_dofs))
x_rest = [net.positions(r) for r in range(net.num_rods)]
r = rodnet.solve(net, "tr-krylov", preconditioner="dd")
print(r)
print("  top-left joint moved by", np.round(net.joint_position(joint[(0, N)]) -
                                            np.array([0, N * a, 0]), 6))
if not r.converged:
    sys.exit("lattice.py: the solve did not converge")

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
from matplotlib.collections import LineCollection

fig, ax = plt.subplots(figsize=(6, 6))
segs, force = [], []
for k in range(net.num_rods):
    p = r.positions(k)
    f, _ = net.internal_forces(k)
    t = np.diff(p, axis=0)
    t /= np.linalg.norm(t, axis=1)[:, None]
    segs += [p[e:e + 2, :2] for e in range(len(p) - 1)]
    force += list(np.einsum("ij,ij->i", f, t))
    ax.plot(x_rest[k][:, 0], x_rest[k][:, 1], color="0.8", lw=1)
lc = LineCollection(segs, array=np.array(force), cmap="coolwarm", linewidths=2.5)
ax.add_collection(lc)
fig.colorbar(lc, ax=ax, label="axial force")
ax.set_aspect("equal")
ax.autoscale()
ax.set_title("%d x %d square lattice, rigid joints (%s, %d Newton steps)"
             % (N, N, r.solver, r.iterations))
fig.savefig(out + ".tmp.png", dpi=110)
import os

os.replace(out + ".tmp.png", out)
print("wrote", out)
