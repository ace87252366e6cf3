"""The Python interface (docs/python.md) against the C library and the rodnet
command: the same answers, analytic derivatives checked by central differences,
scipy reaching rodnet's equilibrium, clean errors for bad input."""
import json
import math
import os
import signal
import subprocess
import sys
import textwrap

import numpy as np
import pytest

import rodnet


def cantilever(scenes):
    return rodnet.load_scene(os.path.join(scenes, "cantilever.json"))


# ---- solve: the same answer as `rodnet solve` -----------------------------------------
def test_solve_matches_the_command(cli, scenes, tmp_path):
    out = tmp_path / "r.json"
    subprocess.run([cli, "solve", os.path.join(scenes, "cantilever.json"), "-o", str(out),
                    "-q"], check=True, capture_output=True)
    ref = json.loads(out.read_text())
    r = rodnet.solve(cantilever(scenes))
    assert r.converged and r.status == ref["status"] == "converged"
    assert r.stop_reason == ref["stop_reason"]
    assert r.iterations == ref["iterations"]
    assert r.energy == pytest.approx(ref["energy"], rel=1e-12)
    assert np.abs(r.positions("beam") - np.array(ref["rods"][0]["vertices"])).max() < 1e-12
    assert r.positions(0).shape == (101, 3)
    st = r.stability
    assert st["verified_minimum"] is ref["stability"]["verified_minimum"] is True
    assert st["lowest_eigenvalue"] == pytest.approx(ref["stability"]["lowest_eigenvalue"],
                                                    rel=1e-6)
    assert st["zero_modes"] == ref["stability"]["zero_modes"]
    sup = r.reactions["supports"][0]
    rsup = ref["reactions"]["supports"][0]
    assert sup["kind"] == rsup["kind"] == "clamp" and sup["rod"] == "beam"
    assert np.allclose(sup["force"], rsup["force"], rtol=1e-9, atol=1e-12)
    assert np.allclose(sup["moment"], rsup["moment"], rtol=1e-9, atol=1e-12)
    # the reactions balance the applied load (0.39 down at the tip)
    assert np.allclose(r.reactions["resultant"]["force"], -r.reactions["applied"]["force"],
                       atol=1e-9)
    for k in ("krylov_iterations", "hvp_evals", "gradient_evals", "load_steps"):
        assert getattr(r, k) >= 1


def test_solver_options(scenes):
    r = rodnet.solve(cantilever(scenes), "tr-krylov", preconditioner="dd", gtol=1e-10,
                     max_iterations=50, stability=False)
    assert r.converged and r.solver == "tr-krylov" and r.preconditioner == "dd"
    assert r.stability["checked"] is False
    ref = rodnet.solve(cantilever(scenes))
    assert np.abs(r.positions(0) - ref.positions(0)).max() < 1e-8
    r2 = rodnet.solve(cantilever(scenes), max_iterations=2, max_load_cuts=0)
    assert not r2.converged and r2.status == "max_iterations" and r2.iterations == 2


def test_progress_once_per_newton_iteration(scenes):
    seen = []
    r = rodnet.solve(cantilever(scenes), progress=seen.append)
    assert [s["iteration"] for s in seen] == list(range(len(seen)))
    assert len(seen) == r.iterations + 1
    assert seen[-1]["energy"] == pytest.approx(r.energy, rel=1e-12)


def test_exception_in_progress_stops_and_is_raised(scenes):
    def boom(info):
        if info["iteration"] == 1:
            raise RuntimeError("stop here")
    with pytest.raises(RuntimeError, match="stop here"):
        rodnet.solve(cantilever(scenes), progress=boom)


