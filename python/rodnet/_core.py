"""Scenes, networks, solves, objectives and homogenisation over the C ABI."""
import ctypes
import math
import signal
import sys
import threading

import numpy as np

from . import _ffi
from ._ffi import Error, fn, ptr

_JOINT_MODELS = {"elastic": 0, "rigid": 1, "smooth": 2}
_ENDS = {"start": 0, "end": 1, 0: 0, 1: 1}
_SUPPORT_KINDS = ("clamp", "vertex", "angle", "joint")
_MODES = {"all": 0, "in-plane": 1, "out-of-plane": 2}
_BLOCH_METHODS = {"auto": 0, "dense": 1, "sparse": 2}
_STAB_METHODS = {"auto": 0, "cholesky": 1, "lobpcg": 2}


def _f64(a, shape=None, what="array"):
    """a as a C-contiguous float64 array (a view when it already is one)."""
    try:
        out = np.ascontiguousarray(a, dtype=np.float64)
    except (TypeError, ValueError) as e:
        raise Error("%s: not an array of numbers (%s)" % (what, e)) from None
    if shape is not None and out.shape != shape:
        raise Error("%s: expected shape %s, got %s" % (what, shape, out.shape))
    return out


class _Context:
    """An rn_context: the last error's message."""

    def __init__(self):
        self.handle = ctypes.c_void_p()
        if fn.rn_context_create(ctypes.byref(self.handle)) != 0:
            raise MemoryError("rodnet: cannot create a context")

    def message(self):
        return _ffi.text(fn.rn_context_last_error(self.handle))

    def check(self, st, where):
        if st < 0:
            msg = self.message() or "%s: %s" % (where, _ffi.status_name(st))
            fn.rn_context_clear_error(self.handle)
            raise Error(msg, _ffi.status_name(st), st)
        return st

    def __del__(self):
        if getattr(self, "handle", None) and fn is not None:
            fn.rn_context_destroy(ctypes.byref(self.handle))


