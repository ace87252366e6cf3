#!/usr/bin/env python3
"""Performance and data profiles of a `rodnet bench` run (docs/benchmarking.md).

    bench_profiles.py DIR/runs.csv [more.csv ...] -o DIR

Writes DIR/profile_time.png and DIR/profile_hvp.png (Dolan-More performance
profiles: the fraction of problems a solver solves within a factor tau of the best
solver's time / Hessian-vector products), DIR/data_profile.png (More-Wild data
profile: the fraction solved within a budget of gradient + HVP evaluations) and
DIR/profile_summary.csv (per solver, and per problem class the best solver), and
prints the summary.

A run counts as solved when it converged, its state is a verified minimum and its
error against the reference answer (where there is one) is at most --max-error
(default 1e-3, relative to the reference's displacement).  Rows of several CSV
files (bench_merge.py) are profiled per machine: a problem is (problem, host).
"""
import argparse
import csv
import math
import os
import sys


def read_rows(paths):
    rows = []
    for path in paths:
        with open(path, newline="") as f:
            for r in csv.DictReader(f):
                rows.append(r)
    if not rows:
        sys.exit(f"bench_profiles.py: no rows in {', '.join(paths)}")
    for need in ("problem", "solver", "converged", "verified_minimum", "time_s", "hvps"):
        if need not in rows[0]:
            sys.exit(f"bench_profiles.py: {paths[0]}: no column '{need}'")
    return rows


def solved(r, max_error):
    if r["converged"] != "1" or r.get("verified_minimum", "") != "1":
        return False
    e = r.get("error", "")
    return e == "" or float(e) <= max_error


def costs(rows, column, max_error):
    """{problem key: {solver: cost or inf}} and the solvers in first-seen order."""
    table, solvers = {}, []
    for r in rows:
        key = (r["problem"], r.get("host", ""))
        s = r["solver"]
        if s not in solvers:
            solvers.append(s)
        if column == "evals":
            c = float(r["gradients"]) + float(r["hvps"])
        else:
            c = float(r[column])
        table.setdefault(key, {})[s] = max(c, 1e-12) if solved(r, max_error) else math.inf
    return table, solvers


def ratios(table, solvers):
    """Performance ratios r[p][s] = cost / best cost (inf: not solved)."""
    out = {}
    for p, by in table.items():
        best = min(by.values())
        out[p] = {s: (by.get(s, math.inf) / best if math.isfinite(best) else math.inf)
                  for s in solvers}
    return out


def rho(rat, s, tau):
    n = len(rat)
    return sum(1 for p in rat if rat[p][s] <= tau * (1 + 1e-12)) / n if n else 0.0


def save(fig, path):
    """Write the figure completely or not at all: PATH.tmp.png, then renamed
    (`rodnet bench` removes PATH.tmp.png when a signal ends it)."""
    tmp = path + ".tmp.png"
    fig.savefig(tmp, dpi=110)
    os.replace(tmp, path)


def plot_profile(plt, rat, solvers, title, path):
    finite = [v for p in rat for v in rat[p].values() if math.isfinite(v)]
    tmax = max(2.0, max(finite) * 1.5 if finite else 2.0)
    fig, ax = plt.subplots(figsize=(7, 4.5))
    for s in solvers:
        taus = sorted({1.0, tmax} | {rat[p][s] for p in rat if math.isfinite(rat[p][s])})
        ax.step(taus, [rho(rat, s, t) for t in taus], where="post", label=s)
    ax.set_xscale("log", base=2)
    ax.set_xlim(1, tmax)
    ax.set_ylim(-0.03, 1.03)  # a solver that solves nothing: a visible line at 0
    ax.set_xlabel("tau (factor of the best solver)")
    ax.set_ylabel("fraction of problems solved within tau")
    ax.set_title(title)
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8, loc="lower right")
    fig.tight_layout()
    save(fig, path)
    plt.close(fig)


