"""The C ABI of librodnet and librodnet_scene through ctypes (no compiler).

Every struct mirrored here is checked field by field against the library's own
layout table (rn_abi_sizeof / rn_abi_offsetof, c_api/abi/abi.c) when the module
is imported: a package that does not match its library refuses to load instead
of reading the wrong bytes.
"""
import ctypes
import ctypes.util
import os

c_double_p = ctypes.POINTER(ctypes.c_double)
c_int_p = ctypes.POINTER(ctypes.c_int)


class Error(Exception):
    """An error of rodnet: the library's status and its message (file, place and
    reason).  ``status`` is the status name (e.g. ``"RN_ERR_PARSE"``), ``code``
    its number."""

    def __init__(self, message, status="RN_ERR_ARG", code=-2):
        super().__init__(message)
        self.message = message
        self.status = status
        self.code = code


# ---- the libraries ---------------------------------------------------------------
def _candidates(env, name):
    out = []
    if os.environ.get(env):
        out.append(os.environ[env])
    here = os.path.dirname(os.path.abspath(__file__))
    try:
        from . import _config  # written by CMake: the build tree's or the install's
        for d in _config.library_dirs:
            d = d if os.path.isabs(d) else os.path.normpath(os.path.join(here, d))
            out.append(os.path.join(d, name + ".so.0"))
            out.append(os.path.join(d, name + ".so"))
    except ImportError:
        pass
    found = ctypes.util.find_library(name[3:])
    if found:
        out.append(found)
    return out


def _load(env, name):
    tried = []
    for path in _candidates(env, name):
        if os.path.sep in path and not os.path.exists(path):
            tried.append(path + " (missing)")
            continue
        try:
            return ctypes.CDLL(path), path
        except OSError as e:
            tried.append("%s (%s)" % (path, e))
    raise ImportError("rodnet: cannot load %s; tried: %s; set %s to its path "
                      "(docs/python.md)" % (name, "; ".join(tried) or "nothing", env))


lib, lib_path = _load("RODNET_LIBRARY", "librodnet")
scene_lib, scene_lib_path = _load("RODNET_SCENE_LIBRARY", "librodnet_scene")


# ---- structs (c_api/include/rodnet.h, rodnet_solve.h) ------------------------------
class Material(ctypes.Structure):
    _fields_ = [("E", ctypes.c_double), ("G", ctypes.c_double),
                ("density", ctypes.c_double)]


class Section(ctypes.Structure):
    _fields_ = [(k, ctypes.c_double) for k in ("A", "I11", "I22", "I12", "J")]


class Reaction(ctypes.Structure):
    _fields_ = [("kind", ctypes.c_int), ("rod", ctypes.c_int), ("index", ctypes.c_int),
                ("fixed", ctypes.c_int), ("fixed_rotation", ctypes.c_int),
                ("point", ctypes.c_double * 3), ("force", ctypes.c_double * 3),
                ("moment", ctypes.c_double * 3)]


class IterationInfo(ctypes.Structure):
    _fields_ = [("iteration", ctypes.c_int), ("energy", ctypes.c_double),
                ("gradient_norm", ctypes.c_double), ("radius", ctypes.c_double),
                ("krylov_iterations", ctypes.c_int), ("seconds", ctypes.c_double),
                ("load_factor", ctypes.c_double)]


PROGRESS = ctypes.CFUNCTYPE(None, ctypes.c_void_p, ctypes.POINTER(IterationInfo))


class SolveOptions(ctypes.Structure):
    _fields_ = [("solver", ctypes.c_int), ("max_iterations", ctypes.c_int),
                ("gtol_rel", ctypes.c_double), ("gtol_abs", ctypes.c_double),
                ("step_tol", ctypes.c_double), ("energy_tol", ctypes.c_double),
                ("krylov_max_iterations", ctypes.c_int), ("krylov_tol", ctypes.c_double),
                ("initial_radius", ctypes.c_double), ("load_steps", ctypes.c_int),
                ("max_load_cuts", ctypes.c_int), ("progress", PROGRESS),
                ("progress_user", ctypes.c_void_p), ("factorization", ctypes.c_int),
                ("predictor", ctypes.c_int), ("preconditioner", ctypes.c_int),
                ("stability", ctypes.c_int), ("stability_method", ctypes.c_int),
                ("interrupt", c_int_p), ("forcing", ctypes.c_double)]