class _Model:
    """What a Scene and a Network share: a finalized rn_network and its results.
    Indices of rods and joints are the network's (0-based); rods and joints may
    also be named."""

    _net = None

    # ---- sizes and names ---------------------------------------------------
    @property
    def num_dofs(self):
        """Free (reduced) degrees of freedom."""
        return int(fn.rn_network_num_dofs(self._handle()))

    @property
    def num_rods(self):
        return int(fn.rn_network_num_rods(self._handle()))

    @property
    def num_joints(self):
        return int(fn.rn_network_num_joints(self._handle()))

    def rod_names(self):
        return [_ffi.text(fn.rn_network_rod_name(self._handle(), r))
                for r in range(self.num_rods)]

    def joint_names(self):
        return [_ffi.text(fn.rn_network_joint_name(self._handle(), j))
                for j in range(self.num_joints)]

    def rod_index(self, rod):
        """The index of rod (an index or a name)."""
        if isinstance(rod, (int, np.integer)):
            r = int(rod)
            if r < 0:
                r += self.num_rods
            if not 0 <= r < self.num_rods:
                raise Error("rod %d: out of range (the network has %d rods)"
                            % (rod, self.num_rods), "RN_ERR_RANGE", -4)
            return r
        names = self.rod_names()
        if rod in names:
            return names.index(rod)
        raise Error("no rod called %r (rods: %s)" % (rod, ", ".join(names[:20])),
                    "RN_ERR_RANGE", -4)

    def joint_index(self, joint):
        if isinstance(joint, (int, np.integer)):
            j = int(joint)
            if not 0 <= j < self.num_joints:
                raise Error("joint %d: out of range (%d joints)" % (j, self.num_joints),
                            "RN_ERR_RANGE", -4)
            return j
        names = self.joint_names()
        if joint in names:
            return names.index(joint)
        raise Error("no joint called %r" % (joint,), "RN_ERR_RANGE", -4)

    def _handle(self):
        if not self._net:
            raise Error("the network is not finalized", "RN_ERR_STATE", -3)
        return self._net

    def _call(self, f, *args, where=None):
        return self._ctx.check(f(*args), where or f.__name__)

    # ---- state ---------------------------------------------------------------
    @property
    def load_factor(self):
        return float(fn.rn_network_load_factor(self._handle()))

    @load_factor.setter
    def load_factor(self, lam):
        self._call(fn.rn_network_set_load_factor, self._handle(), float(lam))

    def dofs(self):
        """The current state's free DOFs (a new array)."""
        x = np.empty(self.num_dofs)
        self._call(fn.rn_network_get_dofs, self._handle(), ptr(x))
        return x

    def set_dofs(self, x):
        x = _f64(x, (self.num_dofs,), "set_dofs: x")
        self._call(fn.rn_network_set_dofs, self._handle(), ptr(x))

    def save_state(self):
        """An opaque snapshot of the whole mutable state (DOFs, reference frames,
        load factor); restore_state(snapshot) brings it back."""
        return _State(self)

    def restore_state(self, snap):
        self._call(fn.rn_network_state_restore, self._handle(), snap.handle)

    # ---- results of the current state ------------------------------------------
    def positions(self, rod):
        """Vertices of rod (index or name) at the current state, nv x 3."""
        r = self.rod_index(rod)
        nv = fn.rn_network_rod_num_vertices(self._handle(), r)
        out = np.empty((nv, 3))
        self._call(fn.rn_network_rod_vertices, self._handle(), r, ptr(out))
        return out

    def theta(self, rod):
        """Material angles of rod's edges (nv - 1)."""
        r = self.rod_index(rod)
        out = np.empty(fn.rn_network_rod_num_vertices(self._handle(), r) - 1)
        self._call(fn.rn_network_rod_theta, self._handle(), r, ptr(out))
        return out

    def frames(self, rod):
        """Material directors (d1, d2) of rod's edges, each (nv - 1) x 3."""
        r = self.rod_index(rod)
        ne = fn.rn_network_rod_num_vertices(self._handle(), r) - 1
        d1, d2 = np.empty((ne, 3)), np.empty((ne, 3))
        self._call(fn.rn_network_rod_frames, self._handle(), r, ptr(d1), ptr(d2))
        return d1, d2

    def internal_forces(self, rod):
        """Internal force and moment per edge of rod (global frame), each ne x 3:
        what the part after the edge's midpoint exerts on the part before it."""
        r = self.rod_index(rod)
        ne = fn.rn_network_rod_num_vertices(self._handle(), r) - 1
        f, m = np.empty((ne, 3)), np.empty((ne, 3))
        self._call(fn.rn_network_rod_internal_forces, self._handle(), r, ptr(f), ptr(m))
        return f, m

    def joint_position(self, joint):
        x = np.empty(3)
        self._call(fn.rn_network_joint_position, self._handle(), self.joint_index(joint),
                   ptr(x))
        return x

    def joint_rotation(self, joint):
        R = np.empty((3, 3))
        self._call(fn.rn_network_joint_rotation, self._handle(), self.joint_index(joint),
                   ptr(R))
        return R

    def energy(self):
        """Total energy at the current state."""
        E = ctypes.c_double()
        self._call(fn.rn_network_energy, self._handle(), ptr(self.dofs()), ctypes.byref(E))
        return E.value

    def energy_terms(self):
        """The energy by term at the current state: stretch, bend, twist, load."""
        E = np.empty(4)
        x = self.dofs()
        self._call(fn.rn_network_energy_terms, self._handle(), ptr(x), ptr(E))
        return {"stretch": E[0], "bend": E[1], "twist": E[2], "load": E[3]}

    def reactions(self):
        """Every support's reaction at the current state, and the resultants of the
        reactions and of the applied loads (moments about the origin), as the
        "reactions" object of RESULT.json."""
        net = self._handle()
        ns = fn.rn_network_num_supports(net)
        x = self.dofs()
        arr = (_ffi.Reaction * max(ns, 1))()
        self._call(fn.rn_network_reactions, net, ptr(x), arr, ns)
        AF, AM = np.empty(3), np.empty(3)
        self._call(fn.rn_network_applied_resultant, net, ptr(AF), ptr(AM))
        supports, F, M = [], np.zeros(3), np.zeros(3)
        for i in range(ns):
            r = arr[i]
            d = {"kind": _SUPPORT_KINDS[r.kind]}
            if r.kind == 3:
                d["joint"] = _ffi.text(fn.rn_network_joint_name(net, r.index))
            else:
                d["rod"] = _ffi.text(fn.rn_network_rod_name(net, r.rod))
                if r.kind == 0:
                    d["end"] = "end" if r.index else "start"
                else:
                    d["vertex" if r.kind == 1 else "edge"] = r.index
            d["components"] = "".join(c for k, c in enumerate("xyz") if r.fixed & (1 << k))
            d["fixes_rotation"] = bool(r.fixed_rotation)
            d["point"] = np.array(r.point[:])
            d["force"] = np.array(r.force[:])
            d["moment"] = np.array(r.moment[:])
            F += d["force"]
            M += d["moment"] + np.cross(d["point"], d["force"])
            supports.append(d)
        return {"supports": supports, "resultant": {"force": F, "moment": M},
                "applied": {"force": AF, "moment": AM}}

    def stability(self):
        """Lowest eigenvalues of the Jacobi-scaled Hessian at the current state
        (rn_network_stability): a dict as the "stability" of RESULT.json."""
        s = _ffi.Stability()
        self._call(fn.rn_network_stability, self._handle(), ctypes.byref(s))
        return _stability_dict(s)

    def objective(self):
        """The energy over the free DOFs as an objective for any optimiser."""
        return Objective(self)

    def cell_info(self):
        """Periodic cell: dict(dim, nstrain, measure, vectors) (dim 0: not periodic)."""
        dim, ns, meas, vec = ctypes.c_int(), ctypes.c_int(), ctypes.c_double(), np.zeros(9)
        self._call(fn.rn_network_cell_info, self._handle(), ctypes.byref(dim),
                   ctypes.byref(ns), ctypes.byref(meas), ptr(vec))
        return {"dim": dim.value, "nstrain": ns.value, "measure": meas.value,
                "vectors": vec.reshape(3, 3)[:dim.value].copy()}


class _State:
    def __init__(self, model):
        self.handle = ctypes.c_void_p()
        self._model = model
        model._call(fn.rn_network_state_save, model._handle(), ctypes.byref(self.handle))

    def __del__(self):
        if getattr(self, "handle", None) and fn is not None:
            fn.rn_state_destroy(ctypes.byref(self.handle))


def _stability_dict(s):
    if not s.checked:
        return {"checked": False, "verified_minimum": False, "lowest_eigenvalue": None,
                "zero_modes": None}
    return {"checked": True, "lowest_eigenvalue": s.lowest_eigenvalue, "scale": s.scale,
            "verified_minimum": bool(s.verified_minimum), "zero_modes": s.zero_modes,
            "symmetries": s.symmetries if s.symmetries >= 0 else None,
            "soft_modes": s.soft_modes if s.soft_modes >= 0 else None,
            "soft_positive": s.soft_positive if s.symmetries >= 0 else None,
            "factorizations": s.factorizations, "time_s": s.time_s,
            "method": "lobpcg" if s.method == 2 else "cholesky",
            "iterations": s.iterations, "cholesky_flops": s.cholesky_flops}


