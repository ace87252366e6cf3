#!/usr/bin/env python3
"""Speed against error (docs/benchmarking.md, section 1).

    pareto.py --rodnet build/rodnet -o DIR [--quick] [--repeats N]

Cases with closed forms (docs/validation.md, tests/validation):
  cantilever  a clamped rod (L = 1, round wire r = 1e-3, E = 1e7) under the tip load
              P = 2 EI / L^2; reference: the inextensible elastica's tip (elliptic
              integrals, Bisshopp & Drucker), error |tip - tip_ref| / L;
  end_moment  the rod of problems/scenes/end_moment_circle.json under the end moment
              M = 2 pi EI / L, which closes it into a circle: the tip returns to the
              root, error |tip - root| / L;
  end_moment_half  the same rod under M = pi EI / L: a half circle, the tip at
              2 L / pi from the root.  (The full circle hides the vertex clamp's
              first-order error: the arc it loses, h, is the clamp's offset, so the
              tip still meets the root to O(h^2); the half circle shows it.)
  honeycomb_cell  the periodic cell of the rigid-jointed regular honeycomb at relative
              density 0.05 (square t x t struts, t/l = 0.043; `rodnet generate honeycomb
              --periodic`), homogenised by `rodnet homogenize` (a direct Schur
              complement: no solver tolerance, gtol 0 in the CSV); reference: the
              Euler-Bernoulli frame closed form with axial stretching
              (problems/cli/plot_sweep.py, VALIDATION.md 6.2), error |E1 - E1_ref| / E1_ref;
              only the number of edges per strut varies (clamp "periodic").
For both clamp conventions (docs/scene-format.md, "at" of a clamp): "midpoint" (the
clamped edge's midpoint at the root, rod from x = -h/2 to L: second order) and
"vertex" (the clamped edge's first vertex at the root, rod from 0 to L: first order),
every number of edges and solver tolerance (--gtol) is solved with `rodnet solve`
(repeats times; the median of the solver's time_s).  Writes DIR/pareto.csv (one row
per case, clamp, edges, gtol), DIR/pareto_orders.csv (the fitted convergence orders,
least squares of log error on log h at the tightest gtol, and the Pareto-optimal
points), and DIR/pareto_<case>.png (error against time, the Pareto front per clamp).
"""
import argparse
import csv
import json
import math
import os
import statistics
import subprocess
import sys
import tempfile

E = 1.0e7


# ---- the inextensible elastica of a tip-loaded cantilever (Carlson forms) --------
def carlson_rf(x, y, z):
    for _ in range(100):
        sx, sy, sz = math.sqrt(x), math.sqrt(y), math.sqrt(z)
        lam = sx * sy + sy * sz + sz * sx
        x, y, z = 0.25 * (x + lam), 0.25 * (y + lam), 0.25 * (z + lam)
        mu = (x + y + z) / 3.0
        dx, dy, dz = 1 - x / mu, 1 - y / mu, 1 - z / mu
        if max(abs(dx), abs(dy), abs(dz)) < 1e-4:
            e2, e3 = dx * dy - dz * dz, dx * dy * dz
            return (1 - e2 / 10 + e3 / 14 + e2 * e2 / 24 - 3 * e2 * e3 / 44) / math.sqrt(mu)
    raise ArithmeticError("carlson_rf did not converge")


def carlson_rd(x, y, z):
    total, fac = 0.0, 1.0
    for _ in range(100):
        sx, sy, sz = math.sqrt(x), math.sqrt(y), math.sqrt(z)
        lam = sx * sy + sy * sz + sz * sx
        total += fac / (sz * (z + lam))
        fac *= 0.25
        x, y, z = 0.25 * (x + lam), 0.25 * (y + lam), 0.25 * (z + lam)
        mu = (x + y + 3 * z) / 5.0
        dx, dy, dz = 1 - x / mu, 1 - y / mu, 1 - z / mu
        if max(abs(dx), abs(dy), abs(dz)) < 1e-4:
            ea, eb = dx * dy, dz * dz
            ec, ed = ea - eb, ea - 6 * eb
            ee = ed + ec + ec
            s = (1 + ed * (-3.0 / 14 + 9.0 / 88 * ed - 4.5 / 26 * dz * ee)
                 + dz * (ee / 6 + dz * (-9.0 / 22 * ec + dz * 3.0 / 26 * ea)))
            return 3 * total + fac * s / (mu * math.sqrt(mu))
    raise ArithmeticError("carlson_rd did not converge")


def ell_f(phi, k):
    s, c = math.sin(phi), math.cos(phi)
    return s * carlson_rf(c * c, 1 - k * k * s * s, 1.0)


