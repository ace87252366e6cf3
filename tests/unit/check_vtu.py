#!/usr/bin/env python3
"""Check a .vtu written by rodnet with VTK's own reader (python3-vtk9).

    check_vtu.py OUT.vtu [--result RESULT.json] [--points N] [--cells M]

Asserts: the reader accepts the file; point and cell counts (from the
options or from RESULT.json: sum of vertices plus joints, sum of edges plus
joints); every point and cell array is present with its component count and
finite values; cells are VTK_LINE (rod edges) then VTK_VERTEX (one per
joint, on its own point); directors are unit, orthogonal and normal to their
edge; the points equal the result's vertices and joint positions (exactly:
both are printed with %.17g), joint_rotation equals the joints' rotation and
is zero on rod points, the cell array joint numbers the joints (-1 on
edges), and the displacement is the difference to the initial positions
(zero at a clamped start).  Exits
non-zero with a message on the first failure."""
import argparse
import json
import math
import sys

from vtkmodules.vtkIOXML import vtkXMLUnstructuredGridReader

POINT_ARRAYS = {"displacement": 3, "curvature": 2, "twist_rate": 1, "joint_rotation": 9}
CELL_ARRAYS = {"rod": 1, "edge": 1, "theta": 1, "stretch": 1, "d1": 3, "d2": 3, "joint": 1}
VTK_VERTEX, VTK_LINE = 1, 3


def fail(msg):
    print("check_vtu: FAILED: " + msg)
    sys.exit(1)


def array_values(arr):
    n, c = arr.GetNumberOfTuples(), arr.GetNumberOfComponents()
    return [[arr.GetComponent(i, k) for k in range(c)] for i in range(n)]


def check_arrays(data, spec, count, where):
    for name, ncomp in spec.items():
        arr = data.GetArray(name)
        if arr is None:
            fail("%s array '%s' missing" % (where, name))
        if arr.GetNumberOfComponents() != ncomp or arr.GetNumberOfTuples() != count:
            fail("%s array '%s': %d x %d, expected %d x %d" % (
                where, name, arr.GetNumberOfTuples(), arr.GetNumberOfComponents(), count, ncomp))
        for k in range(ncomp):
            lo, hi = arr.GetRange(k)
            if not (math.isfinite(lo) and math.isfinite(hi)):
                fail("%s array '%s' component %d not finite: [%r, %r]" % (where, name, k, lo, hi))


def dot(a, b):
    return sum(x * y for x, y in zip(a, b))


def check_directors(grid):
    cd = grid.GetCellData()
    d1, d2 = array_values(cd.GetArray("d1")), array_values(cd.GetArray("d2"))
    pts = grid.GetPoints()
    for c in range(grid.GetNumberOfCells()):
        if grid.GetCellType(c) != VTK_LINE:
            continue
        ids = grid.GetCell(c).GetPointIds()
        a, b = pts.GetPoint(ids.GetId(0)), pts.GetPoint(ids.GetId(1))
        t = [y - x for x, y in zip(a, b)]
        lt = math.sqrt(dot(t, t))
        errs = [abs(dot(d1[c], d1[c]) - 1), abs(dot(d2[c], d2[c]) - 1),
                abs(dot(d1[c], d2[c])), abs(dot(d1[c], t)) / lt, abs(dot(d2[c], t)) / lt]
        if max(errs) > 1e-9:
            fail("cell %d: directors not an orthonormal frame normal to the edge (%r)" % (c, errs))


def check_result(grid, result):
    pts = grid.GetPoints()
    disp = array_values(grid.GetPointData().GetArray("displacement"))
    i = 0
    for rod in result["rods"]:
        for v in rod["vertices"]:
            p = pts.GetPoint(i)
            if list(p) != v:
                fail("point %d = %r differs from the result's vertex %r" % (i, p, v))
            i += 1
        first = disp[i - len(rod["vertices"])]
        if rod.get("_clamped_start") and max(abs(x) for x in first) > 0:
            fail("clamped start moved: %r" % first)
    rot = array_values(grid.GetPointData().GetArray("joint_rotation"))
    if any(any(x != 0 for x in rot[k]) for k in range(i)):
        fail("joint_rotation is not zero on rod points")
    jcell = array_values(grid.GetCellData().GetArray("joint"))
    ncells_rods = sum(len(rod["vertices"]) - 1 for rod in result["rods"])
    for j, joint in enumerate(result.get("joints", [])):
        p = pts.GetPoint(i + j)
        if list(p) != joint["position"]:
            fail("joint point %d = %r differs from the result's %r" % (j, p, joint["position"]))
        want = [x for row in joint["rotation"] for x in row]
        if max(abs(x - y) for x, y in zip(rot[i + j], want)) > 1e-15:
            fail("joint_rotation of joint %d = %r, result %r" % (j, rot[i + j], want))
        c = ncells_rods + j
        ids = grid.GetCell(c).GetPointIds()
        if ids.GetNumberOfIds() != 1 or ids.GetId(0) != i + j or jcell[c][0] != j:
            fail("cell %d is not the vertex cell of joint %d" % (c, j))
    if any(jcell[c][0] != -1 for c in range(ncells_rods)):
        fail("cell array joint is not -1 on rod edges")


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("vtu")
    ap.add_argument("--result")
    ap.add_argument("--points", type=int)
    ap.add_argument("--cells", type=int)
    ap.add_argument("--clamped-start", action="store_true",
                    help="the first vertex of every rod must not move")
    a = ap.parse_args()
    result = None
    if a.result:
        with open(a.result) as f:
            result = json.load(f)
        nj = len(result.get("joints", []))
        a.points = sum(len(r["vertices"]) for r in result["rods"]) + nj
        a.cells = sum(len(r["vertices"]) - 1 for r in result["rods"]) + nj
        for r in result["rods"]:
            r["_clamped_start"] = a.clamped_start
    reader = vtkXMLUnstructuredGridReader()
    reader.SetFileName(a.vtu)
    reader.Update()
    if reader.GetErrorCode() != 0:
        fail("reader error code %d" % reader.GetErrorCode())
    grid = reader.GetOutput()
    n, m = grid.GetNumberOfPoints(), grid.GetNumberOfCells()
    if n == 0 or n != a.points or m != a.cells:
        fail("%d points, %d cells; expected %r, %r" % (n, m, a.points, a.cells))
    lo = [grid.GetBounds()[k] for k in range(6)]
    if not all(math.isfinite(x) for x in lo):
        fail("point bounds not finite: %r" % lo)
    check_arrays(grid.GetPointData(), POINT_ARRAYS, n, "point")
    check_arrays(grid.GetCellData(), CELL_ARRAYS, m, "cell")
    seen_vertex = False
    for c in range(m):
        t = grid.GetCellType(c)
        if t not in (VTK_LINE, VTK_VERTEX) or (seen_vertex and t == VTK_LINE):
            fail("cell %d has type %d: expected VTK_LINE (3) cells, then VTK_VERTEX (1)" % (c, t))
        seen_vertex = seen_vertex or t == VTK_VERTEX
    check_directors(grid)
    if result is not None:
        check_result(grid, result)
    print("check_vtu: ok: %s (%d points, %d cells, %d joint vertices)" % (
        a.vtu, n, m, sum(grid.GetCellType(c) == VTK_VERTEX for c in range(m))))


if __name__ == "__main__":
    main()