class Stability(ctypes.Structure):
    _fields_ = [("checked", ctypes.c_int), ("lowest_eigenvalue", ctypes.c_double),
                ("scale", ctypes.c_double), ("verified_minimum", ctypes.c_int),
                ("zero_modes", ctypes.c_int), ("factorizations", ctypes.c_long),
                ("time_s", ctypes.c_double), ("method", ctypes.c_int),
                ("iterations", ctypes.c_int), ("cholesky_flops", ctypes.c_double),
                ("symmetries", ctypes.c_int), ("soft_modes", ctypes.c_int),
                ("soft_positive", ctypes.c_int)]


class SolveReport(ctypes.Structure):
    _fields_ = [("status", ctypes.c_int), ("stop", ctypes.c_int),
                ("converged", ctypes.c_int), ("iterations", ctypes.c_int),
                ("energy_evals", ctypes.c_long), ("gradient_evals", ctypes.c_long),
                ("hvp_evals", ctypes.c_long), ("hessian_evals", ctypes.c_long),
                ("krylov_iterations", ctypes.c_long), ("load_steps", ctypes.c_int),
                ("energy", ctypes.c_double), ("gradient_norm", ctypes.c_double),
                ("initial_gradient_norm", ctypes.c_double), ("time_s", ctypes.c_double),
                ("factorization", ctypes.c_int), ("factorizations", ctypes.c_long),
                ("predictor_steps", ctypes.c_int),
                ("force_residual", ctypes.c_double), ("moment_residual", ctypes.c_double),
                ("force_scale", ctypes.c_double), ("moment_scale", ctypes.c_double),
                ("force_tolerance", ctypes.c_double),
                ("moment_tolerance", ctypes.c_double), ("preconditioner", ctypes.c_int),
                ("hessian_seconds", ctypes.c_double),
                ("preconditioner_setup_seconds", ctypes.c_double),
                ("preconditioner_apply_seconds", ctypes.c_double),
                ("stability", Stability)]


class Homogenization(ctypes.Structure):
    _fields_ = [("dim", ctypes.c_int), ("nstrain", ctypes.c_int),
                ("measure", ctypes.c_double), ("C", ctypes.c_double * 36),
                ("relative_density", ctypes.c_double), ("fluctuation_dofs", ctypes.c_size_t)]


class CellPathSegment(ctypes.Structure):
    _fields_ = [("steps", ctypes.c_int), ("stress", ctypes.c_int * 6),
                ("target", ctypes.c_double * 6), ("start", ctypes.c_double * 6)]


class CellPathStep(ctypes.Structure):
    _fields_ = [("t", ctypes.c_double), ("seg", ctypes.c_int),
                ("strain", ctypes.c_double * 6), ("stress", ctypes.c_double * 6),
                ("energy", ctypes.c_double), ("newton", ctypes.c_int),
                ("converged", ctypes.c_int), ("outer", ctypes.c_int),
                ("jumped", ctypes.c_int), ("kuu_indefinite", ctypes.c_int),
                ("tangent_min", ctypes.c_double), ("local_min", ctypes.c_double),
                ("acoustic_min", ctypes.c_double), ("stable", ctypes.c_int)]


class CellPathInstability(ctypes.Structure):
    _fields_ = [("found", ctypes.c_int), ("t", ctypes.c_double),
                ("strain", ctypes.c_double * 6), ("stress", ctypes.c_double * 6),
                ("xi", ctypes.c_double * 3), ("nequiv", ctypes.c_int),
                ("xi_equiv", (ctypes.c_double * 3) * 12),
                ("kind_macroscopic", ctypes.c_int), ("multiplicity", ctypes.c_int),
                ("eig", ctypes.c_double * 8), ("neig", ctypes.c_int),
                ("direction", ctypes.c_double * 3), ("amplitude", ctypes.c_double * 3),
                ("bisections", ctypes.c_int), ("stress_limit", ctypes.c_int),
                ("mode", ctypes.c_double * 6), ("cell_periodic", ctypes.c_int)]


