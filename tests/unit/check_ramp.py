#!/usr/bin/env python3
"""Prescribed displacements larger than the edges next to them (issue 10 section 2).

    check_ramp.py RODNET OUTDIR [--mpiexec CMD] [--solvers A,B,...] [--edges N,...]
                  [--cells NX,NY] [--strain S]

`rodnet generate square --cells 10,10 --joint-model rigid --load compress-x:0.015`
moves the face joints by 0.15 while the edges next to them are 1/N long (N = 8: 0.125;
refused before as "degenerate at the initial state"); --cells and --strain change the
lattice and the compression (e.g. 4,4 and 0.05: the face moves by 0.2).  For each edges-per-rod N and
solver the scene is solved (with --mpiexec: on 2 ranks) and the result must be
converged and a verified local minimum, past bar buckling: the bending energy at
least 100 times the stretching energy (a lattice compressed by 1.5 % without
buckling stores its energy in stretch).  A solver written NAME:--no-predictor runs
without the load-step predictor: the face then jumps with the interior held, and
the load step must be split into at least ceil(jump N / (1/2)) sub-steps (no
sub-step may shorten the edge next to the face by more than half its length;
docs/solvers.md, "Prescribed motions of any size").
"""
import math
import argparse
import json
import os
import subprocess
import sys


def run(cmd):
    p = subprocess.run(cmd, capture_output=True, text=True)
    if p.returncode != 0:
        print("check_ramp: FAILED: %s exited %d\n%s%s" % (" ".join(cmd), p.returncode,
                                                          p.stdout, p.stderr))
        sys.exit(1)
    return p


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("rodnet")
    ap.add_argument("outdir")
    ap.add_argument("--mpiexec", default="")
    ap.add_argument("--solvers", default="tr-minres")
    ap.add_argument("--edges", default="8")
    ap.add_argument("--cells", default="10,10")
    ap.add_argument("--strain", default="0.015")
    a = ap.parse_args()
    os.makedirs(a.outdir, exist_ok=True)
    bad = 0
    for n in a.edges.split(","):
        scene = os.path.join(a.outdir, "square_compress_%s.json" % n)
        run([a.rodnet, "generate", "square", "--cells", a.cells, "--joint-model", "rigid",
             "--edges-per-rod", n, "--load", "compress-x:" + a.strain, "-o", scene])
        for spec in a.solvers.split(","):
            solver, _, flag = spec.partition(":")
            out = os.path.join(a.outdir, "square_compress_%s_%s%s%s.json" %
                               (n, solver, flag.replace("-", "_"),
                                "_mpi" if a.mpiexec else ""))
            cmd = [a.rodnet, "solve", scene, "-o", out, "--quiet", "--solver", solver]
            if flag:
                cmd.append(flag)
            if a.mpiexec:
                cmd = a.mpiexec.split() + cmd
            run(cmd)
            r = json.load(open(out))
            st, et = r["stability"], r["energy_terms"]
            # the face moves by strain * cells (unit cells) against edges 1/n long
            jump = float(a.strain) * int(a.cells.split(",")[0])
            need = math.ceil(jump * int(n) / 0.5 - 1e-9) if flag == "--no-predictor" else 1
            ok = (r["converged"] and st.get("verified_minimum") is True and
                  et["bend"] >= 100.0 * et["stretch"] and r["load_steps"] >= need)
            print("edges/rod %s, %s%s: converged %s, verified_minimum %s, lowest "
                  "eigenvalue %.3e, bend %.4e, stretch %.4e, %d load steps (at least %d), "
                  "%d iterations"
                  % (n, spec, " (2 ranks)" if a.mpiexec else "", r["converged"],
                     st.get("verified_minimum"), st.get("lowest_eigenvalue", float("nan")),
                     et["bend"], et["stretch"], r["load_steps"], need, r["iterations"]))
            if not ok:
                print("check_ramp: FAILED for edges/rod %s, %s" % (n, solver))
                bad += 1
    if bad:
        sys.exit(1)
    print("check_ramp: passed")


if __name__ == "__main__":
    main()
