#!/usr/bin/env python3
"""Check the mechanical fields of a .vtu written by rodnet, read back with VTK's
own reader (python3-vtk9).

    check_vtu_fields.py OUT.vtu --result RESULT.json
                        [--tip-force FX FY FZ] [--end-moment MX MY MZ]

Always (every rod; joints, the last points and cells, are skipped):
  - point and cell counts equal the result's vertices and edges (+ joints);
    every field is present with its component count and finite;
  - bending_moment >= 0, equal to |bending_moment_vector|, and 0 (like
    twisting_moment) at rod ends;
  - energy_density >= 0 and sum(energy_density * rest_length) equals the
    result's stretching + bending + twisting energy (is at most that with
    joints, whose energy the rods' cells do not hold);
  - axial_force has the sign of stretch; the cell twist is the mean of the
    point twist_rate of the edge's interior end vertices.
Equilibrium of a solved single rod (rod 0), exact for the discrete rod: a rigid
rotation of the part beyond interior vertex i about x_i changes only the turning
angle phi_i there, and dE_i/dphi_i = |M_i| (1 + |kb_i|^2 / 4) with
|kb_i| = 2 tan(phi_i / 2).  So at equilibrium, for a planar rod,
  --tip-force F  (dead force F on the last vertex, nothing else loaded):
      M_i (1 + |kb_i|^2 / 4) = (x_last - x_i) x F   (vector, every interior i);
  --end-moment C (dead couple C on the last edge, nothing else loaded):
      M_i (1 + |kb_i|^2 / 4) = C.
Both hold up to the solver's convergence (relative gradient 1e-9): the test
allows 1e-9 relative to max |M|.  |kb_i| = |curvature_i| times the current
Voronoi length (the writer divides by it).  Exits non-zero on the first failure.
"""
import argparse
import json
import math
import sys

import numpy as np
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkIOXML import vtkXMLUnstructuredGridReader

POINT_FIELDS = {"displacement": 3, "curvature": 2, "twist_rate": 1, "bending_moment": 1,
                "bending_moment_vector": 3, "twisting_moment": 1}
CELL_FIELDS = {"rod": 1, "edge": 1, "theta": 1, "stretch": 1, "d1": 3, "d2": 3,
               "twist": 1, "axial_force": 1, "rest_length": 1, "energy_density": 1}
EQUILIBRIUM_RTOL = 1e-9


def fail(msg):
    print("check_vtu_fields: FAILED: " + msg)
    sys.exit(1)


def field(data, name, count, ncomp):
    arr = data.GetArray(name)
    if arr is None:
        fail("array '%s' missing" % name)
    a = vtk_to_numpy(arr).astype(float).reshape(count, ncomp)
    if not np.all(np.isfinite(a)):
        fail("array '%s' has non-finite values" % name)
    return a[:, 0] if ncomp == 1 else a


def read(path, result):
    reader = vtkXMLUnstructuredGridReader()
    reader.SetFileName(path)
    reader.Update()
    if reader.GetErrorCode() != 0:
        fail("reader error code %d" % reader.GetErrorCode())
    grid = reader.GetOutput()
    nv = [len(r["vertices"]) for r in result["rods"]]
    nj = len(result.get("joints", []))
    n, m = grid.GetNumberOfPoints(), grid.GetNumberOfCells()
    if n != sum(nv) + nj or m != sum(nv) - len(nv) + nj:
        fail("%d points, %d cells; expected %d, %d (rods, then %d joints)"
             % (n, m, sum(nv) + nj, sum(nv) - len(nv) + nj, nj))
    # rod vertices and edges come first, then one point and cell per joint
    f = {k: field(grid.GetPointData(), k, n, c)[:n - nj] for k, c in POINT_FIELDS.items()}
    f.update({k: field(grid.GetCellData(), k, m, c)[:m - nj]
              for k, c in CELL_FIELDS.items()})
    f["points"] = vtk_to_numpy(grid.GetPoints().GetData()).astype(float)[:n - nj]
    return f, nv, nj


def rod_slices(nv):
    p = c = 0
    for k in nv:
        yield slice(p, p + k), slice(c, c + k - 1)
        p += k
        c += k - 1