class CellPathResult(ctypes.Structure):
    pass


CELL_PROGRESS = ctypes.CFUNCTYPE(None, ctypes.c_void_p, ctypes.POINTER(CellPathResult))


class CellPathOptions(ctypes.Structure):
    _fields_ = [("grid", ctypes.c_int), ("modes", ctypes.c_int),
                ("progress", CELL_PROGRESS), ("user", ctypes.c_void_p),
                ("bloch_method", ctypes.c_int)]


CellPathResult._fields_ = [
    ("ns", ctypes.c_int), ("nseg", ctypes.c_int),
    ("seg", ctypes.POINTER(CellPathSegment)), ("steps", ctypes.c_int),
    ("step", ctypes.POINTER(CellPathStep)), ("done", ctypes.c_int),
    ("stopped", ctypes.c_char_p), ("limit_end", ctypes.c_int),
    ("tangent_scale", ctypes.c_double), ("c_rest", ctypes.c_double * 36),
    ("inst", CellPathInstability)]

_MIRRORED = {"rn_material": Material, "rn_section": Section, "rn_reaction": Reaction,
             "rn_iteration_info": IterationInfo, "rn_solve_options": SolveOptions,
             "rn_stability": Stability, "rn_solve_report": SolveReport,
             "rn_homogenization": Homogenization,
             "rn_cell_path_segment": CellPathSegment, "rn_cell_path_step": CellPathStep,
             "rn_cell_path_instability": CellPathInstability,
             "rn_cell_path_options": CellPathOptions,
             "rn_cell_path_result": CellPathResult}


# ---- prototypes --------------------------------------------------------------------
P = ctypes.c_void_p
I, D, L, S = ctypes.c_int, ctypes.c_double, ctypes.c_long, ctypes.c_size_t
CS = ctypes.c_char_p
i64p = ctypes.POINTER(ctypes.c_int64)
i32p = ctypes.POINTER(ctypes.c_int32)

