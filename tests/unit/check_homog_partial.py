#!/usr/bin/env python3
"""Issue 22 item 2: a `rodnet homogenize --path` that stops early writes its partial
path to RESULT.partial.json ("partial": true) and leaves a complete earlier
RESULT.json as it was; the exit status is 4 and stderr names the partial file.

Usage: check_homog_partial.py RODNET SCENE DIR"""
import json
import os
import subprocess
import sys


def run(args):
    r = subprocess.run(args, capture_output=True, text=True)
    print("$ " + " ".join(args) + f"\nexit {r.returncode}\n{r.stdout}{r.stderr}")
    return r


def main():
    rodnet, scene, out = sys.argv[1:4]
    os.makedirs(out, exist_ok=True)
    res, part = os.path.join(out, "r.json"), os.path.join(out, "r.partial.json")
    for f in (res, part):
        if os.path.exists(f):
            os.remove(f)
    ok = True
    r = run([rodnet, "homogenize", scene, "--path", "-0.001,-0.001,0", "--steps", "2",
             "--bloch-grid", "2", "-q", "-o", res])
    ok &= r.returncode == 0 and os.path.exists(res) and not os.path.exists(part)
    before = open(res, "rb").read()
    ok &= "path_stopped" not in json.loads(before)
    # a shear of 2 in one step: the fluctuations do not converge, the path stops
    r = run([rodnet, "homogenize", scene, "--path", "0,0,2", "--steps", "1",
             "--bloch-grid", "2", "-q", "-o", res])
    ok &= r.returncode == 4 and "r.partial.json" in r.stderr
    ok &= open(res, "rb").read() == before
    print("RESULT.json kept:", open(res, "rb").read() == before)
    if os.path.exists(part):
        p = json.load(open(part))
        print("partial:", p.get("partial"), "path_stopped:", p.get("path_stopped"))
        ok &= p.get("partial") is True and "path_stopped" in p
    else:
        print("no", part)
        ok = False
    # an output without .json: the suffix appended
    base = os.path.join(out, "noext")
    r = run([rodnet, "homogenize", scene, "--path", "0,0,2", "--steps", "1",
             "--bloch-grid", "2", "-q", "-o", base])
    ok &= r.returncode == 4 and os.path.exists(base + ".partial.json") and \
        not os.path.exists(base)
    print("OK" if ok else "FAILED")
    sys.exit(0 if ok else 1)


if __name__ == "__main__":
    main()