class Scene(_Model):
    """A JSON scene (docs/scene-format.md) read by librodnet_scene: its finalized
    network, the rod and joint names and the scene's "solver" block."""

    def __init__(self, handle, ctx):
        self._ctx = ctx
        self._scene = handle
        self._net = fn.rn_scene_network(handle)

    @property
    def label(self):
        return _ffi.text(fn.rn_scene_label(self._scene))

    @property
    def description(self):
        return _ffi.text(fn.rn_scene_description(self._scene))

    @property
    def num_vertices(self):
        return int(fn.rn_scene_num_vertices(self._scene))

    def write_vtu(self, path):
        """The .vtu of the current state, as `rodnet solve --vtk` writes it."""
        self._ctx.check(fn.rn_scene_write_vtu(self._ctx.handle, self._scene,
                                              str(path).encode()), "write_vtu")

    def __del__(self):
        if getattr(self, "_scene", None) and fn is not None:
            fn.rn_scene_destroy(ctypes.byref(self._scene))
            self._net = None

    def __repr__(self):
        return "<rodnet.Scene %r: %d rods, %d joints, %d DOFs>" % (
            self.label, self.num_rods, self.num_joints, self.num_dofs)


def load_scene(path):
    """Read the scene in the JSON file at path; rodnet.Error (with the file, the
    JSON path and the reason) if it cannot be read or breaks the format."""
    ctx = _Context()
    h = ctypes.c_void_p()
    ctx.check(fn.rn_scene_load(ctx.handle, str(path).encode(), ctypes.byref(h)),
              "load_scene")
    return Scene(h, ctx)


def parse_scene(text, label="<string>"):
    """A scene from JSON text (str or bytes); label names it in messages."""
    if isinstance(text, str):
        text = text.encode()
    ctx = _Context()
    h = ctypes.c_void_p()
    ctx.check(fn.rn_scene_parse(ctx.handle, str(label).encode(), text, len(text),
                                ctypes.byref(h)), "parse_scene")
    return Scene(h, ctx)


