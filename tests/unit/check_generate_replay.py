#!/usr/bin/env python3
"""check_generate_replay.py RODNET DIR: issue 22 item 3, the description that
`rodnet generate` writes into a scene is the command that reproduces the file.
For each case below: run `rodnet generate ARGS -o DIR/replay_K.json`, take the
scene's "description", check it starts with "rodnet generate ", run it again
(with `-o DIR/replay_K_again.json`) and compare the two files byte for byte.
The periodic default (once recorded as "--section circle:0.02" while a square
section of slenderness 0.05 was written), --relative-density, --slenderness,
--section, --perturb, --section-scatter, --seed and --repeat must survive the
round trip."""
import json
import os
import shlex
import subprocess
import sys

CASES = [
    ["honeycomb", "--periodic"],
    ["honeycomb", "--periodic", "--section", "circle:0.02"],
    ["kagome", "--periodic", "--relative-density", "0.1", "--cells", "2,3"],
    ["octet", "--periodic", "--slenderness", "0.07"],
    ["reentrant", "--periodic", "--cells", "3,2", "--perturb", "0.1", "--seed", "7",
     "--section-scatter", "0.2", "--repeat", "2,2", "--joint-model", "rigid"],
    ["square", "--periodic", "--load", "shear:0.01", "--model", "planar",
     "--material", "2.5,0.25"],
    ["cubic", "--cells", "2,3,1", "--cell-size", "0.3", "--load", "compress-y:0.01",
     "--edges-per-rod", "3"],
    ["triangular", "--section", "ellipse:0.03,0.01", "--load", "biaxial:0.01,-0.02"],
    ["bcc", "--cells", "2", "--section", "rectangle:0.02,0.03", "--load", "pull-z:1e-3"],
    ["square", "--cells", "3,2"],
]


def run(rodnet, args):
    r = subprocess.run([rodnet] + args, capture_output=True, text=True)
    if r.returncode != 0:
        sys.exit("FAIL: %s exited %d: %s" % (" ".join(args), r.returncode, r.stderr))


def main():
    rodnet, out = sys.argv[1], sys.argv[2]
    for k, args in enumerate(CASES):
        first = os.path.join(out, "replay_%d.json" % k)
        again = os.path.join(out, "replay_%d_again.json" % k)
        run(rodnet, ["generate"] + args + ["-q", "-o", first])
        desc = json.load(open(first))["description"]
        words = shlex.split(desc)
        if words[:2] != ["rodnet", "generate"] or "-o" in words:
            sys.exit("FAIL: case %d: the description is not a generate command: %r"
                     % (k, desc))
        run(rodnet, words[1:] + ["-q", "-o", again])
        a, b = open(first, "rb").read(), open(again, "rb").read()
        if a != b:
            sys.exit("FAIL: case %d (%s): the recorded command %r writes another file"
                     % (k, " ".join(args), desc))
        print("case %d: %s -> identical (%d bytes)" % (k, desc, len(a)))
    print("%d passed, 0 failed" % len(CASES))


if __name__ == "__main__":
    main()