def plot_data_profile(plt, table, solvers, path):
    fig, ax = plt.subplots(figsize=(7, 4.5))
    n = len(table)
    finite = [c for by in table.values() for c in by.values() if math.isfinite(c)]
    kmax = max(finite) * 1.5 if finite else 10.0
    for s in solvers:
        ks = sorted({1.0, kmax} | {by[s] for by in table.values()
                                   if s in by and math.isfinite(by[s])})
        ax.step(ks, [sum(1 for by in table.values() if by.get(s, math.inf) <= k) / n
                     for k in ks], where="post", label=s)
    ax.set_xscale("log")
    ax.set_ylim(-0.03, 1.03)  # a solver that solves nothing: a visible line at 0
    ax.set_xlabel("budget: gradient + Hessian-vector product evaluations")
    ax.set_ylabel("fraction of problems solved")
    ax.set_title("data profile")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8, loc="lower right")
    fig.tight_layout()
    save(fig, path)
    plt.close(fig)


def summary(rows, max_error):
    tt, solvers = costs(rows, "time_s", max_error)
    th, _ = costs(rows, "hvps", max_error)
    rt, rh = ratios(tt, solvers), ratios(th, solvers)
    out = []
    for s in solvers:
        ok = sum(1 for p in tt if math.isfinite(tt[p].get(s, math.inf)))
        out.append({"scope": "all", "solver": s, "problems": len(tt), "solved": ok,
                    "time_rho1": round(rho(rt, s, 1.0), 3),
                    "time_rho2": round(rho(rt, s, 2.0), 3),
                    "time_rho10": round(rho(rt, s, 10.0), 3),
                    "hvp_rho1": round(rho(rh, s, 1.0), 3),
                    "hvp_rho10": round(rho(rh, s, 10.0), 3)})
    classes = sorted({r.get("class", "") for r in rows})
    for c in classes:
        sub = [r for r in rows if r.get("class", "") == c]
        ct, cs = costs(sub, "time_s", max_error)
        cr = ratios(ct, cs)
        for s in cs:
            solved_n = sum(1 for p in ct if math.isfinite(ct[p].get(s, math.inf)))
            fin = [cr[p][s] for p in cr if math.isfinite(cr[p][s])]
            geo = math.exp(sum(math.log(v) for v in fin) / len(fin)) if fin else math.inf
            out.append({"scope": f"class:{c}", "solver": s, "problems": len(ct),
                        "solved": solved_n, "time_rho1": round(rho(cr, s, 1.0), 3),
                        "time_rho2": round(rho(cr, s, 2.0), 3),
                        "time_rho10": round(rho(cr, s, 10.0), 3),
                        "hvp_rho1": "", "hvp_rho10": "",
                        "geomean_time_ratio_solved": round(geo, 3) if fin else ""})
    return out, rt, rh, tt, solvers


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("csv", nargs="+")
    ap.add_argument("-o", "--outdir", required=True)
    ap.add_argument("--max-error", type=float, default=1e-3)
    a = ap.parse_args()
    rows = read_rows(a.csv)
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    out, rt, rh, tt, solvers = summary(rows, a.max_error)
    os.makedirs(a.outdir, exist_ok=True)
    plot_profile(plt, rt, solvers, "performance profile: solve time",
                 os.path.join(a.outdir, "profile_time.png"))
    plot_profile(plt, rh, solvers, "performance profile: Hessian-vector products",
                 os.path.join(a.outdir, "profile_hvp.png"))
    te, _ = costs(rows, "evals", a.max_error)
    plot_data_profile(plt, te, solvers, os.path.join(a.outdir, "data_profile.png"))
    keys = ["scope", "solver", "problems", "solved", "time_rho1", "time_rho2",
            "time_rho10", "hvp_rho1", "hvp_rho10", "geomean_time_ratio_solved"]
    tmp = os.path.join(a.outdir, "profile_summary.csv.tmp")
    with open(tmp, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=keys, restval="")
        w.writeheader()
        w.writerows(out)
    os.replace(tmp, os.path.join(a.outdir, "profile_summary.csv"))
    print(f"{'scope':<16} {'solver':<17} {'solved':>8} {'rho_t(1)':>8} {'rho_t(10)':>9} "
          f"{'rho_h(1)':>8} {'geo t/best':>10}")
    for r in out:
        print(f"{r['scope']:<16} {r['solver']:<17} {r['solved']:>3}/{r['problems']:<4} "
              f"{r['time_rho1']:>8} {r['time_rho10']:>9} {str(r['hvp_rho1']):>8} "
              f"{str(r.get('geomean_time_ratio_solved', '')):>10}")


if __name__ == "__main__":
    main()
