"""Shared by the plot scripts of benchmarks/: reading a benchmark CSV (the common
columns of bench_util.h's rn_bench_csv_header) and the provenance title."""
import csv
import sys

COMMON = ("commit", "compiler", "bench", "case", "size", "median", "min")


def read_rows(path, prog):
    """The rows of the CSV at path as dicts; exits with "<prog>: ..." if it has no
    data rows or lacks one of the common columns."""
    with open(path, newline="") as f:
        rows = list(csv.DictReader(f))
    if not rows:
        sys.exit(f"{prog}: {path} has no data rows")
    for key in COMMON:
        if key not in rows[0]:
            sys.exit(f"{prog}: {path} lacks the column '{key}'")
    return rows


def title(rows, what):
    """"rodnet <what> - commit ..., compiler, ranks" from the first row."""
    r = rows[0]
    return f"rodnet {what} - commit {r['commit']}, {r['compiler']}, {r['ranks']} rank(s)"
