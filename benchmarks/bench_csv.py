"""Shared by the plot scripts of benchmarks/: reading a benchmark CSV (the common
columns of bench_util.h's rn_bench_csv_header) and the provenance title."""
import csv
import os
import re
import subprocess
import sys
import time

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


def provenance(rodnet, commit_override=None):
    """commit, compiler, flags from <build>/benchmarks/bench_config.h of the build
    that holds the rodnet binary (commit_override replaces the commit)."""
    prov = {"commit": "unknown", "compiler": "unknown", "flags": ""}
    cfg = os.path.join(os.path.dirname(os.path.abspath(rodnet)), "benchmarks",
                       "bench_config.h")
    try:
        text = open(cfg).read()
        for key, name in (("commit", "RN_BENCH_COMMIT"), ("compiler", "RN_BENCH_COMPILER"),
                          ("flags", "RN_BENCH_FLAGS")):
            m = re.search(r'#define %s "(.*)"' % name, text)
            if m:
                prov[key] = m.group(1).replace('\\"', '"')
    except OSError:
        pass
    if commit_override:
        prov["commit"] = commit_override
    return prov


def plot_rows(doc, bench, prog):
    """The command line of a plot script (CSV, -o PNG; doc its help) and the CSV's
    rows of bench: (rows, output path); exits with "<prog>: ..." if there are none."""
    import argparse
    ap = argparse.ArgumentParser(description=doc)
    ap.add_argument("csv")
    ap.add_argument("-o", "--output", required=True)
    a = ap.parse_args()
    rows = [r for r in read_rows(a.csv, prog) if r["bench"] == bench]
    if not rows:
        sys.exit(f"{prog}: {a.csv} has no bench_{bench} rows")
    return rows, a.output


def save(fig, output, dpi=120):
    """fig to output through a temporary name (a complete PNG or none)."""
    tmp = output + ".tmp.png"
    fig.savefig(tmp, dpi=dpi)
    os.replace(tmp, output)


def run_once(cmd, env=None):
    """Wall seconds, exit status and the peak resident MB of the largest process of
    one run of cmd, output discarded (RUSAGE_CHILDREN of an MPI launcher covers its
    ranks)."""
    t0 = time.perf_counter()
    p = subprocess.Popen(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL,
                         env=env)
    _, status, ru = os.wait4(p.pid, 0)
    return time.perf_counter() - t0, os.waitstatus_to_exitcode(status), ru.ru_maxrss / 1024


def mpi_env():
    """The environment for mpiexec as root and with more ranks than cores."""
    return dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1",
                OMPI_MCA_rmaps_base_oversubscribe="1")


def pick_cases(arg, known, prog):
    """The case names of a comma list (--cases); exits naming an unknown one."""
    names = [c for c in arg.split(",") if c]
    for c in names:
        if c not in known:
            sys.exit("%s: unknown case '%s' (known: %s)" % (prog, c, ", ".join(known)))
    return names
