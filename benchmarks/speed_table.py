#!/usr/bin/env python3
"""speed_table.py - assemble issue 8's table from the CSVs of speed_table.sh.

    python3 benchmarks/speed_table.py --dir TMP --commit C --out speed_table.csv
    python3 benchmarks/speed_table.py --plot speed_table.csv    # the PNG only

Reads TMP/{kernels,cantilever,arch4,arch8,startup,io}.csv and TMP/hc20-*.json (RESULT.json
of `rodnet solve`), writes one CSV row per measurement (the common benchmark
columns plus unit and target), prints the table as Markdown on stdout and draws
speed_table.png beside the CSV: each row's median over its target (log scale; below
1 is met)."""
import argparse
import csv
import glob
import json
import os
import statistics


def rows(path):
    if not os.path.exists(path):
        return []
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def plot(csv_path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    rs = [r for r in rows(csv_path) if r["target"].replace(".", "", 1).isdigit()]
    labels = ["%s (%s)" % (r["what"], r["size"]) for r in rs]
    ratio = [float(r["median"]) / float(r["target"]) for r in rs]
    fig, ax = plt.subplots(figsize=(9, 0.35 * len(rs) + 1.2))
    ax.barh(range(len(rs)), ratio, color=["tab:green" if q <= 1 else "tab:red"
                                          for q in ratio])
    ax.axvline(1.0, color="k", lw=1)
    ax.set_xscale("log")
    ax.set_yticks(range(len(rs)))
    ax.set_yticklabels(labels, fontsize=7)
    ax.invert_yaxis()
    ax.set_xlabel("median / target (below 1: met)")
    c = rs[0]["commit"] if rs else ""
    ax.set_title("issue 8's table, one run (commit %s)" % c, fontsize=9)
    fig.tight_layout()
    png = os.path.splitext(csv_path)[0] + ".png"
    fig.savefig(png + ".tmp.png", dpi=110)
    os.replace(png + ".tmp.png", png)


def measurements(folder):
    """The table's rows from the CSVs and JSONs in folder: (label, case, size, repeats,
    median, min, unit, target, the CSV row it came from), and the first kernels row
    (the provenance of rows that have none)."""
    out = []  # (label, case, size, repeats, median, min, unit, target, meta)

    def add(label, case, size, reps, med, mn, unit, target, meta):
        out.append((label, case, size, reps, med, mn, unit, target, meta))

    meta = None
    for r in rows(os.path.join(folder, "kernels.csv")):
        meta = meta or r
        names = {"energy": ("energy per vertex", 15),
                 "gradient": ("energy + gradient per vertex", 50),
                 "hvp": ("Hessian-vector product per vertex", 100),
                 "hessian_values": ("Hessian block values per vertex (CSR)", 300)}
        if r["op"] in names:
            lab, tgt = names[r["op"]]
            add(lab, "kernels:" + r["op"], int(r["size"]), int(r["repeats"]),
                1e9 * float(r["median_per_vertex"]), 1e9 * float(r["min_per_vertex"]),
                "ns", tgt, r)
    for r in rows(os.path.join(folder, "cantilever.csv")):
        n = int(r["size"])
        add("cantilever alpha = 5: Newton iterations", "cantilever:newton", n,
            int(r["repeats"]), float(r["newton_iterations"]),
            float(r["newton_iterations"]), "iterations", 12, r)
        add("cantilever alpha = 5: solve time (time_s)", "cantilever:time", n,
            int(r["repeats"]), 1e3 * float(r["median"]), 1e3 * float(r["min"]), "ms",
            7 if n == 401 else 58, r)
    for r in rows(os.path.join(folder, "startup.csv")):
        if r["case"] == "solve":
            add("rodnet solve whole process minus time_s", "startup", int(r["size"]),
                int(r["repeats"]), 1e3 * float(r["median"]), 1e3 * float(r["min"]),
                "ms", 30, r)
    hc = sorted(glob.glob(os.path.join(folder, "hc20-*.json")))
    if hc:
        res = [json.load(open(p)) for p in hc]
        t = [d["time_s"] for d in res]
        its = res[0]["iterations"]
        add("honeycomb 20x20 compress-y:5e-2: Newton iterations", "honeycomb20:newton",
            res[0]["num_vertices"], len(res), its, its, "iterations", 40, meta)
        add("honeycomb 20x20 compress-y:5e-2: time (time_s)", "honeycomb20:time",
            res[0]["num_vertices"], len(res), statistics.median(t), min(t), "s", 3, meta)
    for r in rows(os.path.join(folder, "arch4.csv")) + rows(os.path.join(folder, "arch8.csv")):
        P = float(r["load"])
        add("arch 215 deg, P = %g EI/R^2: Newton iterations" % P, "arch:P%g" % P,
            int(r["size"]), int(r["repeats"]), float(r["newton_iterations"]),
            float(r["newton_iterations"]), "iterations", 15 if P == 4 else 40, r)
    for r in rows(os.path.join(folder, "io.csv")):
        if r["case"] in ("read", "write_json", "write_vtk", "generate"):
            add("%s at %s vertices" % (r["case"], r["size"]), "io:" + r["case"],
                int(r["size"]), int(r["repeats"]), float(r["median"]), float(r["min"]),
                "s", "a few", r)
    return out, meta


def write_csv(out, meta, path, commit):
    """The rows as CSV at path (written to path.tmp, then renamed)."""
    m = meta or {}
    with open(path + ".tmp", "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["commit", "compiler", "flags", "ranks", "bench", "case", "size",
                    "repeats", "median", "min", "unit", "target", "what"])
        for lab, case, size, reps, med, mn, unit, tgt, r in out:
            r = r or m
            w.writerow([commit or r.get("commit", ""), r.get("compiler", ""),
                        r.get("flags", ""), 1, "speed_table", case, size, reps,
                        "%.6g" % med, "%.6g" % mn, unit, tgt, lab])
    os.replace(path + ".tmp", path)


def print_table(out):
    """The rows as a Markdown table on stdout."""
    print("| measurement | size | median | min | target |")
    print("|---|---|---|---|---|")
    for lab, case, size, reps, med, mn, unit, tgt, r in out:
        print("| %s | %s | %.4g %s | %.4g %s | %s %s |" % (lab, size, med, unit, mn, unit,
                                                       tgt, unit))


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--dir")
    ap.add_argument("--commit", default="")
    ap.add_argument("--out")
    ap.add_argument("--plot", help="draw the PNG of an existing speed_table.csv")
    a = ap.parse_args()
    if a.plot:
        plot(a.plot)
        return
    if not a.dir or not a.out:
        ap.error("--dir and --out are required (or --plot CSV)")
    out, meta = measurements(a.dir)
    write_csv(out, meta, a.out, a.commit)
    plot(a.out)
    print_table(out)


if __name__ == "__main__":
    main()