def test_ctrl_c_stops_cleanly(scenes):
    """SIGINT during a solve: the solve stops with status "interrupted" and the
    interpreter lives on."""
    code = textwrap.dedent("""
        import os, signal, rodnet
        s = rodnet.load_scene(%r)
        def kick(info):
            if info["iteration"] == 2:
                os.kill(os.getpid(), signal.SIGINT)
        r = rodnet.solve(s, progress=kick)
        print(r.status, r.converged, r.iterations, r.stability["checked"])
        r = rodnet.solve(s)
        print("alive", r.converged)
    """ % os.path.join(scenes, "cantilever.json"))
    p = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                       timeout=120)
    assert p.returncode == 0, p.stderr
    lines = p.stdout.split("\n")
    status, conv, its, checked = lines[0].split()
    assert status == "interrupted" and conv == "False" and checked == "False"
    assert 2 <= int(its) <= 3
    assert lines[1] == "alive True"


# ---- the objective --------------------------------------------------------------------
def test_objective_derivatives_second_order(scenes):
    """Gradient and HVP against central differences, with an h-sweep: the error
    falls like h^2 until round-off."""
    o = cantilever(scenes).objective()
    rng = np.random.default_rng(3)
    x = o.x0 + 1e-3 * rng.standard_normal(o.n)
    d = rng.standard_normal(o.n)
    d /= np.linalg.norm(d)
    g = o.gradient(x)
    exact = g @ d
    errs = []
    for h in (1e-4, 5e-5, 2.5e-5):
        fd = (o.value(x + h * d) - o.value(x - h * d)) / (2 * h)
        errs.append(abs(fd - exact) / abs(exact))
    orders = [math.log(errs[i] / errs[i + 1], 2) for i in range(2)]
    assert errs[-1] < 1e-6 and min(orders) > 1.8, (errs, orders)
    hv = o.hessp(x, d)
    herrs = []
    for h in (1e-5, 5e-6, 2.5e-6):
        fd = (o.gradient(x + h * d) - o.gradient(x - h * d)) / (2 * h)
        herrs.append(np.linalg.norm(fd - hv) / np.linalg.norm(hv))
    horders = [math.log(herrs[i] / herrs[i + 1], 2) for i in range(2)]
    assert herrs[-1] < 1e-8 and min(horders) > 1.8, (herrs, horders)
    E, g2 = o.value_and_gradient(x)
    assert E == o.value(x) and np.array_equal(g, g2)


def test_hessian_csr(scenes):
    sp = pytest.importorskip("scipy.sparse")
    o = cantilever(scenes).objective()
    x = o.x0 + 1e-3 * np.random.default_rng(1).standard_normal(o.n)
    H = o.hessian(x)
    assert isinstance(H, sp.csr_matrix) and H.shape == (o.n, o.n)
    assert abs(H - H.T).max() <= 1e-14 * abs(H).max()
    p = np.random.default_rng(2).standard_normal(o.n)
    assert np.linalg.norm(H @ p - o.hessp(x, p)) <= 1e-12 * np.linalg.norm(H @ p)


@pytest.mark.parametrize("method", ["trust-krylov", "trust-ncg"])
def test_scipy_reaches_rodnet_equilibrium(scenes, method):
    opt = pytest.importorskip("scipy.optimize")
    ref = rodnet.solve(cantilever(scenes))
    o = cantilever(scenes).objective()
    r = opt.minimize(o.value, o.x0, jac=o.gradient, hessp=o.hessp, method=method)
    assert r.success, r.message
    o.model.set_dofs(r.x)
    disp = np.abs(ref.positions(0) - o.model.positions(0)).max()
    tip = np.linalg.norm(ref.positions(0)[-1] - np.array([1.0, 0, 0]))
    assert disp < 1e-6 * tip, disp
    assert r.fun == pytest.approx(ref.energy, rel=1e-10)


def test_accept_moves_the_frames(scenes):
    o = cantilever(scenes).objective()
    x = o.x0.copy()
    x[-3:] += [0.0, 0.0, -0.01]
    E = o.value(x)
    x2 = o.accept(x)
    assert o.value(x2) == pytest.approx(E, rel=1e-12, abs=1e-15)
    assert np.array_equal(o.x0, x2) and np.array_equal(o.model.dofs(), x2)


