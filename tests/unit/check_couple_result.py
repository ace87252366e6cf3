#!/usr/bin/env python3
"""check_couple_result.py RESULT.json - the RESULT.json of a solve with a couple
fixed in space (docs/model.md, "Loads"): converged to a stationary point, the
nonconservative loads counted, and no claim of a verified minimum (the
stability check does not apply)."""
import json
import sys


def main():
    with open(sys.argv[1]) as f:
        r = json.load(f)
    bad = []
    if r.get("status") != "converged":
        bad.append("status %r" % r.get("status"))
    if r.get("solver") != "nox":
        bad.append("solver %r" % r.get("solver"))
    if r.get("finds") != "stationary point":
        bad.append("finds %r" % r.get("finds"))
    if r.get("nonconservative_loads") != 1:
        bad.append("nonconservative_loads %r" % r.get("nonconservative_loads"))
    st = r.get("stability", {})
    if st.get("checked") is not False or st.get("verified_minimum") is not False:
        bad.append("stability %r" % st)
    if not str(st.get("note", "")).startswith("not applicable"):
        bad.append("stability note %r" % st.get("note"))
    if bad:
        print("check_couple_result: " + "; ".join(bad))
        return 1
    print("check_couple_result: ok")
    return 0


if __name__ == "__main__":
    sys.exit(main())