class Network(_Model):
    """A network built from numpy arrays through the C API (rodnet.h): add rods,
    materials, sections, joints, constraints, loads or a periodic cell, then
    finalize() and solve or evaluate it as a Scene.  Indices are 0-based; ends
    are "start" / "end" (or 0 / 1)."""

    def __init__(self, periodic=None):
        self._ctx = _Context()
        self._build = ctypes.c_void_p()
        self._ctx.check(fn.rn_network_create(self._ctx.handle, ctypes.byref(self._build)),
                        "Network")
        self._net = None
        if periodic is not None:
            v = _f64(periodic, what="periodic vectors")
            if v.ndim != 2 or v.shape[1] != 3 or v.shape[0] not in (2, 3):
                raise Error("periodic: expected 2 or 3 lattice vectors of 3 components")
            self._b(fn.rn_network_set_periodic, v.shape[0], ptr(v))

    def _b(self, f, *args):
        if self._net:
            raise Error("%s: the network is finalized (its topology is frozen)"
                        % f.__name__, "RN_ERR_STATE", -3)
        return self._ctx.check(f(self._build, *args), f.__name__)

    @staticmethod
    def _vec3(v, what):
        return _f64(v, (3,), what) if v is not None else None

    def add_rod(self, xyz, name=None, d1=None, E=None, nu=0.5, density=0.0,
                radius=None, section=None, closed=False):
        """A rod through the vertices xyz (nv x 3); returns its index.  Material
        from E and nu (or set_material later); section a circle of radius or an
        rn section dict(A, I11, I22, I12, J) (or set_section later).  closed: a
        ring (rn_network_add_closed_rod; xyz without the repeated first vertex)."""
        x = _f64(xyz, what="add_rod: xyz")
        if x.ndim != 2 or x.shape[1] != 3:
            raise Error("add_rod: xyz must be nv x 3, got shape %s" % (x.shape,))
        d = self._vec3(d1, "add_rod: d1")
        rod = ctypes.c_int()
        nm = name.encode() if name is not None else None
        if closed:
            joint = ctypes.c_int()
            self._b(fn.rn_network_add_closed_rod, nm, x.shape[0], ptr(x), ptr(d),
                    ctypes.byref(rod), ctypes.byref(joint))
        else:
            self._b(fn.rn_network_add_rod, nm, x.shape[0], ptr(x), ptr(d),
                    ctypes.byref(rod))
        if E is not None:
            self.set_material(rod.value, E=E, nu=nu, density=density)
        if radius is not None or section is not None:
            self.set_section(rod.value, radius=radius, section=section)
        return rod.value

    def set_material(self, rod, E, nu=0.5, density=0.0, edge=-1):
        m = _ffi.Material()
        self._ctx.check(fn.rn_material_from_E_nu(float(E), float(nu), float(density),
                                                 ctypes.byref(m)), "set_material")
        self._b(fn.rn_network_set_material, int(rod), int(edge), ctypes.byref(m))

    def set_section(self, rod, radius=None, section=None, edge=-1):
        s = _ffi.Section()
        if section is not None:
            for k in ("A", "I11", "I22", "I12", "J"):
                setattr(s, k, float(section.get(k, 0.0)))
        elif radius is not None:
            st = fn.rn_section_circle(float(radius), ctypes.byref(s))
            if st:
                raise Error("set_section: radius %r: %s" % (radius, _ffi.status_name(st)))
        else:
            raise Error("set_section: give radius or section")
        self._b(fn.rn_network_set_section, int(rod), int(edge), ctypes.byref(s))

    def add_joint(self, ends, model="elastic", name=None, images=None):
        """A joint where the rod ends meet: ends a list of (rod, "start"|"end");
        model "elastic" (Perez et al. 2015), "rigid" or "smooth"; images: the
        lattice shift (3 integers) of each end in a periodic network."""
        if model not in _JOINT_MODELS:
            raise Error("add_joint: model %r: expected elastic, rigid or smooth" % (model,))
        n = len(ends)
        rods = (ctypes.c_int * max(n, 1))(*[int(r) for r, _ in ends])
        try:
            es = (ctypes.c_int * max(n, 1))(*[_ENDS[e] for _, e in ends])
        except KeyError as e:
            raise Error("add_joint: end %r: expected 'start' or 'end'" % (e.args[0],))
        j = ctypes.c_int()
        nm = name.encode() if name is not None else None
        if images is not None:
            im = np.ascontiguousarray(images, dtype=np.intc).reshape(-1)
            if im.size != 3 * n:
                raise Error("add_joint: images must hold 3 integers per end")
            self._b(fn.rn_network_add_joint_images, nm, _JOINT_MODELS[model], n, rods, es,
                    im.ctypes.data_as(_ffi.c_int_p), ctypes.byref(j))
        else:
            self._b(fn.rn_network_add_joint, nm, _JOINT_MODELS[model], n, rods, es,
                    ctypes.byref(j))
        return j.value

    # constraints and loads (before finalize)
    def clamp(self, rod, end):
        self._b(fn.rn_network_clamp, int(rod), _ENDS[end])

    def pin(self, rod, vertex, components="xyz"):
        mask = sum(1 << "xyz".index(c) for c in set(components))
        self._b(fn.rn_network_pin_components, int(rod), int(vertex), mask)

    def fix_theta(self, rod, edge):
        self._b(fn.rn_network_fix_theta, int(rod), int(edge))

    def displace_end(self, rod, end, displacement=None, rotation=None):
        self._b(fn.rn_network_displace_end, int(rod), _ENDS[end],
                ptr(self._vec3(displacement, "displacement")),
                ptr(self._vec3(rotation, "rotation")))

    def displace_vertex(self, rod, vertex, displacement):
        self._b(fn.rn_network_displace_vertex, int(rod), int(vertex),
                ptr(self._vec3(displacement, "displacement")))

    def add_force(self, rod, vertex, force):
        self._b(fn.rn_network_add_force, int(rod), int(vertex), ptr(self._vec3(force, "force")))

    def add_moment(self, rod, vertex, moment):
        self._b(fn.rn_network_add_moment, int(rod), int(vertex),
                ptr(self._vec3(moment, "moment")))

    def add_line_load(self, rod, w):
        self._b(fn.rn_network_add_line_load, int(rod), ptr(self._vec3(w, "line load")))

    def add_gravity(self, g):
        self._b(fn.rn_network_add_gravity, ptr(self._vec3(g, "gravity")))

    def clamp_joint(self, joint):
        self._b(fn.rn_network_clamp_joint, int(joint))

    def pin_joint(self, joint, components="xyz"):
        mask = sum(1 << "xyz".index(c) for c in set(components))
        self._b(fn.rn_network_pin_joint_components, int(joint), mask)

    def displace_joint(self, joint, displacement=None, rotation=None):
        self._b(fn.rn_network_displace_joint, int(joint),
                ptr(self._vec3(displacement, "displacement")),
                ptr(self._vec3(rotation, "rotation")))

    def add_joint_force(self, joint, force):
        self._b(fn.rn_network_add_joint_force, int(joint), ptr(self._vec3(force, "force")))

    def add_joint_moment(self, joint, moment):
        self._b(fn.rn_network_add_joint_moment, int(joint), ptr(self._vec3(moment, "moment")))

    def set_cell_strain(self, strain, fixed=None):
        """Prescribe macroscopic strain components (Voigt, engineering shear): a
        component is prescribed where fixed (default: where strain is not None)."""
        vals = [0.0 if s is None else float(s) for s in strain]
        fx = [int(s is not None) for s in strain] if fixed is None else [int(bool(f)) for f in fixed]
        n = len(vals)
        self._b(fn.rn_network_set_cell_strain, (ctypes.c_int * n)(*fx),
                ptr(np.array(vals, dtype=np.float64)))

    def set_cell_stress(self, stress):
        self._b(fn.rn_network_set_cell_stress, ptr(_f64(stress, what="stress")))

    def finalize(self):
        """Validate and freeze the network; returns self."""
        self._b(fn.rn_network_finalize)
        self._net = self._build
        return self

    def _handle(self):
        if not self._net:
            raise Error("the network is not finalized: call finalize() first",
                        "RN_ERR_STATE", -3)
        return self._net

    def __del__(self):
        if getattr(self, "_build", None) and fn is not None:
            fn.rn_network_destroy(ctypes.byref(self._build))
            self._net = None


# ---- solves --------------------------------------------------------------------------
def _names(f, count):
    out = []
    for k in range(count):
        s = _ffi.text(f(k))
        if s and s != "unknown":
            out.append(s)
    return out