def test_degenerate_trial_point_is_inf(scenes):
    """A zero-length edge at a trial point: value inf (the optimiser rejects the
    step), gradient an Error; no crash."""
    o = cantilever(scenes).objective()
    x = o.x0.copy()
    # the clamp removes vertices 0, 1 and angle 0: the reduced DOFs start with
    # vertex 2 (x, y, z), angle 2, vertex 3: put vertex 3 onto vertex 2
    x[4:7] = x[0:3]
    assert o.value(x) == math.inf
    with pytest.raises(rodnet.Error, match="degenerate"):
        o.gradient(x)


# ---- networks from arrays ---------------------------------------------------------------
def test_network_from_arrays_equals_the_scene(scenes):
    n = rodnet.Network()
    xyz = np.zeros((101, 3))
    xyz[:, 0] = np.linspace(0, 1, 101)
    rod = n.add_rod(xyz, name="beam", d1=[0, 1, 0], E=1e7, nu=0.5, radius=0.01)
    n.clamp(rod, "start")
    n.add_force(rod, -1, [0, 0, -0.39])
    n.finalize()
    r = rodnet.solve(n)
    ref = rodnet.solve(cantilever(scenes))
    assert r.energy == pytest.approx(ref.energy, rel=1e-12)
    assert np.abs(r.positions("beam") - ref.positions("beam")).max() < 1e-12
    f, m = n.internal_forces(0)
    # at equilibrium the internal force of every edge carries the tip load
    assert np.allclose(f[1:], [0, 0, -0.39], atol=1e-7)
    d1, d2 = n.frames(0)
    assert np.allclose(np.einsum("ij,ij->i", d1, d2), 0, atol=1e-12)


def test_network_joints_and_periodic_cell():
    # a triangle of three rods with rigid joints, one joint clamped, one loaded
    pts = np.array([[0, 0, 0], [1, 0, 0], [0.5, 0.8, 0]], float)
    n = rodnet.Network()
    rods = []
    for a in range(3):
        b = (a + 1) % 3
        line = np.linspace(pts[a], pts[b], 9)
        rods.append(n.add_rod(line, E=1e6, nu=0.3, radius=0.01))
    for a in range(3):
        n.add_joint([(rods[a - 1], "end"), (rods[a], "start")], model="rigid",
                    name="J%d" % a)
    n.clamp_joint(0)
    n.add_joint_force(1, [0, 0, -1e-3])
    n.finalize()
    r = rodnet.solve(n)
    assert r.converged and r.stability["verified_minimum"]
    assert n.joint_names() == ["J0", "J1", "J2"]
    assert n.joint_position("J1")[2] < 0
    R = n.joint_rotation(1)
    assert np.allclose(R @ R.T, np.eye(3), atol=1e-12)
    # a periodic square cell: one rod along x to its image, one along y
    c = rodnet.Network(periodic=[[1, 0, 0], [0, 1, 0]])
    rx = c.add_rod(np.linspace([0, 0, 0], [1, 0, 0], 5), E=1.0, nu=0.3, radius=0.02)
    ry = c.add_rod(np.linspace([0, 0, 0], [0, 1, 0], 5), E=1.0, nu=0.3, radius=0.02)
    c.add_joint([(rx, "start"), (rx, "end"), (ry, "start"), (ry, "end")], model="rigid",
                images=[[0, 0, 0], [1, 0, 0], [0, 0, 0], [0, 1, 0]])
    c.finalize()
    h = rodnet.homogenize(c)
    A = math.pi * 0.02 ** 2
    # the square lattice: C11 = E A / a (per unit length, stretching of the x struts)
    assert h["C"][0, 0] == pytest.approx(A, rel=1e-9)
    assert h["C"][1, 1] == pytest.approx(A, rel=1e-9)
    assert abs(h["C"][0, 1]) < 1e-12 * A


# ---- homogenisation: the same answer as `rodnet homogenize` ---------------------------------
def test_homogenize_matches_the_command(cli, hc8, tmp_path):
    out = tmp_path / "h.json"
    subprocess.run([cli, "homogenize", hc8, "-o", str(out), "-q"], check=True,
                   capture_output=True)
    ref = json.loads(out.read_text())
    h = rodnet.homogenize(rodnet.load_scene(hc8))
    C = np.array(ref["C"])
    assert np.abs(h["C"] - C).max() <= 1e-12 * np.abs(C).max()
    assert h["relative_density"] == pytest.approx(ref["relative_density"], rel=1e-14)
    assert h["area"] == pytest.approx(ref["area"], rel=1e-14)
    for k, v in ref["constants"].items():
        assert h["constants"][k] == pytest.approx(v, rel=1e-10), k


