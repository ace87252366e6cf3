#!/usr/bin/env python3
"""Everything that lists the preconditioners and solver kinds lists exactly the rows
of the library's registry (c_api/include/rodnet_registry.h), as printed by the test
program registry_lists: `rodnet solve --help` (its --solver and --preconditioner
rows), `rodnet bench --help` and its "unknown solver" error (every solver kind, and
for the kinds that take a preconditioner every KIND-PRECONDITIONER; the default
selection unchanged), and the docs' tables (docs/solvers.md, docs/cli.md,
docs/scene-format.md).  With the solver built also `rodnet --version` and the
"unknown solver / preconditioner" errors of `rodnet solve`.

    check_registry_lists.py REGISTRY_LISTS RODNET DOCS_DIR SCENE WORKDIR [solver]
"""
import os
import re
import subprocess
import sys

FAILS = []
TAKES_PRECONDITIONER = 1 << 1  # RN_SOLVER_TAKES_PRECONDITIONER
ALIAS = 1 << 3  # RN_PC_ALIAS
DEFAULT_BENCH = ["tr-minres", "tr-krylov-dd", "tr-krylov-factor", "rol-tr-tcg",
                 "rol-ls-newton", "nox-dd", "rol-lbfgs"]


def run(args, expect):
    p = subprocess.run(args, capture_output=True, text=True)
    if p.returncode != expect:
        FAILS.append("%s: exit %d (expected %d)\n%s%s" % (" ".join(args), p.returncode,
                                                         expect, p.stdout, p.stderr))
    return p


def same(what, got, want, ordered=True):
    if (got if ordered else sorted(got)) != (want if ordered else sorted(want)):
        FAILS.append("%s: %s, the registry has %s (missing %s, extra %s)" % (
            what, got, want, sorted(set(want) - set(got)), sorted(set(got) - set(want))))


def help_rows(text, start, stop):
    """The names of a help list: the lines from the one containing start to the one
    containing stop, each row a name at column 24."""
    lines = text.splitlines()
    i = next(k for k, l in enumerate(lines) if start in l)
    j = next(k for k, l in enumerate(lines) if k > i and stop in l)
    return [m.group(1) for l in lines[i + 1:j] for m in [re.match(r" {24}(\S+) ", l)] if m]


def help_list(text, label):
    """The comma-separated names after label, continued on the lines indented by 22."""
    lines = text.splitlines()
    i = next(k for k, l in enumerate(lines) if l.strip().startswith(label))
    words = lines[i].strip()[len(label):]
    for l in lines[i + 1:]:
        if not l.startswith(" " * 22) or l.strip().endswith(":") or \
                l.strip().split()[0].endswith(":") or l.lstrip().startswith("-"):
            break
        words += " " + l.strip()
    return [w.strip() for w in words.split(",") if w.strip()]


def known_list(message):
    m = re.search(r"\(known: ([^)]*)\)", message)
    return m.group(1).split(", ") if m else []


def table_names(text, heading):
    """The backquoted names of the first column of the first table after heading."""
    body = text[text.index(heading):]
    rows = re.findall(r"^\| (.*?) \|", body[body.index("\n|"):].split("\n\n")[0], re.M)
    return [n for r in rows for n in re.findall(r"`([^`]+)`", r)]  # (the header has none)


def main():
    reg, rodnet, docs, scene, work = sys.argv[1:6]
    with_solver = len(sys.argv) > 6 and sys.argv[6] == "solver"
    os.makedirs(work, exist_ok=True)
    out = run([reg], 0).stdout
    solvers = [(n, int(f)) for n, f in re.findall(r"^solver (\S+) (\d+)$", out, re.M)]
    precs = [(n, int(f)) for n, f in re.findall(r"^preconditioner (\S+) (\d+)$", out, re.M)]
    kinds = [n for n, _ in solvers]
    pcs = [n for n, _ in precs]
    if not kinds or not pcs:
        sys.exit("registry_lists printed no rows:\n" + out)

    # rodnet solve --help
    h = run([rodnet, "solve", "--help"], 0).stdout
    same("solve --help, --solver", help_rows(h, "--solver NAME", "--preconditioner NAME"),
         kinds)
    same("solve --help, --preconditioner",
         help_rows(h, "--preconditioner NAME", "--factorization NAME"), pcs)
    taking = [n for n, f in solvers if f & TAKES_PRECONDITIONER]
    m = re.search(r"--preconditioner NAME  preconditioner of (.*?) \(", h)
    same("solve --help, the kinds that take a preconditioner",
         re.split(r", | and ", m.group(1)) if m else [], taking)

    # rodnet bench: every kind, KIND-PRECONDITIONER for those that take one
    pairs = [k if not f & TAKES_PRECONDITIONER else "%s-%s" % (k, p)
             for k, f in solvers for p, pf in (precs if f & TAKES_PRECONDITIONER
                                               else [(None, 0)]) if not pf & ALIAS]
    pairs = list(dict.fromkeys(pairs))
    h = run([rodnet, "bench", "--help"], 0).stdout
    default, also = help_list(h, "default:"), help_list(h, "also:")
    same("bench --help, default selection", default, DEFAULT_BENCH)
    same("bench --help, every solver", default + also, pairs, ordered=False)
    e = run([rodnet, "bench", "--solvers", "no-such-name", "-o",
             os.path.join(work, "bench")], 2).stderr
    same("bench unknown solver, known", known_list(e), default + also)

    # the docs
    def read(name):
        with open(os.path.join(docs, name)) as f:
            return f.read()
    text = read("solvers.md")
    same("docs/solvers.md, Solver kinds", table_names(text, "## Solver kinds"), kinds,
         ordered=False)
    same("docs/solvers.md, Preconditioners for networks",
         table_names(text, "## Preconditioners for networks"), pcs, ordered=False)
    text = read("cli.md")
    for opt, want in (("--solver", kinds), ("--preconditioner", pcs)):
        m = re.search(r"\[%s ([\w|-]+)\]" % opt, text)
        same("docs/cli.md, synopsis %s" % opt, m.group(1).split("|") if m else [], want,
             ordered=False)
    text = read("scene-format.md")
    for key, want in (("method", kinds), ("preconditioner", pcs)):
        m = re.search(r"^\| `%s` \| (.*?) \|" % key, text, re.M)
        same("docs/scene-format.md, solver.%s" % key,
             re.findall(r'`"([^"`]+)"`', m.group(1)) if m else [], want, ordered=False)

    if with_solver:
        v = run([rodnet, "--version"], 0).stdout
        m = re.search(r"solver: built in \((.*); Trilinos\)", v)
        same("rodnet --version", m.group(1).split(", ") if m else [], kinds)
        res = os.path.join(work, "x.json")
        e = run([rodnet, "solve", scene, "-o", res, "--solver", "no-such-name"], 2).stderr
        same("solve unknown solver, known", known_list(e), kinds)
        e = run([rodnet, "solve", scene, "-o", res, "--solver", taking[0],
                 "--preconditioner", "no-such-name"], 2).stderr
        same("solve unknown preconditioner, known", known_list(e), pcs)

    for f in FAILS:
        print("FAIL: " + f)
    print("check_registry_lists: %d solver kinds, %d preconditioners, %d bench solvers: %s"
          % (len(kinds), len(pcs), len(pairs), "FAILED" if FAILS else "ok"))
    sys.exit(1 if FAILS else 0)


main()
