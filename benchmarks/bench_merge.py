#!/usr/bin/env python3
"""Merge the runs.csv files of several `rodnet bench` runs (other machines, commits,
suites) into one CSV (docs/benchmarking.md).

    bench_merge.py A/runs.csv B/runs.csv ... -o merged.csv

Keeps every column of every file (the union, in first-seen order; a missing field is
empty) and adds "source" (the file a row came from).  Rows that repeat a (problem,
solver, host, commit, date) already taken are dropped, so merging a file twice is
harmless.  The merged file is written completely or not at all;
bench_profiles.py draws profiles from it, per machine (host).
"""
import argparse
import csv
import os
import sys


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("csv", nargs="+")
    ap.add_argument("-o", "--output", required=True)
    a = ap.parse_args()
    fields, rows, seen = [], [], set()
    for path in a.csv:
        with open(path, newline="") as f:
            rd = csv.DictReader(f)
            if not rd.fieldnames or "problem" not in rd.fieldnames \
                    or "solver" not in rd.fieldnames:
                sys.exit(f"bench_merge.py: {path}: not a rodnet bench runs.csv "
                         "(no problem / solver columns)")
            for c in rd.fieldnames:
                if c not in fields:
                    fields.append(c)
            for r in rd:
                key = tuple(r.get(c, "") for c in ("problem", "solver", "host", "commit",
                                                   "date"))
                if key in seen:
                    continue
                seen.add(key)
                r["source"] = path
                rows.append(r)
    fields.append("source")
    tmp = f"{a.output}.tmp.{os.getpid()}"
    with open(tmp, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=fields, restval="")
        w.writeheader()
        w.writerows(rows)
    os.replace(tmp, a.output)
    print(f"bench_merge.py: {len(rows)} rows from {len(a.csv)} files -> {a.output}")


if __name__ == "__main__":
    main()