_PROTOS = {
    # rodnet.h
    "rn_abi_sizeof": (S, [CS]), "rn_abi_offsetof": (L, [CS, CS]),
    "rn_abi_num_fields": (I, [CS]),
    "rn_status_name": (CS, [I]), "rn_version_string": (CS, []),
    "rn_context_create": (I, [ctypes.POINTER(P)]),
    "rn_context_destroy": (None, [ctypes.POINTER(P)]),
    "rn_context_last_error": (CS, [P]),
    "rn_context_clear_error": (None, [P]),
    "rn_material_from_E_nu": (I, [D, D, D, ctypes.POINTER(Material)]),
    "rn_section_circle": (I, [D, ctypes.POINTER(Section)]),
    "rn_section_hollow_circle": (I, [D, D, ctypes.POINTER(Section)]),
    "rn_section_ellipse": (I, [D, D, ctypes.POINTER(Section)]),
    "rn_section_rectangle": (I, [D, D, ctypes.POINTER(Section)]),
    "rn_section_validate": (I, [ctypes.POINTER(Section)]),
    "rn_network_create": (I, [P, ctypes.POINTER(P)]),
    "rn_network_destroy": (None, [ctypes.POINTER(P)]),
    "rn_network_add_rod": (I, [P, CS, I, c_double_p, c_double_p, c_int_p]),
    "rn_network_add_closed_rod": (I, [P, CS, I, c_double_p, c_double_p, c_int_p, c_int_p]),
    "rn_network_set_material": (I, [P, I, I, ctypes.POINTER(Material)]),
    "rn_network_set_section": (I, [P, I, I, ctypes.POINTER(Section)]),
    "rn_network_set_rest_curvature": (I, [P, I, c_double_p]),
    "rn_network_set_rest_twist": (I, [P, I, c_double_p]),
    "rn_network_set_rest_lengths": (I, [P, I, c_double_p]),
    "rn_network_clamp": (I, [P, I, I]), "rn_network_pin": (I, [P, I, I]),
    "rn_network_fix_theta": (I, [P, I, I]),
    "rn_network_pin_components": (I, [P, I, I, I]),
    "rn_network_displace_end": (I, [P, I, I, c_double_p, c_double_p]),
    "rn_network_displace_vertex": (I, [P, I, I, c_double_p]),
    "rn_network_add_force": (I, [P, I, I, c_double_p]),
    "rn_network_add_moment": (I, [P, I, I, c_double_p]),
    "rn_network_add_line_load": (I, [P, I, c_double_p]),
    "rn_network_add_gravity": (I, [P, c_double_p]),
    "rn_network_finalize": (I, [P]),
    "rn_network_set_load_factor": (I, [P, D]), "rn_network_load_factor": (D, [P]),
    "rn_network_num_dofs": (S, [P]), "rn_network_num_rods": (I, [P]),
    "rn_network_rod_num_vertices": (I, [P, I]), "rn_network_rod_name": (CS, [P, I]),
    "rn_network_get_dofs": (I, [P, c_double_p]),
    "rn_network_set_dofs": (I, [P, c_double_p]),
    "rn_network_energy": (I, [P, c_double_p, c_double_p]),
    "rn_network_gradient": (I, [P, c_double_p, c_double_p, c_double_p]),
    "rn_network_hvp": (I, [P, c_double_p, c_double_p, c_double_p]),
    "rn_network_energy_terms": (I, [P, c_double_p, c_double_p]),
    "rn_network_hessian_pattern": (I, [P, ctypes.POINTER(S), ctypes.POINTER(i64p),
                                       ctypes.POINTER(i32p)]),
    "rn_network_hessian_values": (I, [P, c_double_p, c_double_p]),
    "rn_network_update_reference": (I, [P, c_double_p]),
    "rn_network_state_save": (I, [P, ctypes.POINTER(P)]),
    "rn_network_state_restore": (I, [P, P]),
    "rn_state_destroy": (None, [ctypes.POINTER(P)]),
    "rn_network_rod_vertices": (I, [P, I, c_double_p]),
    "rn_network_rod_theta": (I, [P, I, c_double_p]),
    "rn_network_rod_frames": (I, [P, I, c_double_p, c_double_p]),
    "rn_network_rod_internal_forces": (I, [P, I, c_double_p, c_double_p]),
    "rn_network_add_joint": (I, [P, CS, I, I, c_int_p, c_int_p, c_int_p]),
    "rn_network_add_joint_images": (I, [P, CS, I, I, c_int_p, c_int_p, c_int_p, c_int_p]),
    "rn_network_num_joints": (I, [P]), "rn_network_joint_name": (CS, [P, I]),
    "rn_network_clamp_joint": (I, [P, I]), "rn_network_pin_joint": (I, [P, I]),
    "rn_network_pin_joint_components": (I, [P, I, I]),
    "rn_network_displace_joint": (I, [P, I, c_double_p, c_double_p]),
    "rn_network_add_joint_force": (I, [P, I, c_double_p]),
    "rn_network_add_joint_moment": (I, [P, I, c_double_p]),
    "rn_network_joint_position": (I, [P, I, c_double_p]),
    "rn_network_joint_rotation": (I, [P, I, c_double_p]),
    "rn_network_set_periodic": (I, [P, I, c_double_p]),
    "rn_network_set_cell_strain": (I, [P, c_int_p, c_double_p]),
    "rn_network_set_cell_stress": (I, [P, c_double_p]),
    "rn_network_cell_info": (I, [P, c_int_p, c_int_p, c_double_p, c_double_p]),
    "rn_network_cell_strain": (I, [P, c_double_p, c_double_p]),
    "rn_network_cell_stress": (I, [P, c_double_p, c_double_p]),
    "rn_network_num_supports": (I, [P]),
    "rn_network_reactions": (I, [P, c_double_p, ctypes.POINTER(Reaction), I]),
    "rn_network_applied_resultant": (I, [P, c_double_p, c_double_p]),
    # rodnet_solve.h
    "rn_solve_options_default": (None, [ctypes.POINTER(SolveOptions)]),
    "rn_solve_stop_name": (CS, [I]), "rn_solver_name": (CS, [I]),
    "rn_solver_from_name": (I, [CS, c_int_p]),
    "rn_factorization_name": (CS, [I]), "rn_factorization_from_name": (I, [CS, c_int_p]),
    "rn_preconditioner_name": (CS, [I]),
    "rn_preconditioner_from_name": (I, [CS, c_int_p]),
    "rn_solve": (I, [P, ctypes.POINTER(SolveOptions), ctypes.POINTER(SolveReport)]),
    "rn_network_stability": (I, [P, ctypes.POINTER(Stability)]),
    "rn_homogenize": (I, [P, ctypes.POINTER(Homogenization)]),
    "rn_homogenization_invert": (I, [I, c_double_p, c_double_p]),
    "rn_cell_path_options_default": (None, [ctypes.POINTER(CellPathOptions)]),
    "rn_cell_path_run": (I, [P, I, ctypes.POINTER(CellPathSegment),
                             ctypes.POINTER(CellPathOptions),
                             ctypes.POINTER(CellPathResult)]),
    "rn_cell_path_result_free": (None, [ctypes.POINTER(CellPathResult)]),
}
_SCENE_PROTOS = {
    "rn_scene_load": (I, [P, CS, ctypes.POINTER(P)]),
    "rn_scene_parse": (I, [P, CS, CS, S, ctypes.POINTER(P)]),
    "rn_scene_destroy": (None, [ctypes.POINTER(P)]),
    "rn_scene_network": (P, [P]), "rn_scene_label": (CS, [P]),
    "rn_scene_description": (CS, [P]),
    "rn_scene_find_rod": (I, [P, CS]), "rn_scene_find_joint": (I, [P, CS]),
    "rn_scene_num_vertices": (L, [P]),
    "rn_scene_apply_solver": (None, [P, ctypes.POINTER(SolveOptions)]),
    "rn_scene_sets_solver_kind": (I, [P]),
    "rn_scene_write_json": (I, [P, P, ctypes.POINTER(SolveOptions),
                                ctypes.POINTER(SolveReport), CS]),
    "rn_scene_write_vtu": (I, [P, P, CS]),
}


