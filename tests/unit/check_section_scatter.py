#!/usr/bin/env python3
"""check_section_scatter.py A.json B.json C.json: `rodnet generate --periodic
--section-scatter S --seed N`: A and B (same seed) are identical, C (another seed)
differs; every rod has its own section, the widths (2D) or radii (3D) scaled by
factors of mean 1 and relative standard deviation S (within the sampling error
of the number of rods), square sections stay square."""
import json
import math
import sys


def scales(path):
    s = json.load(open(path))
    secs = s["sections"]
    rods = s["rods"]
    assert len(secs) == len(rods), (len(secs), len(rods))
    out = []
    for r in rods:
        sec = secs[r["section"]]
        if sec["shape"] == "rectangle":
            assert sec["width"] == sec["height"], sec
            out.append(sec["width"])
        else:
            out.append(sec["radius"])
    return out


def main():
    S = float(sys.argv[4])
    a, b, c = scales(sys.argv[1]), scales(sys.argv[2]), scales(sys.argv[3])
    assert a == b, "same seed, different sections"
    assert a != c, "different seeds, same sections"
    for v in (a, c):
        n = len(v)
        mean = sum(v) / n
        sd = math.sqrt(sum((x - mean) ** 2 for x in v) / (n - 1))
        # the nominal thickness is the median-free mean; 4 standard errors
        assert abs(sd / mean - S) < 4 * S / math.sqrt(2 * n), (sd / mean, S, n)
        print("section scatter: %d rods, relative std %.4f (asked %.4f)" % (n, sd / mean, S))
    return 0


if __name__ == "__main__":
    sys.exit(main())
