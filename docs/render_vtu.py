#!/usr/bin/env python3
"""Render a rodnet .vtu (rods as VTK_LINE cells) to a PNG: VTK reads the file,
matplotlib (Agg, no display needed) draws the deformed rods colored by one
field, over the undeformed shape (points minus displacement) in gray.

    /usr/bin/python3 docs/render_vtu.py OUT.vtu PNG [--field bending_moment]
        [--view xz|xy|yz|3d] [--title TEXT] [--width-px 1400] [--quiet]

--field names a point array (each half edge gets the value of its vertex) or a
cell array of the .vtu; vector fields are shown by their magnitude.  Needs
python3-vtk9 and matplotlib (Debian's /usr/bin/python3 has both).  The PNG is
written to a temporary file and renamed (completely or not at all); --quiet: no
"wrote" line.
"""
import argparse
import os

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from matplotlib.collections import LineCollection  # noqa: E402
from mpl_toolkits.mplot3d.art3d import Line3DCollection  # noqa: E402
from vtkmodules.util.numpy_support import vtk_to_numpy  # noqa: E402
from vtkmodules.vtkIOXML import vtkXMLUnstructuredGridReader  # noqa: E402

AXES = {"x": 0, "y": 1, "z": 2}


def read(path):
    reader = vtkXMLUnstructuredGridReader()
    reader.SetFileName(path)
    reader.Update()
    if reader.GetErrorCode() != 0:
        raise SystemExit("render_vtu: cannot read %s" % path)
    return reader.GetOutput()


def segments(grid):
    """Point-index pairs of the line cells (other cells, e.g. joints, skipped)."""
    pairs, cells = [], []
    for c in range(grid.GetNumberOfCells()):
        ids = grid.GetCell(c).GetPointIds()
        if grid.GetCellType(c) == 3 and ids.GetNumberOfIds() == 2:
            pairs.append((ids.GetId(0), ids.GetId(1)))
            cells.append(c)
    return np.array(pairs), np.array(cells)


def segment_values(grid, name, pts, pairs, cells):
    """Segments to draw and their values.  A cell field colors each edge; a
    point field colors each half edge by its vertex (its Voronoi cell)."""
    arr = grid.GetPointData().GetArray(name)
    on_points = arr is not None
    if not on_points:
        arr = grid.GetCellData().GetArray(name)
    if arr is None:
        raise SystemExit("render_vtu: no point or cell array '%s'" % name)
    v = vtk_to_numpy(arr).astype(float)
    if v.ndim > 1:
        v = np.linalg.norm(v, axis=1)
    if not on_points:
        return pts[pairs], v[cells]
    a, b = pts[pairs[:, 0]], pts[pairs[:, 1]]
    mid = 0.5 * (a + b)
    segs = np.concatenate([np.stack([a, mid], axis=1), np.stack([mid, b], axis=1)])
    return segs, np.concatenate([v[pairs[:, 0]], v[pairs[:, 1]]])


def draw(ax, segs, view, **kw):
    if view == "3d":
        coll = Line3DCollection(segs, **kw)
        ax.add_collection3d(coll)
    else:
        i, j = AXES[view[0]], AXES[view[1]]
        coll = LineCollection(segs[:, :, [i, j]], **kw)
        ax.add_collection(coll)
    return coll


def frame(ax, allpts, view):
    lo, hi = allpts.min(axis=0), allpts.max(axis=0)
    pad = 0.06 * max(hi - lo)
    if view == "3d":
        for k, setter in enumerate((ax.set_xlim, ax.set_ylim, ax.set_zlim)):
            setter(lo[k] - pad, hi[k] + pad)
        ax.set_box_aspect(tuple(np.maximum(hi - lo, 0.05 * max(hi - lo))))
        ax.set_xlabel("x")
        ax.set_ylabel("y")
        ax.set_zlabel("z")
    else:
        i, j = AXES[view[0]], AXES[view[1]]
        ax.set_xlim(lo[i] - pad, hi[i] + pad)
        ax.set_ylim(lo[j] - pad, hi[j] + pad)
        ax.set_aspect("equal")
        ax.set_xlabel(view[0])
        ax.set_ylabel(view[1])
        ax.grid(True, lw=0.3, alpha=0.5)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("vtu")
    ap.add_argument("png")
    ap.add_argument("--field", default="bending_moment")
    ap.add_argument("--view", default="xz", choices=["xz", "xy", "yz", "3d"])
    ap.add_argument("--title", default="")
    ap.add_argument("--label", default="", help="colorbar label (default: the field)")
    ap.add_argument("--width-px", type=int, default=1400)
    ap.add_argument("--quiet", action="store_true", help="no 'wrote' line")
    a = ap.parse_args()

    grid = read(a.vtu)
    pts = vtk_to_numpy(grid.GetPoints().GetData()).astype(float)
    disp = grid.GetPointData().GetArray("displacement")
    rest = pts - vtk_to_numpy(disp) if disp is not None else pts
    pairs, cells = segments(grid)
    segs, vals = segment_values(grid, a.field, pts, pairs, cells)

    dpi = 200
    fig = plt.figure(figsize=(a.width_px / dpi, 0.6 * a.width_px / dpi), dpi=dpi)
    ax = fig.add_subplot(111, projection="3d" if a.view == "3d" else None)
    draw(ax, rest[pairs], a.view, colors="0.6", linewidths=1.0, linestyles="dashed")
    coll = draw(ax, segs, a.view, cmap="viridis", linewidths=3.0, capstyle="butt")
    coll.set_array(vals)
    coll.set_clim(vals.min(), vals.max() if vals.max() > vals.min() else vals.min() + 1)
    frame(ax, np.vstack([pts, rest]), a.view)
    fig.colorbar(coll, ax=ax, label=a.label or a.field, shrink=0.8)
    ax.set_title(a.title or "%s: %s (undeformed dashed)" % (a.vtu.split("/")[-1], a.field),
                 fontsize=9)
    fig.tight_layout()
    tmp = a.png + ".tmp.png"
    fig.savefig(tmp, dpi=dpi)
    os.replace(tmp, a.png)
    if not a.quiet:
        print("render_vtu: wrote %s (%d segments, %s in [%.4g, %.4g])"
              % (a.png, len(pairs), a.field, vals.min(), vals.max()))


if __name__ == "__main__":
    main()
