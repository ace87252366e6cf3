"""rodnet from Python: static equilibria of discrete elastic rods and rod
networks (docs/python.md).

    import rodnet
    scene = rodnet.load_scene("problems/scenes/cantilever.json")
    result = rodnet.solve(scene)                 # as `rodnet solve`
    tip = result.positions("beam")[-1]
    o = scene.objective()                        # for any optimiser

A thin layer over the C ABI of librodnet and librodnet_scene through ctypes: no
compiled extension, no compiler at import.  Errors raise rodnet.Error with the
library's message (file, place, reason).
"""
from ._ffi import Error, lib_path, scene_lib_path
from ._ffi import fn as _fn
from ._core import (Network, Objective, Result, Scene, homogenize, load_scene,
                    parse_scene, solve, solve_options)
from . import bench

__version__ = _fn.rn_version_string().decode()

__all__ = ["Error", "Network", "Objective", "Result", "Scene", "bench", "homogenize",
           "load_scene", "parse_scene", "solve", "solve_options", "__version__"]