def _from_name(kind, value, parse, names):
    v = ctypes.c_int()
    if not isinstance(value, str) or parse(value.encode(), ctypes.byref(v)) != 0:
        raise Error("%s %r: unknown; known: %s" % (kind, value, ", ".join(names)))
    return v.value


_OPTION_FIELDS = {"gtol": "gtol_rel", "gtol_rel": "gtol_rel", "gtol_abs": "gtol_abs",
                  "max_iterations": "max_iterations", "max_iter": "max_iterations",
                  "step_tol": "step_tol", "energy_tol": "energy_tol",
                  "krylov_max_iterations": "krylov_max_iterations",
                  "krylov_tol": "krylov_tol", "initial_radius": "initial_radius",
                  "load_steps": "load_steps", "max_load_cuts": "max_load_cuts",
                  "predictor": "predictor", "stability": "stability",
                  "forcing": "forcing"}
_OPTION_TYPES = dict(_ffi.SolveOptions._fields_)
_OPTION_WORDS = ("solver", "preconditioner", "factorization", "factorisation",
                 "stability_method", "progress")


def solve_options(model=None, solver=None, **options):
    """The rn_solve_options of a solve: the defaults, then the scene's "solver"
    block, then solver and options (the names of `rodnet solve`'s options)."""
    o = _ffi.SolveOptions()
    fn.rn_solve_options_default(ctypes.byref(o))
    if isinstance(model, Scene):
        fn.rn_scene_apply_solver(model._scene, ctypes.byref(o))
    if solver is not None:
        o.solver = _from_name("solver", solver, fn.rn_solver_from_name,
                              _names(fn.rn_solver_name, 6))
    for k, v in options.items():
        if k == "preconditioner":
            o.preconditioner = _from_name("preconditioner", v, fn.rn_preconditioner_from_name,
                                          _names(fn.rn_preconditioner_name, 9))
        elif k in ("factorization", "factorisation"):
            o.factorization = _from_name("factorization", v, fn.rn_factorization_from_name,
                                         _names(fn.rn_factorization_name, 4))
        elif k == "stability_method":
            if v not in _STAB_METHODS:
                raise Error("stability_method %r: expected auto, cholesky or lobpcg" % (v,))
            o.stability_method = _STAB_METHODS[v]
        elif k in _OPTION_FIELDS:
            field = _OPTION_FIELDS[k]
            try:
                setattr(o, field, int(v) if _OPTION_TYPES[field] is ctypes.c_int else float(v))
            except (TypeError, ValueError):
                raise Error("option %s: %r is not a number" % (k, v)) from None
        elif k == "progress":
            pass
        else:
            raise Error("unknown option %r; known: %s" % (
                k, ", ".join(sorted(set(_OPTION_FIELDS) | set(_OPTION_WORDS)))))
    return o


class Result:
    """The outcome of rodnet.solve: the report's numbers (as in RESULT.json) and a
    snapshot of the state it returned (positions, reactions)."""

    def __init__(self, model, rep, opt):
        self.status = "converged" if rep.converged else _ffi.text(fn.rn_solve_stop_name(rep.stop))
        self.stop_reason = _ffi.text(fn.rn_solve_stop_name(rep.stop))
        self.converged = bool(rep.converged)
        self.solver = _ffi.text(fn.rn_solver_name(opt.solver))
        self.preconditioner = _ffi.text(fn.rn_preconditioner_name(rep.preconditioner))
        self.factorization = _ffi.text(fn.rn_factorization_name(rep.factorization))
        for k in ("iterations", "energy_evals", "gradient_evals", "hvp_evals",
                  "hessian_evals", "krylov_iterations", "load_steps", "factorizations",
                  "predictor_steps", "energy", "gradient_norm", "initial_gradient_norm",
                  "time_s", "force_residual", "moment_residual", "force_scale",
                  "moment_scale", "force_tolerance", "moment_tolerance",
                  "hessian_seconds", "preconditioner_setup_seconds",
                  "preconditioner_apply_seconds"):
            setattr(self, k, getattr(rep, k))
        self.stability = (_stability_dict(rep.stability) if opt.stability and
                          rep.stability.checked else {"checked": False,
                                                      "verified_minimum": False,
                                                      "lowest_eigenvalue": None,
                                                      "zero_modes": None})
        self.load_factor = model.load_factor
        self.num_dofs = model.num_dofs
        self._rods = model.rod_names()
        self._pos = [model.positions(r) for r in range(len(self._rods))]
        self._theta = [model.theta(r) for r in range(len(self._rods))]
        self.dofs = model.dofs()
        self.reactions = model.reactions() if self.stop_reason != "failed" else None

    def positions(self, rod):
        """Vertices (nv x 3) of rod (name or index) at the returned state."""
        if isinstance(rod, (int, np.integer)):
            return self._pos[int(rod)]
        if rod not in self._rods:
            raise Error("no rod called %r" % (rod,), "RN_ERR_RANGE", -4)
        return self._pos[self._rods.index(rod)]

    def theta(self, rod):
        if isinstance(rod, (int, np.integer)):
            return self._theta[int(rod)]
        return self._theta[self._rods.index(rod)]

    @property
    def rods(self):
        return list(self._rods)

    def __repr__(self):
        return ("<rodnet.Result %s: energy %.10g, %d iterations, |g| %.3g, %.3g s>"
                % (self.status, self.energy, self.iterations, self.gradient_norm,
                   self.time_s))


def _progress_line(it):
    sys.stderr.write("iter %4d  E % .10e  |g| %.3e  radius %.3e  krylov %4d  %8.3f s  "
                     "load %.4g\n" % (it["iteration"], it["energy"], it["gradient_norm"],
                                      it["radius"], it["krylov_iterations"],
                                      it["seconds"], it["load_factor"]))


