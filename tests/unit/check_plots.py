#!/usr/bin/env python3
"""Issue 22 item 8: properties of rodnet's plots that a reader needs and a test can
check, on the figures the scripts build (problems/plot_*.py):
  - plot_stiffness: the polar curve of an isotropic cell (a circle) lies inside
    the frame circle (the radial limit above the largest modulus), also in 3D;
  - plot_sweep: several seeds are averaged and the legend says "mean of N seeds";
    a series has the same colour in both panels;
  - plot_path: the tick labels of the eigenvalue axis (symlog) do not overlap.
Each also writes its PNG (atomically) from files: RESULT.json, sweep.csv and
path.csv given on the command line (made by rodnet in the ctest fixtures), and
the same checks run on them.

Usage: check_plots.py RESULT.json SWEEP.csv PATH.csv OUTDIR"""
import csv
import json
import math
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "..", "problems", "cli"))
import plot_path  # noqa: E402
import plot_stiffness  # noqa: E402
import plot_sweep  # noqa: E402

failures = []


def check(ok, what):
    print(("ok      " if ok else "FAILED  ") + what)
    if not ok:
        failures.append(what)


def stiffness(r, tag):
    fig, ax = plot_stiffness.figure(r)
    top = max(max(r[k]) for k in r if k.startswith("directional_modulus_")
              and k != "directional_modulus_angles_deg")
    rmax = ax.get_ylim()[1]
    check(rmax >= 1.05 * top, f"{tag}: polar frame radius {rmax:.4g} above the largest "
          f"modulus {top:.4g} by 5 % at least")


def sweep(series, tag, seeds):
    fig, (ax_e, ax_nu) = plot_sweep.figure(series)
    texts = [t.get_text() for t in ax_e.get_legend().get_texts()]
    if seeds > 1:
        check(any(f"mean of {seeds} seeds" in t for t in texts),
              f"{tag}: the legend says 'mean of {seeds} seeds': {texts}")
    else:
        check(not any("mean of" in t for t in texts), f"{tag}: one seed, no mean: {texts}")
    # same colour for a series in both panels (legend handles by label)
    def colours(ax):
        h, lab = ax.get_legend_handles_labels()
        out = {}
        for handle, label in zip(h, lab):
            line = handle.lines[0] if hasattr(handle, "lines") else handle  # errorbar
            out[label.split(" (")[0]] = line.get_color()
        return out
    ce, cn = colours(ax_e), colours(ax_nu)
    common = [k for k in ce if k in cn and k.startswith("rodnet")]
    check(common and all(ce[k] == cn[k] for k in common),
          f"{tag}: each rodnet series one colour in both panels: {ce} / {cn}")


def overlapping(labels, renderer):
    boxes = [t.get_window_extent(renderer) for t in labels if t.get_text()]
    boxes.sort(key=lambda b: b.y0)
    return any(b.y0 < a.y1 - 0.5 for a, b in zip(boxes, boxes[1:]))


def path(rows, tag):
    fig, (ax, ax2) = plot_path.figure(rows, tag)
    fig.canvas.draw()
    r = fig.canvas.get_renderer()
    labels = [t for t in ax2.get_yticklabels() if t.get_visible()]
    check(not overlapping(labels, r),
          f"{tag}: {len(labels)} eigenvalue tick labels, none overlapping "
          f"({[t.get_text() for t in labels]})")
    check(len(labels) <= 2 * plot_path.MAX_DECADE_TICKS + 1,
          f"{tag}: at most {2 * plot_path.MAX_DECADE_TICKS + 1} eigenvalue tick labels")


def synthetic():
    iso = {"directional_modulus_angles_deg": [0, 360, 2],
           "directional_modulus_xy": [0.0123] * 181, "units": "force per length (2D)",
           "constants": {"E1": 0.0123, "E2": 0.0123, "nu12": 0.98},
           "relative_density": 0.05}
    stiffness(iso, "synthetic isotropic 2D")
    iso3 = dict(iso, directional_modulus_xz=[0.02] * 181)
    stiffness(iso3, "synthetic isotropic 3D (xz larger)")
    from collections import defaultdict
    ser = defaultdict(lambda: defaultdict(list))
    for lat in ("honeycomb", "kagome"):
        for rho in (0.01, 0.03, 0.1):
            for seed in ("0", "1", "2"):
                e, nu, _ = plot_sweep.honeycomb_closed_form(rho)
                f = 1.0 + 0.01 * int(seed)
                ser[(lat, "rigid")][rho].append((e * f, nu, seed))
    sweep(ser, "synthetic sweep, 3 seeds", 3)
    rows = []
    for k in range(60):  # an eigenvalue over 14 decades, both signs
        lam = (10.0 ** (2 - 0.25 * k)) * (1 if k < 40 else -1)
        rows.append({"event": "point", "load_factor": "%r" % (k / 60), "force": "0",
                     "displacement": "%r" % (0.01 * k), "stability":
                     "stable" if lam > 0 else "unstable", "arclength": "%r" % (0.01 * k),
                     "lowest_eigenvalue": "%r" % lam})
    path(rows, "synthetic path, eigenvalue over 14 decades")


def main():
    synthetic()
    if len(sys.argv) == 5:
        res, swp, pth, out = sys.argv[1:5]
        with open(res) as f:
            stiffness(json.load(f), os.path.basename(res))
        series = plot_sweep.read(swp)
        seeds = len({p[2] for s in series.values() for v in s.values() for p in v})
        sweep(series, os.path.basename(swp), seeds)
        with open(pth, newline="") as f:
            path(list(csv.DictReader(f)), os.path.basename(pth))
        for script, args in ((plot_stiffness, [res]), (plot_sweep, [swp]),
                             (plot_path, [pth])):
            png = os.path.join(out, "check_plots_" + script.__name__ + ".png")
            sys.argv = [script.__name__, args[0], png]
            rc = script.main(sys.argv) if script is plot_path else script.main()
            check(rc in (0, None) and os.path.getsize(png) > 10000
                  and not os.path.exists(png + ".tmp.png"),
                  f"{script.__name__}: wrote {png} ({os.path.getsize(png)} bytes)")
    print("FAILED: %d" % len(failures) if failures else "all checks passed")
    sys.exit(1 if failures else 0)


if __name__ == "__main__":
    main()