def test_homogenize_path_matches_the_command(cli, hc8, tmp_path):
    out = tmp_path / "p.json"
    subprocess.run([cli, "homogenize", hc8, "--path", "-0.004,-0.004,0", "--steps", "4",
                    "--modes", "in-plane", "--bloch-grid", "4", "-o", str(out), "-q"],
                   check=True, capture_output=True)
    ref = json.loads(out.read_text())
    steps = []
    h = rodnet.homogenize(rodnet.load_scene(hc8), path=[-0.004, -0.004, 0], steps=4,
                          modes="in-plane", bloch_grid=4, progress=steps.append)
    assert len(steps) == len(ref["path"]) - 1
    inst, rinst = h["instability"], ref["instability"]
    assert inst["kind"] == rinst["kind"] == "local"
    assert inst["wave_vector"] == rinst["wave_vector"]
    assert inst["load_factor"] == pytest.approx(rinst["load_factor"], rel=1e-12)
    assert np.allclose(inst["strain"], rinst["strain"], rtol=1e-10, atol=1e-15)
    assert [s["stable"] for s in h["path"]] == [s["stable"] for s in ref["path"]]
    assert h["path_kind"] == ref["path_kind"] == "strain"
    # the string form of --path gives the same
    h2 = rodnet.homogenize(rodnet.load_scene(hc8), path="-0.004,-0.004,0", steps=4,
                           modes="in-plane", bloch_grid=4)
    assert h2["instability"]["load_factor"] == inst["load_factor"]


def test_homogenize_path_bloch_method(cli, hc8, tmp_path):
    # bloch_method is the command's --bloch-method; dense and sparse agree on the
    # critical strain far inside the locate tolerance
    found = {}
    for m in ("dense", "sparse"):
        out = tmp_path / ("%s.json" % m)
        subprocess.run([cli, "homogenize", hc8, "--path", "-0.004,-0.004,0", "--steps",
                        "4", "--modes", "in-plane", "--bloch-grid", "4", "--bloch-method",
                        m, "-o", str(out), "-q"], check=True, capture_output=True)
        ref = json.loads(out.read_text())
        assert ref["bloch_method"] == m
        h = rodnet.homogenize(rodnet.load_scene(hc8), path=[-0.004, -0.004, 0], steps=4,
                              modes="in-plane", bloch_grid=4, bloch_method=m)
        assert h["instability"]["load_factor"] == pytest.approx(
            ref["instability"]["load_factor"], rel=1e-12)
        found[m] = h["instability"]["load_factor"]
    assert found["sparse"] == pytest.approx(found["dense"], rel=1e-7)
    with pytest.raises(rodnet.Error, match="bloch_method"):
        rodnet.homogenize(rodnet.load_scene(hc8), path=[-0.004, -0.004, 0],
                          bloch_method="lanczos")