def solve(model, solver=None, progress=None, **options):
    """Equilibrium of a Scene or a finalized Network from its current state, as
    `rodnet solve` computes it (the scene's "solver" block, then solver and
    options: preconditioner, factorization, gtol, gtol_abs, max_iterations,
    load_steps, predictor, stability, stability_method, ...).  The model is left
    at the returned state.  progress: None (quiet), True (one line per Newton
    iteration on stderr) or a callable given a dict per Newton iteration.
    Ctrl-C (SIGINT) stops the solve at its next iteration check: the Result then
    has status "interrupted".  The GIL is released while the library runs.
    Raises rodnet.Error when the solver cannot run (bad options, bad network)."""
    if not isinstance(model, _Model):
        raise Error("solve: expected a rodnet.Scene or a finalized rodnet.Network, got %s"
                    % type(model).__name__)
    opt = solve_options(model, solver, **options)
    flag = ctypes.c_int(0)
    opt.interrupt = ctypes.pointer(flag)
    user = progress if callable(progress) else (_progress_line if progress else None)
    failure = []

    def on_iteration(_, info):
        if user is None or failure:
            return
        i = info.contents
        try:
            user({"iteration": i.iteration, "energy": i.energy,
                  "gradient_norm": i.gradient_norm, "radius": i.radius,
                  "krylov_iterations": i.krylov_iterations, "seconds": i.seconds,
                  "load_factor": i.load_factor})
        except BaseException as e:  # stop the solve, re-raised below
            failure.append(e)
            flag.value = 1

    cb = _ffi.PROGRESS(on_iteration)
    opt.progress = cb
    rep = _ffi.SolveReport()
    old = None
    if threading.current_thread() is threading.main_thread():
        def on_sigint(signum, frame):
            flag.value = 1
        try:
            old = signal.signal(signal.SIGINT, on_sigint)
        except ValueError:
            old = None
    try:
        st = fn.rn_solve(model._handle(), ctypes.byref(opt), ctypes.byref(rep))
    finally:
        if old is not None:
            signal.signal(signal.SIGINT, old)
    model._ctx.check(st, "rn_solve")
    if failure:
        raise failure[0]
    return Result(model, rep, opt)


# ---- the objective ---------------------------------------------------------------
class Objective:
    """The energy over the free (reduced) DOFs of a model, for any optimiser.

    x0 is the model's current state.  Every evaluation is relative to the
    model's current reference frames (those of x0): the DER energy is a smooth
    function of x there as long as no edge turns by close to 180 degrees from
    its reference tangent.  After a large step, accept(x) moves the reference
    frames to x (time-parallel transport) and returns the updated x (rigid
    joints' rotation DOFs reset to 0; energy unchanged), which is the new x0:
    restart the optimiser from it.  value(x) is inf at a degenerate trial point
    (a zero-length edge), so that trust-region and line-search methods reject
    the step."""

    def __init__(self, model):
        self.model = model
        self._net = model._handle()
        self.n = model.num_dofs
        self.x0 = model.dofs()
        self.evaluations = {"value": 0, "gradient": 0, "hessp": 0, "hessian": 0}
        self._pattern = None

    def _x(self, x, what="x"):
        return _f64(x, (self.n,), what)

    def _status(self, st, where):
        return self.model._ctx.check(st, where)

    def value(self, x):
        x = self._x(x)
        E = ctypes.c_double()
        self.evaluations["value"] += 1
        st = self._status(fn.rn_network_energy(self._net, ptr(x), ctypes.byref(E)), "value")
        return math.inf if st > 0 else E.value

    __call__ = value

    def gradient(self, x):
        x = self._x(x)
        g = np.empty(self.n)
        self.evaluations["gradient"] += 1
        st = self._status(fn.rn_network_gradient(self._net, ptr(x), None, ptr(g)),
                          "gradient")
        if st > 0:
            raise Error("gradient: degenerate configuration at x (%s)" % _ffi.status_name(st),
                        _ffi.status_name(st), st)
        return g

    def value_and_gradient(self, x):
        """(E, g) in one evaluation (scipy: jac=True)."""
        x = self._x(x)
        g = np.empty(self.n)
        E = ctypes.c_double()
        self.evaluations["gradient"] += 1
        st = self._status(fn.rn_network_gradient(self._net, ptr(x), ctypes.byref(E), ptr(g)),
                          "value_and_gradient")
        if st > 0:
            return math.inf, np.full(self.n, np.nan)
        return E.value, g

    def hessp(self, x, p):
        """H(x) p, matrix-free."""
        x = self._x(x)
        p = self._x(p, "p")
        out = np.empty(self.n)
        self.evaluations["hessp"] += 1
        st = self._status(fn.rn_network_hvp(self._net, ptr(x), ptr(p), ptr(out)), "hessp")
        if st > 0:
            raise Error("hessp: degenerate configuration at x", _ffi.status_name(st), st)
        return out

    def hessian_pattern(self):
        """(indptr int64 [n+1], indices int32 [nnz]) of the Hessian (both
        triangles); read-only views of the library's arrays."""
        nnz = ctypes.c_size_t()
        rp, col = _ffi.i64p(), _ffi.i32p()
        self._status(fn.rn_network_hessian_pattern(self._net, ctypes.byref(nnz),
                                                   ctypes.byref(rp), ctypes.byref(col)),
                     "hessian_pattern")
        indptr = np.ctypeslib.as_array(rp, shape=(self.n + 1,))
        indices = np.ctypeslib.as_array(col, shape=(nnz.value,)) if nnz.value else \
            np.zeros(0, np.int32)
        indptr.flags.writeable = False
        indices.flags.writeable = False
        return indptr, indices

    def hessian(self, x):
        """H(x) as a scipy.sparse CSR matrix (both triangles); without scipy a
        dense numpy array."""
        x = self._x(x)
        indptr, indices = self.hessian_pattern()
        vals = np.empty(indices.shape[0])
        self.evaluations["hessian"] += 1
        st = self._status(fn.rn_network_hessian_values(self._net, ptr(x), ptr(vals)),
                          "hessian")
        if st > 0:
            raise Error("hessian: degenerate configuration at x", _ffi.status_name(st), st)
        try:
            import scipy.sparse as sp
        except ImportError:
            H = np.zeros((self.n, self.n))
            for i in range(self.n):
                H[i, indices[indptr[i]:indptr[i + 1]]] = vals[indptr[i]:indptr[i + 1]]
            return H
        return sp.csr_matrix((vals, indices, indptr), shape=(self.n, self.n))

    def accept(self, x):
        """Make x the model's state and move the reference frames to it; returns
        the updated x (also the new x0)."""
        x = np.array(self._x(x), dtype=np.float64, copy=True)
        self._status(fn.rn_network_update_reference(self._net, ptr(x)), "accept")
        self.x0 = x.copy()
        return x


