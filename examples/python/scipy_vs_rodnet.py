"""scipy.optimize against rodnet's solvers on the problems of `rodnet bench`
(docs/python.md, docs/benchmarking.md).

    PYTHONPATH=build/python /usr/bin/python3 examples/python/scipy_vs_rodnet.py \
        [--suite quick] [-o DIR] [--max-iter N]

Each problem of the suite is solved by rodnet (tr-minres; tr-krylov with the dd
preconditioner) and minimised by scipy's trust-krylov, trust-ncg, Newton-CG
(Hessian-vector products of rodnet's objective) and L-BFGS-B (gradients only),
from the scene's start at its full load (scipy has no load stepping).  A run
solves a problem when it converged to a verified minimum (rodnet's stability
check of the state it returned) within 1e-3 of the stored reference answer.
Writes DIR/runs.csv in the format of `rodnet bench` and draws the performance
profiles with benchmarks/bench_profiles.py (DIR/profile_*.png).
"""
import argparse
import os
import subprocess
import sys
import time

import numpy as np

import rodnet

ap = argparse.ArgumentParser()
ap.add_argument("--suite", default="quick")
ap.add_argument("-o", "--output", default="scipy_vs_rodnet")
ap.add_argument("--max-iter", type=int, default=2000,
                help="iteration limit of the scipy methods (default 2000)")
ap.add_argument("--no-plot", action="store_true")
args = ap.parse_args()
try:
    import scipy.optimize as so
except ImportError:
    sys.exit("scipy_vs_rodnet.py: needs scipy (Debian: python3-scipy)")

os.makedirs(args.output, exist_ok=True)
problems = rodnet.bench.problems(args.suite)
RODNET = [("tr-minres", {}), ("tr-krylov-dd", {"preconditioner": "dd"})]
SCIPY = ["trust-krylov", "trust-ncg", "Newton-CG", "L-BFGS-B"]
rows = []


def finish(p, model, name, converged, fields):
    """Stability and error of the model's state; one row."""
    verified = 0
    if converged:
        try:
            verified = int(model.stability()["verified_minimum"])
        except rodnet.Error:
            verified = 0
    err = p.error(model)
    rows.append(rodnet.bench.row(p, name, converged=int(converged),
                                 verified_minimum=verified, error=err,
                                 dofs=model.num_dofs, **fields))
    solved = converged and verified and np.isfinite(err) and err <= 1e-3
    return solved


table = {}
for p in problems:
    for name, opts in RODNET:
        s = p.load()
        solver = name.split("-dd")[0]
        r = rodnet.solve(s, solver, stability=False, **opts)
        table[(p.name, name)] = (finish(p, s, name, r.converged, dict(
            iterations=r.iterations, gradients=r.gradient_evals, hvps=r.hvp_evals,
            krylov_iterations=r.krylov_iterations, gradient_norm=r.gradient_norm,
            time_s=r.time_s, stop=r.stop_reason, energy=r.energy,
            energy_evals=r.energy_evals, factorizations=r.factorizations,
            load_steps=r.load_steps)), r.time_s)
    for m in SCIPY:
        o = p.objective()
        kw = {} if m == "L-BFGS-B" else {"hessp": o.hessp}
        t0 = time.perf_counter()
        try:
            res = so.minimize(o.value, o.x0, jac=o.gradient, method=m,
                              options={"maxiter": args.max_iter}, **kw)
            x, ok, nit = res.x, bool(res.success), int(res.nit)
            stop = "gradient" if ok else ("max_iterations" if nit >= args.max_iter
                                          else "failed")
        except rodnet.Error as e:  # a degenerate point the method did not reject
            x, ok, nit, stop = o.x0, False, 0, "error"
        dt = time.perf_counter() - t0
        o.model.set_dofs(x)
        try:
            E, g = o.value_and_gradient(x)
            gn = float(np.linalg.norm(g))
        except rodnet.Error:
            E, gn = float("nan"), float("nan")
        ev = o.evaluations
        table[(p.name, m)] = (finish(p, o.model, m, ok, dict(
            iterations=nit, gradients=ev["gradient"], hvps=ev["hessp"],
            krylov_iterations=0, gradient_norm=gn, time_s=dt, stop=stop, energy=E,
            energy_evals=ev["value"], factorizations=0, load_steps=1)), dt)
    print("%-22s %s" % (p.name, "  ".join(
        "%s %s %.3gs" % (n, "ok" if table[(p.name, n)][0] else "--", table[(p.name, n)][1])
        for n in [x for x, _ in RODNET] + SCIPY)), flush=True)

csv_path = os.path.join(args.output, "runs.csv")
rodnet.bench.write_rows(csv_path, rows, append=False)
print("wrote", csv_path)
names = [x for x, _ in RODNET] + SCIPY
print("\n%-14s %8s %14s" % ("solver", "solved", "median time s"))
for n in names:
    ok = [table[(p.name, n)] for p in problems]
    t = [v[1] for v in ok if v[0]]
    print("%-14s %5d/%-3d %14s" % (n, sum(v[0] for v in ok), len(ok),
                                   "%.3g" % np.median(t) if t else "-"))
if not args.no_plot:
    here = os.path.dirname(os.path.abspath(__file__))
    script = os.path.join(here, "..", "..", "benchmarks", "bench_profiles.py")
    subprocess.run([sys.executable, script, csv_path, "-o", args.output], check=True)