def check_general(f, nv, nj, result):
    M, Mv = f["bending_moment"], f["bending_moment_vector"]
    if M.min() < 0:
        fail("negative bending moment %g" % M.min())
    scale = max(M.max(), 1e-300)
    err = np.abs(M - np.linalg.norm(Mv, axis=1)).max()
    if err > 1e-12 * scale:
        fail("bending_moment differs from |bending_moment_vector| by %g" % err)
    for ps, cs in rod_slices(nv):
        ends = [ps.start, ps.stop - 1]
        if np.any(M[ends] != 0) or np.any(f["twisting_moment"][ends] != 0):
            fail("moments not zero at the ends of the rod at points %r" % ends)
        rate = f["twist_rate"][ps]
        k = ps.stop - ps.start
        for e in range(k - 1):
            inner = [rate[v] for v in (e, e + 1) if 0 < v < k - 1]
            want = sum(inner) / len(inner) if inner else 0.0
            if abs(f["twist"][cs][e] - want) > 1e-12 * max(1.0, abs(want)):
                fail("cell twist %g of edge %d, expected %g" % (f["twist"][cs][e], e, want))
    ed, lr = f["energy_density"], f["rest_length"]
    if ed.min() < 0 or lr.min() <= 0:
        fail("negative energy density (%g) or rest length (%g)" % (ed.min(), lr.min()))
    t = result["energy_terms"]
    elastic = t["stretch"] + t["bend"] + t["twist"]
    total = float(np.sum(ed * lr))
    tol = 1e-10 * max(abs(elastic), 1e-300)
    if nj == 0 and abs(total - elastic) > tol:
        fail("sum of energy_density * rest_length = %.17g, elastic energy %.17g"
             % (total, elastic))
    if nj > 0 and total > elastic + tol:  # joints' energy is not in the rods' cells
        fail("sum of energy_density * rest_length = %.17g exceeds the elastic energy "
             "%.17g" % (total, elastic))
    if np.any(f["axial_force"] * f["stretch"] < 0):
        fail("axial_force and stretch of opposite signs")
    print("check_vtu_fields: max |M| %.6g, max |twisting moment| %.3g, max |axial force| "
          "%.6g, elastic energy %.9g, sum of energy_density * rest_length %.9g"
          % (M.max(), np.abs(f["twisting_moment"]).max(), np.abs(f["axial_force"]).max(),
             elastic, total))


def check_equilibrium(f, nv, tip_force, end_moment):
    """Rod 0: M_i (1 + |kb_i|^2 / 4) against the statics of the loaded end."""
    x = f["points"][:nv[0]]
    Mv = f["bending_moment_vector"][:nv[0]]
    vor = 0.5 * (np.linalg.norm(x[1:-1] - x[:-2], axis=1) +
                 np.linalg.norm(x[2:] - x[1:-1], axis=1))
    kb = np.linalg.norm(f["curvature"][1:nv[0] - 1], axis=1) * vor
    lhs = Mv[1:-1] * (1 + kb[:, None] ** 2 / 4)
    if tip_force is not None:
        rhs = np.cross(x[-1] - x[1:-1], np.array(tip_force))
    else:
        rhs = np.tile(np.array(end_moment), (len(lhs), 1))
    scale = np.linalg.norm(rhs, axis=1).max()
    err = np.linalg.norm(lhs - rhs, axis=1).max() / scale
    if not err <= EQUILIBRIUM_RTOL:
        fail("moment equilibrium off by %.3g relative to max |M| %.6g" % (err, scale))
    m0 = np.linalg.norm(Mv[1])
    print("check_vtu_fields: equilibrium of moments within %.2g; |M| at the first "
          "interior vertex %.9g (its statics: %.9g)" % (err, m0, np.linalg.norm(rhs[0])))


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("vtu")
    ap.add_argument("--result", required=True)
    ap.add_argument("--tip-force", type=float, nargs=3)
    ap.add_argument("--end-moment", type=float, nargs=3)
    a = ap.parse_args()
    with open(a.result) as fh:
        result = json.load(fh)
    f, nv, nj = read(a.vtu, result)
    check_general(f, nv, nj, result)
    if a.tip_force or a.end_moment:
        if len(nv) != 1 or nj:
            fail("the equilibrium checks are for a single rod")
        if result.get("status") != "converged":
            fail("equilibrium checks need a converged result")
        check_equilibrium(f, nv, a.tip_force, a.end_moment)
    print("check_vtu_fields: ok: %s (%d points, %d cells)"
          % (a.vtu, len(f["points"]), len(f["rod"])))


if __name__ == "__main__":
    main()