def ell_e(phi, k):
    s, c = math.sin(phi), math.cos(phi)
    q = 1 - k * k * s * s
    return s * carlson_rf(c * c, q, 1.0) - k * k * s ** 3 * carlson_rd(c * c, q, 1.0) / 3.0


def elastica_tip(alpha):
    """(dh, dv) / L of the tip of the inextensible elastica, alpha = P L^2 / EI."""
    lo, hi = 1e-12, math.pi / 2 - 1e-12
    for _ in range(200):  # bisection on the tip slope theta0
        th0 = 0.5 * (lo + hi)
        k = math.sqrt((1 + math.sin(th0)) / 2)
        phi1 = math.asin(1 / (k * math.sqrt(2.0)))
        if ell_f(math.pi / 2, k) - ell_f(phi1, k) - math.sqrt(alpha) > 0:
            hi = th0
        else:
            lo = th0
    k = math.sqrt((1 + math.sin(th0)) / 2)
    phi1 = math.asin(1 / (k * math.sqrt(2.0)))
    dh = 1 - math.sqrt(2 * math.sin(th0) / alpha)
    dv = 1 - (2 / math.sqrt(alpha)) * (ell_e(math.pi / 2, k) - ell_e(phi1, k))
    return dh, dv


# ---- scenes -----------------------------------------------------------------------
CASES = ("cantilever", "end_moment", "end_moment_half")
ALL_CASES = CASES + ("honeycomb_cell",)
HC_DENSITY = 0.05


def clamps_of(case):
    return ("periodic",) if case == "honeycomb_cell" else ("midpoint", "vertex")


def honeycomb_E1(rho, E_s=1.0):
    """E1 of the rigid-jointed regular honeycomb with square t x t struts at relative
    density rho = 2 t / (sqrt(3) l), cell size 1 (as problems/cli/plot_sweep.py)."""
    l = 1.0 / math.sqrt(3.0)
    t = math.sqrt(3.0) * rho * l / 2.0
    EA, EI = E_s * t * t, E_s * t ** 4 / 12.0
    s = EI / (EA * l * l)
    return 16.0 * math.sqrt(3.0) * EI / l ** 3 / (1.0 + 36.0 * s)


