#!/usr/bin/env python3
"""Export rodnet's optimiser benchmark suite for other codes (docs/benchmarking.md).

    bench_export.py [--manifest benchmarks/suite/suite.json] [--suite full] -o DIR

Writes DIR/suite.json (the manifest of the selected problems with paths inside DIR),
DIR/scenes/<problem>.json (the scene; an OBJ line graph it names is copied next to it)
and DIR/reference/<problem>.json (the reference answer: every rod's vertex positions
at the equilibrium, rod after rod, from rodnet's tr-minres at gtol 1e-11), plus
DIR/README.md on how to score a run: error = max over vertices of the distance to the
reference, over the reference's largest displacement from the scene's start.
"""
import argparse
import json
import os
import shutil
import sys

README = """# rodnet optimiser benchmark suite (exported)

Each problem of `suite.json` is a rodnet scene (`scenes/`, format:
rodnet docs/scene-format.md) and a reference answer
(`reference/`: `vertices`, every rod's vertex positions at the equilibrium, rod
after rod, from rodnet's trust-region Newton method `tr-minres` at a relative
equilibrium tolerance of 1e-11).  Classes: rod (single rods), hard (buckling,
snap-through, large rotations), network (rods joined at joints), lattice.

Score a run as rodnet bench does: converged or not, whether the state is a
verified local minimum (lowest eigenvalue of the reduced Hessian > 0), the number
of gradient and Hessian-vector product evaluations, the time, and
error = max_i |x_i - x_ref_i| / max_i |x_ref_i - x0_i| (x0: the scene's
vertices).  A run solves a problem when it converged to a verified minimum with
error <= 1e-3.
"""


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    here = os.path.dirname(os.path.abspath(__file__))
    ap.add_argument("--manifest", default=os.path.join(here, "suite", "suite.json"))
    ap.add_argument("--suite", default="full", choices=["smoke", "quick", "full"])
    ap.add_argument("-o", "--outdir", required=True)
    a = ap.parse_args()
    base = os.path.dirname(os.path.abspath(a.manifest))
    with open(a.manifest) as f:
        man = json.load(f)
    os.makedirs(os.path.join(a.outdir, "scenes"), exist_ok=True)
    os.makedirs(os.path.join(a.outdir, "reference"), exist_ok=True)
    out = {"description": man.get("description", ""), "problems": []}
    for p in man["problems"]:
        if a.suite not in p["suites"]:
            continue
        name = p["name"]
        src = os.path.join(base, p["scene"])
        with open(src) as f:
            scene = json.load(f)
        dst = os.path.join(a.outdir, "scenes", f"{name}.json")
        obj = scene.get("graph", {}).get("obj") if isinstance(scene.get("graph"), dict) \
            else None
        if obj:  # the OBJ line graph, next to the scene under its own name
            shutil.copyfile(os.path.join(os.path.dirname(src), obj),
                            os.path.join(a.outdir, "scenes", os.path.basename(obj)))
            scene["graph"]["obj"] = os.path.basename(obj)
        with open(dst, "w") as f:
            json.dump(scene, f, indent=1)
        entry = {"name": name, "class": p.get("class", ""),
                 "scene": f"scenes/{name}.json", "suites": p["suites"]}
        ref = p.get("reference")
        if ref and os.path.exists(os.path.join(base, ref)):
            shutil.copyfile(os.path.join(base, ref),
                            os.path.join(a.outdir, "reference", f"{name}.json"))
            entry["reference"] = f"reference/{name}.json"
        out["problems"].append(entry)
    with open(os.path.join(a.outdir, "suite.json"), "w") as f:
        json.dump(out, f, indent=1)
    with open(os.path.join(a.outdir, "README.md"), "w") as f:
        f.write(README)
    print(f"bench_export.py: {len(out['problems'])} problems -> {a.outdir}")


if __name__ == "__main__":
    sys.exit(main())