# ---- homogenisation -----------------------------------------------------------------
def _constants(n, S):
    s = lambda i, j: S[i, j]
    if n == 3:
        return {"E1": 1 / s(0, 0), "E2": 1 / s(1, 1), "nu12": -s(0, 1) / s(0, 0),
                "nu21": -s(0, 1) / s(1, 1), "G12": 1 / s(2, 2)}
    return {"E1": 1 / s(0, 0), "E2": 1 / s(1, 1), "E3": 1 / s(2, 2),
            "nu12": -s(0, 1) / s(0, 0), "nu13": -s(0, 2) / s(0, 0),
            "nu23": -s(1, 2) / s(1, 1), "nu21": -s(0, 1) / s(1, 1),
            "nu31": -s(0, 2) / s(2, 2), "nu32": -s(1, 2) / s(2, 2),
            "G23": 1 / s(3, 3), "G13": 1 / s(4, 4), "G12": 1 / s(5, 5)}


def _path_controls(path, n, stress_default):
    """(targets, stress flags) of a path as `rodnet homogenize --path` takes it: a
    string "E,E,E" or a sequence; an entry is a number (strain, or stress when
    stress_default), None or "-" (stress-controlled at zero stress), "s:V" or
    "e:V"."""
    items = path.split(",") if isinstance(path, str) else list(path)
    if len(items) != n:
        raise Error("path %r: expected %d components (%s) for this cell" % (
            path, n, "E11,E22,E12" if n == 3 else "E11,E22,E33,E23,E13,E12"))
    tgt, st = [], []
    for it in items:
        s = stress_default
        if it is None or (isinstance(it, str) and it.strip() == "-"):
            v, s = 0.0, True
        elif isinstance(it, str) and it.strip()[:2] in ("s:", "e:"):
            s = it.strip()[0] == "s"
            v = it.strip()[2:]
        else:
            v = it
        try:
            v = float(v)
        except (TypeError, ValueError):
            raise Error("path %r: %r is not a number, '-', s:VALUE or e:VALUE" % (path, it))
        if not math.isfinite(v):
            raise Error("path %r: %r is not finite" % (path, it))
        tgt.append(v)
        st.append(int(bool(s)))
    return tgt, st


def _vec(a, n):
    return [float(a[i]) for i in range(n)]


def _num(v):
    return float(v) if math.isfinite(v) else None


def _path_dict(res, ns, dim, target, steps, modes):
    segs = [res.seg[j] for j in range(res.nseg)]
    ctl = lambda g: ["stress" if g.stress[v] else "strain" for v in range(ns)]
    nstress = sum(segs[0].stress[v] for v in range(ns)) if segs else 0
    out = {"path_target": list(target), "path_steps": steps, "bloch_modes": modes,
           "path_kind": "strain" if nstress == 0 else "stress" if nstress == ns else "mixed",
           "path_segments": [{"control": ctl(g), "start": _vec(g.start, ns),
                              "target": _vec(g.target, ns), "steps": g.steps}
                             for g in segs],
           "path": []}
    for k in range(res.done + 1):
        s = res.step[k]
        out["path"].append({
            "step": k, "load_factor": s.t, "strain": _vec(s.strain, ns),
            "stress": _vec(s.stress, ns), "energy": s.energy,
            "newton_iterations": s.newton,
            "stable": True if s.stable == 1 else False if s.stable == 0 else None,
            "segment": s.seg, "control": ctl(segs[s.seg]), "mixed_iterations": s.outer,
            "tangent_min": _num(s.tangent_min), "bloch_min": _num(s.local_min),
            "acoustic_min": _num(s.acoustic_min)})
    if res.stopped:
        out["path_stopped"] = _ffi.text(res.stopped)
        out["partial"] = True
    if res.limit_end == 1:
        out["path_end"] = "limit point of the stress (no equilibrium beyond)"
    elif res.limit_end == 2:
        out["path_end"] = ("past the instability the cell-periodic fluctuations are "
                           "unstable: no tangent for the stress control")
    inst = res.inst
    if not inst.found:
        out["instability"] = None
        return out
    d = {"strain": _vec(inst.strain, ns), "stress": _vec(inst.stress, ns),
         "wave_vector": _vec(inst.xi, dim)}
    if not inst.kind_macroscopic and inst.nequiv > 0:
        d["equivalent_wave_vectors"] = [_vec(inst.xi_equiv[e], dim)
                                        for e in range(inst.nequiv)]
    d["kind"] = "macroscopic" if inst.kind_macroscopic else "local"
    d["criterion"] = ("stress_limit" if inst.stress_limit else
                      "cell_periodic_fluctuations" if inst.cell_periodic else
                      "rank_one_convexity" if inst.kind_macroscopic else "bloch")
    d["multiplicity"] = inst.multiplicity
    d["load_factor"] = inst.t
    d["bloch_eigenvalues"] = _vec(inst.eig, inst.neig)
    if inst.stress_limit:
        d["strain_mode"] = _vec(inst.mode, ns)
    elif inst.kind_macroscopic:
        d["direction"] = _vec(inst.direction, 3)
        d["amplitude"] = _vec(inst.amplitude, 3)
    d["bisections"] = inst.bisections
    out["instability"] = d
    return out


