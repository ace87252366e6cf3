"""A cantilever under a tip load, from Python (docs/python.md).

    PYTHONPATH=build/python /usr/bin/python3 examples/python/cantilever.py

Reads problems/scenes/cantilever.json, solves it as `rodnet solve` does, prints
the tip deflection, the clamp's reaction and the stability verdict, then
minimises the same energy with scipy's trust-krylov on rodnet's objective and
compares the two equilibria.
"""
import os
import sys

import numpy as np

import rodnet

here = os.path.dirname(os.path.abspath(__file__))
scene = os.path.join(here, "..", "..", "problems", "scenes", "cantilever.json")

s = rodnet.load_scene(scene)
r = rodnet.solve(s, progress=True if "-v" in sys.argv else None)
tip = r.positions("beam")[-1]
clamp = r.reactions["supports"][0]
print("rodnet.solve: %s in %d Newton iterations, %.3g s" % (r.status, r.iterations, r.time_s))
print("  energy %.12g, tip at (%.6f, %.6f, %.6f)" % (r.energy, *tip))
print("  clamp reaction force %s, moment %s" % (np.round(clamp["force"], 9),
                                               np.round(clamp["moment"], 9)))
print("  verified minimum: %s (lowest scaled eigenvalue %.3g)"
      % (r.stability["verified_minimum"], r.stability["lowest_eigenvalue"]))

try:
    from scipy.optimize import minimize
except ImportError:
    sys.exit(0)
o = rodnet.load_scene(scene).objective()
m = minimize(o.value, o.x0, jac=o.gradient, hessp=o.hessp, method="trust-krylov")
o.model.set_dofs(m.x)
gap = np.abs(o.model.positions("beam") - r.positions("beam")).max()
print("scipy trust-krylov: %s in %d iterations (%d HVPs); energy %.12g; largest vertex "
      "distance from rodnet's equilibrium %.2e" % ("converged" if m.success else m.message,
                                                    m.nit, o.evaluations["hessp"], m.fun, gap))
if not m.success or gap > 1e-6:
    sys.exit("cantilever.py: scipy did not reach rodnet's equilibrium")
