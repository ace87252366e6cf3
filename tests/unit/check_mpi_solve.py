#!/usr/bin/env python3
"""Solve one scene with `rodnet solve` on 1 rank and under `mpirun -np N`, then
compare the two RESULT.json files (issue 7, the `mpi` tests):

    check_mpi_solve.py --rodnet RODNET --mpiexec MPIEXEC --np N --scene S.json
                       --solver NAME --out DIR [--max-share 0.55]
                       [--args "common options"] [--args1 "one rank's"]
                       [--argsn "N ranks' options"] [--same-iterations]
                       [--same-path-above G]

- both runs exit with status 0 (converged);
- energy and every vertex position agree to 1e-10 relative (positions relative to
  the largest coordinate); with --same-iterations (the same preconditioner on both,
  e.g. gathered) the Newton iterations and load steps are equal, otherwise they are
  printed;
- with --same-path-above G (a scene whose trust region meets the energy's round-off
  before it converges, where its decisions are noise and the paths may part): both
  runs print their progress, and every iteration line of the one-rank run whose
  gradient norm is at least G (at least two lines) has its twin in the N-rank run:
  the same iteration number, trust radius and Krylov iterations (as printed), the
  energy to 1e-10 relative, the gradient norm to 1e-3 (printed to 4 digits);
- "stability": both checked or neither; verified_minimum and zero_modes equal,
  the lowest eigenvalues within 1e-6 relative (+ 1e-12 scale), scale to 1e-12
  (one rank: the Cholesky check by default; N ranks: LOBPCG on the parts, or the
  Cholesky check on rank 0's gathered state where LOBPCG gave no eigenpair);
- standard output holds rodnet's summary only (no solver library's messages);
- "partition": one rank has "ranks": 1 with one-element lists equal to the
  network's free DOFs; N ranks have N-element lists whose sums are the one-rank
  totals, and with more than one rod per rank no rank owns more than max-share of
  the DOFs or of the stencils (max-share 1 turns that off, e.g. for a single rod).
Prints what it compares; exits non-zero on the first difference."""
import argparse
import json
import os
import subprocess
import sys


def run(cmd, progress=None):
    """Runs cmd; returns its exit status.  progress: a list that receives the
    progress lines of stderr as (iteration, energy, gnorm, radius, krylov) with
    radius and krylov as printed."""
    print("running:", " ".join(cmd), flush=True)
    p = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                       timeout=1200)
    sys.stdout.write(p.stdout)
    if progress is None:
        sys.stdout.write(p.stderr)
    # the library prints nothing: standard output is rodnet's summary only (its lines
    # start with "rodnet " or are indented), no solver library's messages
    for line in p.stdout.splitlines():
        if line and not line.startswith(("rodnet ", " ")):
            fail("a line on standard output that is not rodnet's summary: %r" % line)
    if progress is not None:
        for line in p.stderr.splitlines():
            f = line.split()
            if len(f) == 7 and f[0].isdigit():
                progress.append((int(f[0]), float(f[1]), float(f[2]), f[3], f[4]))
            else:
                sys.stdout.write(line + "\n")
    return p.returncode


def compare_paths(one, many, gmin, np):
    """The progress lines of one rank with |g| >= gmin against the N-rank run's."""
    n = 0
    for k, a in enumerate(one):
        if a[2] < gmin:
            break
        if k >= len(many):
            fail("the %d-rank run stopped after %d progress lines" % (np, len(many)))
        b = many[k]
        print("iteration %d: energy %.17g vs %.17g, |g| %.4g vs %.4g, radius %s vs %s, "
              "krylov %s vs %s" % (a[0], a[1], b[1], a[2], b[2], a[3], b[3], a[4], b[4]))
        if (a[0] != b[0] or a[3] != b[3] or a[4] != b[4] or
                rel(a[1], b[1], a[1]) > 1e-10 or rel(a[2], b[2], a[2]) > 1e-3):
            fail("the paths part at progress line %d (iteration %d)" % (k, a[0]))
        n += 1
    print("same path over %d progress lines (|g| >= %g on one rank)" % (n, gmin))
    if n < 2:
        fail("fewer than 2 progress lines compared")


def fail(msg):
    print("check_mpi_solve: FAIL:", msg)
    sys.exit(1)


