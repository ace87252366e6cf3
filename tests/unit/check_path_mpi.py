#!/usr/bin/env python3
"""Issue 24: strain paths of periodic (super)cells under mpirun.

`mpirun -np NP rodnet homogenize SCENE --path ...` follows the path with the cell
split over the ranks: the fluctuations relaxed by the distributed Newton solver
with the strain held, the cell-periodic stability test (xi = 0 of the supercell)
by distributed LOBPCG, the long-wavelength test from the distributed tangent.
Checked against `rodnet homogenize` on one process (the Bloch search over the
whole zone of the same supercell):
- square 2 x 2 supercell, equibiaxial compression: the first instability is
  macroscopic (rank-one convexity) on both, at the same load factor to 1e-3 (the
  tolerance of the location), the stresses of the steps before it to 1e-8;
- honeycomb 2 x 2 supercell, equibiaxial compression: local on both; the
  distributed test sees the supercell's cell-periodic modes only, so its critical
  load factor is not below the whole zone's (to 1e-4) and within 1e-3 of it, at
  wave vector 0;
- honeycomb 2 x 2 supercell under uniaxial stress (mixed control, --path E,-,-):
  the same strains at every step to 1e-8;
- the regular 20 x 20 honeycomb supercell on NP ranks against the primitive cell
  on one process: the same critical load factor and stress to 1e-6;
- on NP ranks the path ends with the step past the instability (path_end says
  why), RESULT.json has the partition, exit status 0;
- refused once (exit 2, nothing written): --modes in-plane on a scene on the 3D
  model.
All scenes on the planar model, rigid joints, 4 edges per strut.

Usage: check_path_mpi.py RODNET MPIEXEC NP DIR"""
import json
import os
import sys

from mpi_cli import check, finish, load_all, rel, run, setup


def both(rodnet, mpi, scene, path, d, stem, name):
    outs = [os.path.join(d, f"{stem}{k}.json") for k in (1, 2)]
    args = ["homogenize", scene, "--path", path, "--steps", "10", "-q"]
    run([rodnet] + args + ["-o", outs[0]], f"{name}: one process")
    run(mpi + [rodnet] + args + ["-o", outs[1]], f"{name}: mpirun")
    return load_all(outs)


def instabilities(res, name):
    """The two results' instabilities, or None unless both have one."""
    if not res:
        return None
    ia, ib = res[0]["instability"], res[1]["instability"]
    check(ia is not None and ib is not None, f"{name}: an instability on both")
    return (ia, ib) if ia and ib else None