class _Functions:
    pass


fn = _Functions()
for _lib, _table in ((lib, _PROTOS), (scene_lib, _SCENE_PROTOS)):
    for _name, (_res, _args) in _table.items():
        try:
            _f = getattr(_lib, _name)
        except AttributeError:
            raise ImportError("rodnet: %s does not export %s (a library older than this "
                              "package?)" % (_lib._name, _name))
        _f.restype = _res
        _f.argtypes = _args
        setattr(fn, _name, _f)


def _check_layout():
    for cname, cls in _MIRRORED.items():
        n = fn.rn_abi_sizeof(cname.encode())
        if n != ctypes.sizeof(cls):
            raise ImportError("rodnet: struct %s is %d bytes in %s, %d in the Python "
                              "package: package and library do not match"
                              % (cname, n, lib_path, ctypes.sizeof(cls)))
        if fn.rn_abi_num_fields(cname.encode()) != len(cls._fields_):
            raise ImportError("rodnet: struct %s has %d fields in %s, %d in the Python "
                              "package" % (cname, fn.rn_abi_num_fields(cname.encode()),
                                           lib_path, len(cls._fields_)))
        for f in cls._fields_:
            off = fn.rn_abi_offsetof(cname.encode(), f[0].encode())
            if off != getattr(cls, f[0]).offset:
                raise ImportError("rodnet: field %s.%s is at offset %d in %s, %d in the "
                                  "Python package" % (cname, f[0], off, lib_path,
                                                      getattr(cls, f[0]).offset))


_check_layout()


def text(b):
    return b.decode("utf-8", "replace") if b else ""


def status_name(st):
    return text(fn.rn_status_name(st))


def ptr(a):
    """A double* to the data of the float64 C-contiguous numpy array a (or None)."""
    if a is None:
        return None
    return a.ctypes.data_as(c_double_p)