# ---- errors: rodnet.Error with the library's message, never a crash ---------------------
def test_errors(tmp_path, scenes, hc8):
    bad = tmp_path / "bad.json"
    bad.write_text('{"rods": [ }')
    with pytest.raises(rodnet.Error) as e:
        rodnet.load_scene(bad)
    assert str(bad) in str(e.value) and e.value.status == "RN_ERR_PARSE"
    with pytest.raises(rodnet.Error, match="missing.json"):
        rodnet.load_scene(tmp_path / "missing.json")
    unknown = tmp_path / "unknown.json"
    unknown.write_text('{"rods": [], "colour": 1}')
    with pytest.raises(rodnet.Error, match="colour"):
        rodnet.load_scene(unknown)
    s = cantilever(scenes)
    with pytest.raises(rodnet.Error, match="unknown option 'tolerance'"):
        rodnet.solve(s, tolerance=1)
    with pytest.raises(rodnet.Error, match="solver 'newton': unknown; known: tr-minres"):
        rodnet.solve(s, "newton")
    with pytest.raises(rodnet.Error, match="preconditioner"):
        rodnet.solve(s, "tr-krylov", preconditioner="ilu")
    with pytest.raises(rodnet.Error, match="max_iterations"):
        rodnet.solve(s, max_iterations=0)
    with pytest.raises(rodnet.Error, match="not a number"):
        rodnet.solve(s, gtol="tight")
    o = s.objective()
    with pytest.raises(rodnet.Error, match="expected shape"):
        o.value(np.zeros(3))
    with pytest.raises(rodnet.Error, match="not finite|NaN|finite"):
        o.gradient(np.full(o.n, np.nan))
    with pytest.raises(rodnet.Error, match="no rod called"):
        s.positions("nothing")
    with pytest.raises(rodnet.Error, match="not periodic"):
        rodnet.homogenize(s)
    n = rodnet.Network()
    with pytest.raises(rodnet.Error, match="zero-length|degenerate|length"):
        n.add_rod([[0, 0, 0], [0, 0, 0], [1, 0, 0]])
    with pytest.raises(rodnet.Error):
        n.add_rod([[0, 0, 0], [np.nan, 0, 0]])
    with pytest.raises(rodnet.Error, match="not finalized"):
        rodnet.solve(n)
    with pytest.raises(rodnet.Error, match="nv x 3"):
        n.add_rod([0, 1, 2])
    n.add_rod([[0, 0, 0], [1, 0, 0]])  # no material, no section
    with pytest.raises(rodnet.Error):
        n.finalize()
    with pytest.raises(rodnet.Error, match="expected 3 components"):
        rodnet.homogenize(rodnet.load_scene(hc8), path=[1, 2])
    with pytest.raises(rodnet.Error, match="'x' is not a number"):
        rodnet.homogenize(rodnet.load_scene(hc8), path="1,-,x")
    with pytest.raises(rodnet.Error, match="not finalized"):
        rodnet.homogenize(rodnet.Network(periodic=[[1, 0, 0], [0, 1, 0]]))


def test_layout_checked_against_the_library():
    import ctypes
    from rodnet import _ffi
    for name, cls in _ffi._MIRRORED.items():
        assert _ffi.fn.rn_abi_sizeof(name.encode()) == ctypes.sizeof(cls)
        assert _ffi.fn.rn_abi_num_fields(name.encode()) == len(cls._fields_)
        for f in cls._fields_:
            assert _ffi.fn.rn_abi_offsetof(name.encode(), f[0].encode()) == \
                getattr(cls, f[0]).offset


# ---- the benchmark suite's problems ----------------------------------------------------
def test_bench_problems_and_rows(tmp_path):
    ps = rodnet.bench.problems("quick")
    assert len(ps) >= 10 and all(p.reference is not None for p in ps)
    p = next(q for q in ps if q.name == "cantilever")
    s = p.load()
    r = rodnet.solve(s)
    assert p.error(s) < 1e-6
    o = p.objective()
    assert p.error_of(o, o.x0) == pytest.approx(1.0, rel=1e-6)  # the start: error 1
    out = tmp_path / "runs.csv"
    rodnet.bench.write_rows(out, [rodnet.bench.row(p, "py-test", converged=True,
                                                   verified_minimum=1, iterations=r.iterations,
                                                   gradients=r.gradient_evals, hvps=r.hvp_evals,
                                                   time_s=r.time_s, error=p.error(s),
                                                   dofs=r.num_dofs)])
    rodnet.bench.write_rows(out, [rodnet.bench.row(p, "py-test-2", converged=False)])
    import csv
    rows = list(csv.DictReader(open(out)))
    assert list(rows[0].keys()) == rodnet.bench.COLUMNS and len(rows) == 2
    assert rows[0]["converged"] == "1" and rows[1]["solver"] == "py-test-2"
    with pytest.raises(rodnet.Error, match="unknown column"):
        rodnet.bench.row(p, "x", speed=1)