def rel(a, b, scale):
    return abs(a - b) / max(abs(scale), 1e-300)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--rodnet", required=True)
    ap.add_argument("--mpiexec", required=True)
    ap.add_argument("--np", type=int, default=2)
    ap.add_argument("--scene", required=True)
    ap.add_argument("--solver", required=True)
    ap.add_argument("--out", required=True)
    ap.add_argument("--max-share", type=float, default=0.55)
    ap.add_argument("--args", default="")
    ap.add_argument("--args1", default="")
    ap.add_argument("--argsn", default="")
    ap.add_argument("--same-iterations", action="store_true")
    ap.add_argument("--same-path-above", type=float, default=None)
    ap.add_argument("--label", default="")
    a = ap.parse_args()
    os.makedirs(a.out, exist_ok=True)
    base = os.path.splitext(os.path.basename(a.scene))[0] + a.label
    r1 = os.path.join(a.out, base + ".np1.json")
    rn = os.path.join(a.out, base + ".np%d.json" % a.np)
    path = a.same_path_above is not None
    args = (["solve", a.scene, "--solver", a.solver] + ([] if path else ["-q"]) +
            a.args.split())
    prog1, progn = ([], []) if path else (None, None)
    if run([a.rodnet] + args + a.args1.split() + ["-o", r1], prog1) != 0:
        fail("one rank did not converge")
    if run([a.mpiexec, "-q", "-n", str(a.np), a.rodnet] + args + a.argsn.split() +
           ["-o", rn], progn) != 0:
        fail("%d ranks did not converge" % a.np)
    if path:
        compare_paths(prog1, progn, a.same_path_above, a.np)
    one, many = json.load(open(r1)), json.load(open(rn))
    e = rel(many["energy"], one["energy"], one["energy"])
    print("energy %.17g vs %.17g (rel %.3g)" % (many["energy"], one["energy"], e))
    if e > 1e-10:
        fail("energies differ")
    scale = max(abs(c) for r in one["rods"] for v in r["vertices"] for c in v)
    worst = 0.0
    for ra, rb in zip(one["rods"], many["rods"]):
        for va, vb in zip(ra["vertices"], rb["vertices"]):
            worst = max(worst, max(rel(x, y, scale) for x, y in zip(va, vb)))
    print("positions: worst difference %.3g of the largest coordinate" % worst)
    if len(one["rods"]) != len(many["rods"]) or worst > 1e-10:
        fail("positions differ")
    print("Newton iterations %d (one rank) and %d (%d ranks), load steps %d and %d" %
          (one["iterations"], many["iterations"], a.np, one["load_steps"],
           many["load_steps"]))
    keys = ("iterations", "load_steps", "num_dofs") if a.same_iterations else ("num_dofs",)
    for k in keys:
        if one[k] != many[k]:
            fail("%s: %s vs %s" % (k, one[k], many[k]))
    s1, sn = one["stability"], many["stability"]
    print("stability: one rank %s, %d ranks %s" % (s1, a.np, sn))
    if s1["checked"] != sn["checked"]:
        fail("stability checked on one side only")
    if s1["checked"]:
        for k in ("verified_minimum", "zero_modes"):
            if s1[k] != sn[k]:
                fail("stability %s: %s vs %s" % (k, s1[k], sn[k]))
        d = abs(s1["lowest_eigenvalue"] - sn["lowest_eigenvalue"])
        if d > 1e-6 * abs(s1["lowest_eigenvalue"]) + 1e-12 * s1["scale"]:
            fail("lowest eigenvalues differ by %.3g" % d)
        if abs(s1["scale"] - sn["scale"]) > 1e-12 * s1["scale"]:
            fail("stability scales differ")
    p1, pn = one["partition"], many["partition"]
    if p1["ranks"] != 1 or p1["owned_dofs"] != [one["num_dofs"]]:
        fail("one-rank partition block %s" % p1)
    if pn["ranks"] != a.np or len(pn["owned_dofs"]) != a.np:
        fail("partition block %s" % pn)
    for k in ("owned_dofs", "owned_stencils"):
        if sum(pn[k]) != sum(p1[k]):
            fail("%s sum %d vs %d" % (k, sum(pn[k]), sum(p1[k])))
        share = max(pn[k]) / float(sum(pn[k]))
        print("%s per rank %s (largest share %.3f)" % (k, pn[k], share))
        if len(one["rods"]) > a.np and share > a.max_share:
            fail("a rank owns %.3f of the %s" % (share, k))
    print("check_mpi_solve: ok")


if __name__ == "__main__":
    main()