def honeycomb_rows(rodnet, tmp, edges, repeats, commit, version):
    """One row per number of edges per strut: rodnet homogenize's E1 against the
    closed form, the median of repeats runs' time_s."""
    ref = honeycomb_E1(HC_DENSITY)
    rows = []
    for n in edges:
        path = os.path.join(tmp, f"honeycomb_{n}.json")
        out = os.path.join(tmp, "h.json")
        gen = subprocess.run([rodnet, "generate", "honeycomb", "--periodic", "--cells", "1",
                              "--joint-model", "rigid", "--edges-per-rod", str(n),
                              "--relative-density", repr(HC_DENSITY), "-o", path],
                             stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
        if gen.returncode != 0:
            sys.exit(f"pareto.py: rodnet generate failed: {gen.stderr}")
        res = []
        for _ in range(repeats):
            rc = subprocess.run([rodnet, "homogenize", path, "-o", out],
                                stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
            if rc.returncode != 0:
                sys.exit(f"pareto.py: rodnet homogenize {path} failed: {rc.stderr}")
            with open(out) as f:
                res.append(json.load(f))
        E1 = res[0]["constants"]["E1"]
        times = [r["time_s"] for r in res]
        rows.append({"case": "honeycomb_cell", "clamp": "periodic", "edges": n, "gtol": 0.0,
                     "error": abs(E1 - ref) / ref, "time_s": statistics.median(times),
                     "time_min_s": min(times), "repeats": repeats,
                     "converged": int(math.isfinite(E1)), "iterations": 0, "load_steps": 0,
                     "commit": commit, "rodnet": version})
        print(f"honeycomb_cell periodic n={n:<4} error={rows[-1]['error']:.3e} "
              f"time={rows[-1]['time_s']:.4f}s", flush=True)
    return rows


def scene(case, clamp, edges):
    L = 1.0
    if case == "cantilever":
        r = 1e-3
        EI = E * math.pi * r ** 4 / 4
        section = {"shape": "circle", "radius": r}
        load = {"type": "force", "rod": "beam", "vertex": -1, "value": [0, 0, -2.0 * EI]}
    else:
        r = 0.01
        A, I = math.pi * r * r, math.pi * r ** 4 / 4
        EI = E * I
        # the round wire in the plane of bending, 100 times stiffer out of plane and
        # in torsion (as problems/scenes/end_moment_circle.json: no lateral buckling)
        section = {"shape": "explicit", "A": A, "I11": 100 * I, "I22": I, "I12": 0,
                   "J": 200 * I}
        load = {"type": "moment", "rod": "beam", "vertex": -1,
                "value": [0, -(2 if case == "end_moment" else 1) * math.pi * EI / L, 0]}
    return {
        "description": f"pareto.py: {case}, clamp at the {clamp}, {edges} edges",
        "materials": {"m": {"E": E, "nu": 0.5}},
        "sections": {"s": section},
        "rods": [{"name": "beam", "material": "m", "section": "s",
                  "line": {"from": [0, 0, 0], "to": [L, 0, 0], "vertices": edges + 1},
                  "d1": [0, 1, 0]}],
        "constraints": [{"type": "clamp", "rod": "beam", "end": "start", "at": clamp}],
        "loads": [load],
    }


def error_of(case, tip, ref):
    if case == "cantilever":
        dh, dv = ref
        return math.hypot((1.0 - tip[0]) - dh, -tip[2] - dv)
    if case == "end_moment_half":  # a half circle of radius L / pi: tip at (0, 0, 2L/pi)
        return math.sqrt(tip[0] ** 2 + tip[1] ** 2 + (abs(tip[2]) - 2 / math.pi) ** 2)
    return math.sqrt(tip[0] ** 2 + tip[1] ** 2 + tip[2] ** 2)


def solve(rodnet, path, out, gtol):
    rc = subprocess.run([rodnet, "solve", path, "-o", out, "--gtol", repr(gtol), "-q"],
                        stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    if rc.returncode not in (0, 1):
        sys.exit(f"pareto.py: rodnet solve {path} failed ({rc.returncode}): {rc.stderr}")
    with open(out) as f:
        return json.load(f)


def slope(xs, ys):
    lx, ly = [math.log(x) for x in xs], [math.log(y) for y in ys]
    mx, my = sum(lx) / len(lx), sum(ly) / len(ly)
    return (sum((a - mx) * (b - my) for a, b in zip(lx, ly))
            / sum((a - mx) ** 2 for a in lx))


def pareto_front(points):
    """Indices of the points (time, error) no other point beats in both."""
    order = sorted(range(len(points)), key=lambda i: (points[i][0], points[i][1]))
    front, best = [], math.inf
    for i in order:
        if points[i][1] < best:
            front.append(i)
            best = points[i][1]
    return front


def provenance(rodnet):
    out = subprocess.run([rodnet, "--version"], capture_output=True, text=True).stdout
    commit = subprocess.run(["git", "rev-parse", "--short=12", "HEAD"], capture_output=True,
                            text=True, cwd=os.path.dirname(os.path.abspath(__file__)))
    return out.splitlines()[0] if out else "rodnet", commit.stdout.strip() or "unknown"


def parse_args():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--rodnet", default="build/rodnet")
    ap.add_argument("-o", "--outdir", required=True)
    ap.add_argument("--quick", action="store_true", help="fewer sizes and tolerances")
    ap.add_argument("--repeats", type=int, default=None)
    ap.add_argument("--check", action="store_true",
                    help="exit 1 unless every solve converged and the orders are those "
                         "of the conventions: midpoint 2 (+-0.15) in every case, vertex "
                         "1 (+-0.25) for the cantilever and the half circle, and 2 "
                         "(+-0.15) for the honeycomb cell")
    return ap.parse_args()


def rod_rows(rodnet, tmp, edges, gtols, repeats, commit, version):
    """Every rod case (CASES) with both clamps at every size and tolerance: a row of
    error and time per (case, clamp, edges, gtol), printed as it is measured."""
    ref = elastica_tip(2.0)
    rows = []
    for case in CASES:
        for clamp in ("midpoint", "vertex"):
            for n in edges:
                path = os.path.join(tmp, f"{case}_{clamp}_{n}.json")
                with open(path, "w") as f:
                    json.dump(scene(case, clamp, n), f)
                for g in gtols:
                    res = [solve(rodnet, path, os.path.join(tmp, "r.json"), g)
                           for _ in range(repeats)]
                    tip = res[0]["rods"][0]["vertices"][-1]
                    times = [r["time_s"] for r in res]
                    rows.append({
                        "case": case, "clamp": clamp, "edges": n, "gtol": g,
                        "error": error_of(case, tip, ref),
                        "time_s": statistics.median(times), "time_min_s": min(times),
                        "repeats": repeats, "converged": int(res[0]["converged"]),
                        "iterations": res[0]["iterations"],
                        "load_steps": res[0]["load_steps"], "commit": commit,
                        "rodnet": version})
                    print(f"{case:<11} {clamp:<9} n={n:<4} gtol={g:<7g} "
                          f"error={rows[-1]['error']:.3e} time={rows[-1]['time_s']:.4f}s",
                          flush=True)
    return rows


def write_csv(path, rows):
    with open(path, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0].keys()))
        w.writeheader()
        w.writerows(rows)


def summarise(rows):
    """Per (case, clamp): the fitted order of the error at the tightest tolerance and
    the Pareto front of (time, error), printed."""
    summary = []
    for case in ALL_CASES:
        for clamp in clamps_of(case):
            sub = [r for r in rows if r["case"] == case and r["clamp"] == clamp]
            tight = [r for r in sub if r["gtol"] == min(x["gtol"] for x in sub)]
            hs = [1.0 / r["edges"] for r in tight]
            order = slope(hs, [r["error"] for r in tight])
            front = pareto_front([(r["time_s"], r["error"]) for r in sub])
            summary.append({"case": case, "clamp": clamp, "order": round(order, 3),
                            "pareto": " ".join(
                                f"n={sub[i]['edges']}/gtol={sub[i]['gtol']:g}:"
                                f"{sub[i]['error']:.2e}@{sub[i]['time_s']:.4f}s"
                                for i in front)})
            print(f"{case:<11} clamp at {clamp:<9} order {order:.3f}; Pareto front: "
                  f"{summary[-1]['pareto']}")
    return summary


def check(rows, summary):
    """--check: exits 1 naming what failed unless every solve converged and every
    order is that of its convention."""
    bad = [f"{r['case']} {r['clamp']} n={r['edges']} gtol={r['gtol']:g}: not converged"
           for r in rows if not r["converged"]]
    for s in summary:
        want = 1.0 if s["clamp"] == "vertex" else 2.0
        tol = 0.25 if s["clamp"] == "vertex" else 0.15
        if s["clamp"] == "vertex" and s["case"] == "end_moment":
            continue  # the full circle hides the vertex clamp's first order
        if abs(s["order"] - want) > tol:
            bad.append(f"{s['case']} clamp at {s['clamp']}: order {s['order']}, "
                       f"expected {want} +- {tol}")
    if bad:
        sys.exit("pareto.py: " + "\n  ".join(bad))
    print("pareto.py: every solve converged; orders as expected")


def main():
    a = parse_args()
    edges = [10, 20, 40, 80] if a.quick else [10, 20, 40, 80, 160, 320]
    gtols = [1e-3, 1e-9] if a.quick else [1e-2, 1e-4, 1e-6, 1e-9]
    repeats = a.repeats or (1 if a.quick else 3)
    os.makedirs(a.outdir, exist_ok=True)
    version, commit = provenance(a.rodnet)
    with tempfile.TemporaryDirectory() as tmp:
        rows = rod_rows(a.rodnet, tmp, edges, gtols, repeats, commit, version)
        hc_edges = [4, 8, 16, 32] if a.quick else [4, 8, 16, 32, 64, 128]
        rows += honeycomb_rows(a.rodnet, tmp, hc_edges, repeats, commit, version)
    write_csv(os.path.join(a.outdir, "pareto.csv"), rows)
    summary = summarise(rows)
    write_csv(os.path.join(a.outdir, "pareto_orders.csv"), summary)
    plot(rows, summary, a.outdir)
    if a.check:
        check(rows, summary)


def plot(rows, summary, outdir):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    colours = {"midpoint": "tab:blue", "vertex": "tab:red", "periodic": "tab:green"}
    for case in ALL_CASES:
        fig, ax = plt.subplots(figsize=(7, 4.8))
        for clamp in clamps_of(case):
            colour = colours[clamp]
            sub = [r for r in rows if r["case"] == case and r["clamp"] == clamp]
            order = next(s["order"] for s in summary
                         if s["case"] == case and s["clamp"] == clamp)
            sizes = sorted({r["edges"] for r in sub})
            ax.scatter([r["time_s"] for r in sub], [r["error"] for r in sub],
                       s=[12 + 12 * sizes.index(r["edges"]) for r in sub], c=colour,
                       alpha=0.45,
                       label=(f"periodic cell (order {order:.2f})" if clamp == "periodic"
                              else f"clamp at {clamp} (order {order:.2f})"))
            front = pareto_front([(r["time_s"], r["error"]) for r in sub])
            ax.step([sub[i]["time_s"] for i in front], [sub[i]["error"] for i in front],
                    where="post", color=colour)
            for i in front:
                ax.annotate(f"{sub[i]['edges']}/{sub[i]['gtol']:g}",
                            (sub[i]["time_s"], sub[i]["error"]), fontsize=6,
                            color=colour)
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlabel("solve time [s] (median)")
        ax.set_ylabel("relative error of E1 against the frame closed form"
                      if case == "honeycomb_cell" else "tip error / L against the closed form")
        ax.set_title(f"{case}: error against time (marker size: edges; "
                     f"labels: edges/gtol on the Pareto front)", fontsize=9)
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=8)
        fig.tight_layout()
        fig.savefig(os.path.join(outdir, f"pareto_{case}.png"), dpi=110)
        plt.close(fig)


if __name__ == "__main__":
    main()
