#!/usr/bin/env python3
"""The conformance suite of the preconditioners on 2 ranks, driven by the registries
(c_api/include/rodnet_registry.h, rows printed by the test program registry_rows):
every solver kind that takes a preconditioner and solves distributed networks
(tr-krylov, nox) with every preconditioner of the registry, `rodnet solve` under
`mpirun -np NP` on the scene, against `rodnet solve --solver tr-minres` on one
process:

- a preconditioner for one rank only (RN_PC_ONE_RANK: factor) is refused with exit
  status 4 and one message naming "one rank", nothing written;
- every other one converges (exit status 0), RESULT.json names the preconditioner
  that ran (an alias: the row it stands for), and its energy equals tr-minres's to
  TOL relative (default 1e-9, as shim_dd_solve on one rank).

    check_conformance_mpi.py REGISTRY_ROWS RODNET MPIEXEC NP SCENE WORKDIR [TOL]
"""
import json
import os
import re
import subprocess
import sys

CAN_DISTRIBUTE = 1 << 0  # RN_SOLVER_CAN_DISTRIBUTE
TAKES_PRECONDITIONER = 1 << 1  # RN_SOLVER_TAKES_PRECONDITIONER
ONE_RANK = 1 << 0  # RN_PC_ONE_RANK
FAILS = []


def run(cmd):
    print("running:", " ".join(cmd), flush=True)
    return subprocess.run(cmd, capture_output=True, text=True, timeout=1200)


def main():
    reg, rodnet, mpiexec, np, scene, work = sys.argv[1:7]
    tol = float(sys.argv[7]) if len(sys.argv) > 7 else 1e-9
    os.makedirs(work, exist_ok=True)
    rows = run([reg]).stdout
    solvers = [(n, int(f)) for n, f in re.findall(r"^solver (\S+) (\d+)$", rows, re.M)]
    precs = [(n, int(f)) for n, f in
             re.findall(r"^preconditioner (\S+) (\d+)$", rows, re.M)]
    resolves = dict(re.findall(r"^resolves (\S+) (\S+)$", rows, re.M))
    if not solvers or not precs:
        sys.exit("registry_rows printed no rows:\n" + rows)
    ref = os.path.join(work, "tr-minres.json")
    p = run([rodnet, "solve", scene, "-o", ref, "--solver", "tr-minres", "-q"])
    if p.returncode != 0:
        sys.exit("tr-minres: exit %d\n%s%s" % (p.returncode, p.stdout, p.stderr))
    with open(ref) as f:
        E_ref = json.load(f)["energy"]
    print("tr-minres on one process: E = %.12e" % E_ref)
    runs = 0
    for kind, kf in solvers:
        if not (kf & TAKES_PRECONDITIONER and kf & CAN_DISTRIBUTE):
            continue
        for pc, pf in precs:
            out = os.path.join(work, "%s-%s.json" % (kind, pc))
            if os.path.exists(out):
                os.remove(out)
            p = run([mpiexec, "-q", "-n", np, rodnet, "solve", scene, "-o", out,
                     "--solver", kind, "--preconditioner", pc, "-q"])
            runs += 1
            what = "%s %s on %s ranks" % (kind, pc, np)
            if pf & ONE_RANK:
                ok = p.returncode == 4 and "one rank" in p.stderr and \
                    not os.path.exists(out)
                print("%s: exit %d, %s" % (what, p.returncode, p.stderr.strip()))
                if not ok:
                    FAILS.append("%s: expected exit 4 naming 'one rank', nothing "
                                 "written; got %d\n%s" % (what, p.returncode, p.stderr))
                continue
            if p.returncode != 0:
                FAILS.append("%s: exit %d\n%s%s" % (what, p.returncode, p.stdout,
                                                    p.stderr))
                continue
            with open(out) as f:
                r = json.load(f)
            E, used = r["energy"], r.get("preconditioner")
            rel = abs(E - E_ref) / abs(E_ref)
            print("%s: %s, preconditioner %s, %d iterations, E = %.12e, |dE|/|E| = "
                  "%.1e" % (what, r["status"], used, r["iterations"], E, rel))
            if used != resolves.get(pc, pc):
                FAILS.append("%s: ran preconditioner %s, expected %s" %
                             (what, used, resolves.get(pc, pc)))
            if not rel <= tol:
                FAILS.append("%s: energy %.12e, tr-minres's %.12e (relative %.1e > %g)"
                             % (what, E, E_ref, rel, tol))
    for f in FAILS:
        print("FAIL: " + f)
    print("check_conformance_mpi: %d runs: %s" % (runs, "FAILED" if FAILS else "ok"))
    sys.exit(1 if FAILS else 0)


main()
