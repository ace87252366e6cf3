"""Helpers of the scripts that run `rodnet` on one process and under mpirun
(check_periodic_mpi.py, check_path_mpi.py): the checks they record, a run with
its exit status checked, the relative difference of two vectors, the mpirun
command."""
import json
import os
import shutil
import subprocess

FAILED = []


def check(ok, what):
    print(("ok   " if ok else "FAIL ") + what)
    if not ok:
        FAILED.append(what)


def run(cmd, name, want=0):
    r = subprocess.run(cmd, capture_output=True, text=True, timeout=600)
    print(f"--- {name}: exit {r.returncode}")
    if r.returncode != want:
        print(r.stdout[-3000:])
        print(r.stderr[-3000:])
    check(r.returncode == want, f"{name}: exit status {want}")
    return r


def rel(a, b):
    """max |a - b| over max |b| (1 if b is zero)."""
    a = [float(v) for v in a]
    b = [float(v) for v in b]
    scale = max(abs(v) for v in b) or 1.0
    return max(abs(x - y) for x, y in zip(a, b)) / scale


def setup(argv):
    """RODNET MPIEXEC NP DIR: rodnet, NP, DIR (made empty), the mpirun command."""
    rodnet, mpiexec, np_, d = argv[1], argv[2], int(argv[3]), argv[4]
    shutil.rmtree(d, ignore_errors=True)
    os.makedirs(d)
    return rodnet, np_, d, mpi_command(mpiexec, np_)


def load_all(paths):
    """The JSON files, or None if one is missing."""
    if not all(os.path.exists(p) for p in paths):
        return None
    return [json.load(open(p)) for p in paths]


def mpi_command(mpiexec, np_):
    mpi = [mpiexec, "-n", str(np_)]
    if os.geteuid() == 0:
        mpi.append("--allow-run-as-root")
    if np_ > (os.cpu_count() or 1):
        mpi.append("--oversubscribe")
    return mpi


def finish():
    print("FAILED: " + "; ".join(FAILED) if FAILED else "all passed")
    return 1 if FAILED else 0