def main():
    rodnet, np_, d, mpi = setup(sys.argv)
    scenes = {}
    for kind in ("square", "honeycomb"):
        raw = os.path.join(d, kind + "_3d.json")
        run([rodnet, "generate", kind, "--periodic", "--cells", "2,2", "--edges-per-rod",
             "4", "--joint-model", "rigid", "-o", raw], f"{kind}: generate")
        cell = json.load(open(raw))
        cell["model"] = "planar"
        scenes[kind] = os.path.join(d, kind + ".json")
        json.dump(cell, open(scenes[kind], "w"))

    # square: macroscopic first
    res = both(rodnet, mpi, scenes["square"], "-0.01,-0.01,0", d, "sq", "square")
    if res:
        a, b = res
        ia, ib = a["instability"], b["instability"]
        check(ia is not None and ib is not None, "square: an instability on both")
        if ia and ib:
            print(f"    load factor {ia['load_factor']:.9g} (one process) "
                  f"{ib['load_factor']:.9g} ({np_} ranks)")
            check(ia["criterion"] == ib["criterion"] == "rank_one_convexity",
                  f"square: rank-one convexity on both ({ia['criterion']}, "
                  f"{ib['criterion']})")
            check(abs(ib["load_factor"] - ia["load_factor"]) <= 1e-3 * ia["load_factor"],
                  "square: the same critical load factor to 1e-3")
            before = [k for k, s in enumerate(a["path"]) if s["load_factor"] < ia["load_factor"]]
            e = max(rel(b["path"][k]["stress"], a["path"][k]["stress"]) for k in before
                    if k > 0)
            check(e <= 1e-8, f"square: the steps' stresses before it agree ({e:.3g})")
        check("path_end" in b and "mpirun" in b["path_end"] and "path_end" not in a,
              "square: the path ends with the step past the instability on the ranks")
        check(len(b["path"]) == len([s for s in a["path"]
                                     if s["load_factor"] < ia["load_factor"]]) + 1,
              "square: ... which is recorded")
        check(b.get("partition", {}).get("ranks") == np_, "square: the partition")

    # honeycomb: local first, cell-periodic in the supercell
    res = both(rodnet, mpi, scenes["honeycomb"], "-0.004,-0.004,0", d, "hc", "honeycomb")
    pair = instabilities(res, "honeycomb")
    if pair:
        ia, ib = pair
        ta, tb = ia["load_factor"], ib["load_factor"]
        print(f"    load factor {ta:.9g} at {ia['wave_vector']} (one process), "
              f"{tb:.9g} at {ib['wave_vector']} ({np_} ranks)")
        check(ia["kind"] == ib["kind"] == "local", "honeycomb: local on both")
        check(tb >= ta * (1 - 1e-4) and tb <= ta * (1 + 1e-3),
              "honeycomb: the cell-periodic critical load factor is the zone's to 1e-3")
        check(ib["wave_vector"] == [0, 0], "honeycomb: at wave vector 0")

    # at scale: the regular 20 x 20 supercell against the primitive cell (one process,
    # the whole zone): its M-point critical mode is cell-periodic in the supercell.
    # The sparse search's target against the dense oracle, 1e-6 (issue 24; measured
    # 1e-11).  It was 1.5e-4 low before the relaxation on a part solved each Newton
    # step to 1e-6 (the step past the instability had left the principal branch)
    # and before the secant stopped at a trial on the singular point itself.
    prim, sup = os.path.join(d, "hc_prim.json"), os.path.join(d, "hc20.json")
    for cells, out in (("1,1", prim), ("20,20", sup)):
        run([rodnet, "generate", "honeycomb", "--periodic", "--cells", cells,
             "--edges-per-rod", "4", "--joint-model", "rigid", "--model", "planar", "-o",
             out], f"honeycomb {cells}: generate")
    outs = [os.path.join(d, "hc_prim_r.json"), os.path.join(d, "hc20_r.json")]
    args = ["--path", "-0.002,-0.002,0", "--steps", "8", "-q", "-o"]
    run([rodnet, "homogenize", prim] + args + [outs[0]], "primitive cell: one process")
    run(mpi + [rodnet, "homogenize", sup] + args + [outs[1]], "20 x 20: mpirun")
    pair = instabilities(load_all(outs), "20 x 20")
    if pair:
        ia, ib = pair
        ta, tb = ia["load_factor"], ib["load_factor"]
        print(f"    load factor {ta:.9g} at {ia['wave_vector']} (primitive cell), "
              f"{tb:.9g} (20 x 20 on {np_} ranks), {(tb - ta) / ta:.3g} relative")
        check([0.5, 0] in ia.get("equivalent_wave_vectors", []),
              "primitive cell: an M point")
        check(abs(tb - ta) <= 1e-6 * ta, "20 x 20: the primitive cell's to 1e-6")
        check(abs(ib["stress"][0] - ia["stress"][0]) <= 1e-6 * abs(ia["stress"][0]),
              "20 x 20: the critical stress to 1e-6")

    # mixed control: uniaxial stress
    res = both(rodnet, mpi, scenes["honeycomb"], "-0.02,-,-", d, "hm", "honeycomb mixed")
    if res:
        a, b = res
        check(len(a["path"]) == len(b["path"]) == 11, "honeycomb mixed: every step")
        e = max(rel(sb["strain"], sa["strain"]) for sa, sb in zip(a["path"], b["path"])
                if sa["step"] > 0)
        print(f"    strains agree to {e:.3g}")
        check(e <= 1e-8, f"honeycomb mixed: the same strains ({e:.3g})")

    r = run(mpi + [rodnet, "homogenize", os.path.join(d, "square_3d.json"), "--path",
                   "-0.01,-0.01,0", "--modes", "in-plane", "-o",
                   os.path.join(d, "no.json")], "--modes in-plane on the 3D model", 2)
    check(r.stderr.count("every mode of the cell") == 1, "--modes in-plane refused once")
    check(not os.path.exists(os.path.join(d, "no.json")), "nothing written")
    return finish()


if __name__ == "__main__":
    sys.exit(main())
