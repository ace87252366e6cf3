#!/usr/bin/env python3
"""Regenerate the example scenes of problems/scenes/ whose vertex lists or
rest shapes are too long to write by hand (ring.json, helix.json).

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


if __name__ == "__main__":
    main()