def homogenize(model, path=None, steps=20, stress=False, modes="all", bloch_grid=0,
               progress=None, bloch_method="auto"):
    """Effective linear stiffness of a periodic cell at its current (rest) state,
    as `rodnet homogenize` computes it: a dict with "C" (numpy, Voigt with
    engineering shear, per unit cell area in 2D / volume in 3D), "constants"
    (E1, E2, nu12, ..., G12), "relative_density", "dimension", "area" or
    "volume", "voigt", "fluctuation_dofs".

    path: follow the proportional macroscopic path from the rest state to this
    target (`--path`: "E,E,E" or a sequence; None or "-" a stress-controlled
    component at zero stress, "s:V" / "e:V" mixed; stress=True: every number a
    stress, `--path-stress`) in steps steps, with the Bloch-Floquet test at
    every step (modes: all, in-plane, out-of-plane; bloch_grid as
    `--bloch-grid`, bloch_method as `--bloch-method`: auto, dense, sparse); the dict gains "path", "path_segments", "instability"
    (None if the path is stable) and, if it stopped early, "path_stopped" and
    "partial": True.  progress: a callable given each step's dict."""
    net = model._handle()
    info = model.cell_info()
    if info["dim"] == 0:
        raise Error("%s: the scene is not periodic (it has no top-level \"periodic\" "
                    "object with lattice vectors)" % getattr(model, "label", "network"))
    if modes not in _MODES:
        raise Error("modes %r: expected all, in-plane or out-of-plane" % (modes,))
    if bloch_method not in _BLOCH_METHODS:
        raise Error("bloch_method %r: expected auto, dense or sparse" % (bloch_method,))
    if path is not None and modes != "all" and info["dim"] == 3:
        raise Error("modes %s: a 3D cell has no in-plane / out-of-plane split of its "
                    "modes (use modes='all')" % modes)
    ns = info["nstrain"]
    seg = None
    if path is not None:
        if int(steps) < 1:
            raise Error("steps: %r must be at least 1" % (steps,))
        tgt, flags = _path_controls(path, ns, stress)
        seg = _ffi.CellPathSegment()
        seg.steps = int(steps)
        for v in range(ns):
            seg.target[v] = tgt[v]
            seg.stress[v] = flags[v]
    h = _ffi.Homogenization()
    model._ctx.check(fn.rn_homogenize(net, ctypes.byref(h)), "rn_homogenize")
    n = h.nstrain
    C = np.array(h.C[:n * n]).reshape(n, n)
    S = np.empty((n, n))
    Cc = np.ascontiguousarray(C)
    if not fn.rn_homogenization_invert(n, ptr(Cc), ptr(S)):
        raise Error("homogenize: the effective stiffness is singular (a mechanism)",
                    "RN_ERR_SOLVER", -9)
    out = {"dimension": h.dim, ("area" if h.dim == 2 else "volume"): h.measure,
           "relative_density": h.relative_density,
           "voigt": ["11", "22", "12"] if n == 3 else ["11", "22", "33", "23", "13", "12"],
           "C": C, "constants": _constants(n, S), "fluctuation_dofs": int(h.fluctuation_dofs)}
    if seg is None:
        return out
    o = _ffi.CellPathOptions()
    fn.rn_cell_path_options_default(ctypes.byref(o))
    o.grid = int(bloch_grid)
    o.modes = _MODES[modes]
    o.bloch_method = _BLOCH_METHODS[bloch_method]
    failure = []

    def on_step(_, r):
        if progress is None or failure:
            return
        res = r.contents
        s = res.step[res.done]
        try:
            progress({"step": res.done, "steps": res.steps, "load_factor": s.t,
                      "strain": _vec(s.strain, ns), "stress": _vec(s.stress, ns),
                      "newton_iterations": s.newton,
                      "stable": True if s.stable == 1 else False if s.stable == 0 else None})
        except BaseException as e:
            failure.append(e)

    cb = _ffi.CELL_PROGRESS(on_step)
    o.progress = cb
    res = _ffi.CellPathResult()
    try:
        st = fn.rn_cell_path_run(net, 1, ctypes.byref(seg), ctypes.byref(o),
                                 ctypes.byref(res))
        model._ctx.check(st, "rn_cell_path_run")
        out.update(_path_dict(res, ns, h.dim, tgt, int(steps), modes))
    finally:
        fn.rn_cell_path_result_free(ctypes.byref(res))
    if failure:
        raise failure[0]
    return out
