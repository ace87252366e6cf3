#!/usr/bin/env python3
"""Regenerate the example scenes of problems/scenes/ whose vertex lists or
rest shapes are too long to write by hand (ring.json, helix.json,
arch_p4.json, arch_p8.json, end_moment_circle.json).

    python3 problems/scenes/make_examples.py [OUTDIR]
"""
import json
import math
import os
import re
import sys


def fmt(x):
    return float("%.12g" % x)


def ring():
    # A straight rod of length 1 whose rest shape is a circle of the same
    # length: 40 edges turning by 2 pi / 40 at each of the 39 interior
    # vertices (integrated curvature 2 tan(phi / 2), seed 000 (2.2)), in the
    # plane of the tangent and d1 (kappa1).  Clamped at the start, it relaxes
    # into the ring (its two ends meet).
    nv = 41
    phi = 2 * math.pi / (nv - 1)
    kappa = fmt(2 * math.tan(phi / 2))
    return {
        "description": "A straight rod with the rest curvature of a circle of its own "
                       "length relaxes into a ring (radius 1 / (2 pi)).",
        "materials": {"steel": {"E": 1.0e7, "nu": 0.5}},
        "sections": {"wire": {"shape": "circle", "radius": 0.01}},
        "rods": [{
            "name": "ring", "material": "steel", "section": "wire",
            "line": {"from": [0, 0, 0], "to": [1, 0, 0], "vertices": nv},
            "d1": [0, 1, 0],
            "rest": {"curvature": [[kappa, 0.0] for _ in range(nv - 2)]},
        }],
        "constraints": [{"type": "clamp", "rod": "ring", "end": "start"}],
        "solver": {"load_steps": 4},
    }


def helix():
    # A coil spring: 3 turns of radius 0.1 and pitch 0.05, clamped at the
    # bottom and pulled along its axis at the top.
    turns, radius, pitch, per_turn = 3, 0.1, 0.05, 60
    nv = turns * per_turn + 1
    verts = []
    for i in range(nv):
        a = 2 * math.pi * i / per_turn
        verts.append([fmt(radius * math.cos(a)), fmt(radius * math.sin(a)),
                      fmt(pitch * a / (2 * math.pi))])
    return {
        "description": "A coil spring (3 turns, radius 0.1, pitch 0.05) clamped at the "
                       "bottom and pulled along its axis at the top.",
        "materials": {"steel": {"E": 1.0e7, "nu": 0.5}},
        "sections": {"wire": {"shape": "circle", "radius": 0.01}},
        "rods": [{"name": "spring", "material": "steel", "section": "wire",
                  "vertices": verts, "d1": [1, 0, 0]}],
        "constraints": [{"type": "clamp", "rod": "spring", "end": "start"}],
        "loads": [{"type": "force", "rod": "spring", "vertex": -1, "value": [0, 0, 0.05]}],
    }


def arch(load):
    # A 215-degree circular arch (R = 1, 320 edges) in the xz plane, symmetric
    # about the z axis, hinged (pinned) at its start and clamped at its end,
    # under a dead crown load P = load * EI / R^2 along -z, the classical
    # in-plane problem (DaDeppo and Schmidt 1975: limit load about 9 EI / R^2).
    # In-plane the section is a round wire's of radius r = 2e-3 R (EA R^2 / EI
    # = 4 R^2 / r^2 = 1e6), with E chosen so that EI = 1; a round arch this
    # slender buckles out of its plane (lateral-torsional) near P = 0.7 EI/R^2,
    # so, as in end_moment.json, the section is 100 times stiffer out of plane
    # (I11, d1 = y) and in torsion.  The stress-free shape is the arch itself.
    edges, span = 320, math.radians(215.0)
    r = 2.0e-3
    i22 = math.pi * r**4 / 4.0
    verts = []
    for i in range(edges + 1):
        a = -0.5 * span + span * i / edges
        verts.append([fmt(math.sin(a)), 0.0, fmt(math.cos(a))])
    return {
        "description": "A 215-degree circular arch (R = 1, 320 edges, EA R^2/EI = 1e6, "
                       "EI = 1 in plane, 100 EI out of plane and in torsion) hinged at its "
                       "start and clamped at its end, under a dead crown load P = %g EI/R^2 "
                       "applied at once from the unloaded arch (issue 8)." % load,
        "materials": {"arch": {"E": fmt(1.0 / i22), "nu": 0.3}},
        "sections": {"laterally_stiff_wire": {
            "shape": "explicit", "A": fmt(math.pi * r**2), "I11": fmt(100 * i22),
            "I22": fmt(i22), "I12": 0, "J": fmt(200 * i22)}},
        "rods": [{"name": "arch", "material": "arch", "section": "laterally_stiff_wire",
                  "vertices": verts, "d1": [0, 1, 0]}],
        "constraints": [{"type": "pin", "rod": "arch", "vertex": 0},
                        {"type": "clamp", "rod": "arch", "end": "end"}],
        "loads": [{"type": "force", "rod": "arch", "vertex": edges // 2,
                   "value": [0, 0, -float(load)]}],
    }


def end_moment_circle():
    # end_moment.json's rod and section under the closing moment M = 2 pi EI/L
    # (a full circle), applied at once.
    EI = 1.0e7 * 7.853981633974483e-9
    return {
        "description": "A clamped rod under the end moment M = 2 pi E I / L closes into a "
                       "full circle of radius L / (2 pi); the load is applied at once.  The "
                       "section is the round wire's in the plane of bending and 100 times "
                       "stiffer out of plane and in torsion (see end_moment.json).",
        "materials": {"steel": {"E": 1.0e7, "nu": 0.5}},
        "sections": {"laterally_stiff_wire": {
            "shape": "explicit", "A": 3.141592653589793e-4, "I11": 7.853981633974483e-7,
            "I22": 7.853981633974483e-9, "I12": 0, "J": 1.5707963267948966e-6}},
        "rods": [{"name": "beam", "material": "steel", "section": "laterally_stiff_wire",
                  "line": {"from": [0, 0, 0], "to": [1, 0, 0], "vertices": 101},
                  "d1": [0, 1, 0]}],
        "constraints": [{"type": "clamp", "rod": "beam", "end": "start"}],
        "loads": [{"type": "moment", "rod": "beam", "vertex": -1,
                   "value": [0, -2 * math.pi * EI, 0]}],
    }


def dump(scene, path):
    # One vertex / curvature pair per line keeps the files readable.
    text = json.dumps(scene, indent=2)
    # Collapse innermost numeric arrays onto one line.
    text = re.sub(r"\[\s*(-?[\d.e+-]+),\s*(-?[\d.e+-]+)(?:,\s*(-?[\d.e+-]+))?\s*\]",
                  lambda m: "[" + ", ".join(g for g in m.groups() if g is not None) + "]",
                  text)
    with open(path, "w") as f:
        f.write(text + "\n")


def main():
    outdir = sys.argv[1] if len(sys.argv) > 1 else os.path.dirname(os.path.abspath(__file__))
    dump(ring(), os.path.join(outdir, "ring.json"))
    dump(helix(), os.path.join(outdir, "helix.json"))
    dump(arch(4), os.path.join(outdir, "arch_p4.json"))
    dump(arch(8), os.path.join(outdir, "arch_p8.json"))
    dump(end_moment_circle(), os.path.join(outdir, "end_moment_circle.json"))


if __name__ == "__main__":
    main()
