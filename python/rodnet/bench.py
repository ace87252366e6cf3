"""rodnet bench's problems from Python: objectives with reference answers for
anyone's optimiser, and rows in the format of `rodnet bench`'s runs.csv
(docs/benchmarking.md), so that a Python optimiser's runs sit beside rodnet's
solvers in the same performance profiles (benchmarks/bench_profiles.py).

    for p in rodnet.bench.problems("quick"):
        o = p.objective()
        x = my_optimiser(o.value, o.gradient, o.hessp, o.x0)
        print(p.name, p.error_of(o, x))
"""
import csv
import datetime
import functools
import json
import math
import os
import platform
import socket
import subprocess

import numpy as np

from . import _core
from ._ffi import Error

COLUMNS = ["problem", "class", "solver", "converged", "verified_minimum", "iterations",
           "gradients", "hvps", "krylov_iterations", "gradient_norm", "error", "time_s",
           "time_min_s", "repeats", "stop", "energy", "lowest_eigenvalue", "energy_evals",
           "factorizations", "load_steps", "dofs", "suite", "commit", "compiler", "flags",
           "cpu", "cores", "blas", "host", "date"]


def default_manifest():
    """The suite manifest: $RODNET_BENCH_SUITE, else the source tree's
    benchmarks/suite/suite.json that the package was built from."""
    if os.environ.get("RODNET_BENCH_SUITE"):
        return os.environ["RODNET_BENCH_SUITE"]
    try:
        from . import _config
        return _config.bench_suite
    except (ImportError, AttributeError):
        raise Error("rodnet.bench: no suite manifest known: set RODNET_BENCH_SUITE or "
                    "pass manifest=") from None


def _vertices(model):
    return np.concatenate([model.positions(r) for r in range(model.num_rods)])


class Problem:
    """One problem of the suite: its scene, class and stored reference answer."""

    def __init__(self, entry, base, suite):
        self.name = entry["name"]
        self.klass = entry.get("class", "")
        self.scene_path = os.path.normpath(os.path.join(base, entry["scene"]))
        self.suite = suite
        self._start = None  # the start's vertices, read once by error()
        self.reference = None
        if entry.get("reference"):
            ref = os.path.normpath(os.path.join(base, entry["reference"]))
            with open(ref) as f:
                self.reference = np.array(json.load(f)["vertices"], dtype=np.float64)

    def load(self):
        """A fresh Scene of the problem (at its start)."""
        return _core.load_scene(self.scene_path)

    def objective(self):
        """The energy of a fresh scene over its free DOFs (rodnet.Objective; its
        model is the scene)."""
        return self.load().objective()

    def error(self, model, start=None):
        """The benchmark's error of the model's current state: the largest vertex
        distance from the reference over the reference's largest displacement
        from the start (NaN without a reference or with other vertex counts)."""
        if self.reference is None:
            return math.nan
        x = _vertices(model)
        if start is None:
            if self._start is None:
                self._start = _vertices(self.load())
            start = self._start
        x0 = start
        if x.shape != self.reference.shape:
            return math.nan
        err = np.max(np.linalg.norm(x - self.reference, axis=1))
        disp = np.max(np.linalg.norm(self.reference - x0, axis=1))
        return err / disp if disp > 0 else err

    def error_of(self, objective, x):
        """error() of the state x of objective (installs x as the model's state)."""
        objective.model.set_dofs(x)
        return self.error(objective.model)

    def __repr__(self):
        return "<rodnet.bench.Problem %s (%s)>" % (self.name, self.klass)


def problems(suite="quick", manifest=None):
    """The problems of a suite ("smoke", "quick" or "full") of the manifest."""
    if suite not in ("smoke", "quick", "full"):
        raise Error("suite %r: expected smoke, quick or full" % (suite,))
    path = manifest or default_manifest()
    try:
        with open(path) as f:
            m = json.load(f)
    except (OSError, ValueError) as e:
        raise Error("%s: cannot read the suite manifest (%s)" % (path, e)) from None
    base = os.path.dirname(os.path.abspath(path))
    return [Problem(e, base, suite) for e in m.get("problems", [])
            if suite in e.get("suites", [])]


@functools.lru_cache(maxsize=None)
def provenance():
    """The machine and build columns of a row (commit, compiler, flags, cpu, cores,
    blas, host, date) for a run from Python; found once per process (the date is
    the first call's)."""
    commit = ""
    try:
        from . import _config
        src = _config.source_dir
        commit = subprocess.run(["git", "-C", src, "describe", "--always", "--dirty",
                                 "--abbrev=12"], capture_output=True, text=True,
                                timeout=10).stdout.strip()
    except Exception:
        pass
    cpu = ""
    try:
        with open("/proc/cpuinfo") as f:
            for line in f:
                if line.startswith("model name"):
                    cpu = line.split(":", 1)[1].strip()
                    break
    except OSError:
        pass
    try:
        import scipy
        sv = " scipy " + scipy.__version__
    except ImportError:
        sv = ""
    return {"commit": commit, "compiler": "CPython %s numpy %s%s" % (
                platform.python_version(), np.__version__, sv),
            "flags": "", "cpu": cpu, "cores": os.cpu_count() or 1, "blas": "",
            "host": socket.gethostname(),
            "date": datetime.datetime.now(datetime.timezone.utc).strftime(
                "%Y-%m-%dT%H:%M:%SZ")}


def row(problem, solver, **fields):
    """A runs.csv row (dict) of problem solved by solver: fields as the columns
    (converged, verified_minimum, iterations, gradients, hvps, error, time_s, ...);
    the suite and provenance are filled in."""
    r = {"problem": problem.name, "class": problem.klass, "solver": solver,
         "suite": problem.suite}
    r.update(provenance())  # (cached: one git call per process)
    for k, v in fields.items():
        if k not in COLUMNS:
            raise Error("row: unknown column %r (columns: %s)" % (k, ", ".join(COLUMNS)))
        r[k] = v
    r.setdefault("repeats", 1)
    r.setdefault("time_min_s", r.get("time_s", ""))
    return r


def _cell(v):
    if isinstance(v, bool):
        return "1" if v else "0"
    if isinstance(v, float):
        return "%.6e" % v if math.isfinite(v) else ""
    return "" if v is None else str(v)


def write_rows(path, rows, append=True):
    """Write rows to a runs.csv (the header when the file is new or append is
    False), completely or not at all (a temporary file renamed)."""
    old = []
    if append and os.path.exists(path):
        with open(path, newline="") as f:
            old = list(csv.DictReader(f))
    tmp = "%s.tmp.%d" % (path, os.getpid())
    try:
        with open(tmp, "w", newline="") as f:
            w = csv.DictWriter(f, fieldnames=COLUMNS, restval="", extrasaction="ignore")
            w.writeheader()
            for r in old:
                w.writerow(r)
            for r in rows:
                w.writerow({k: _cell(v) for k, v in r.items()})
        os.replace(tmp, path)
    finally:
        if os.path.exists(tmp):
            os.unlink(tmp)
