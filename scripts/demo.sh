#!/usr/bin/env bash
# demo.sh: set up and build (scripts/setup.sh), then solve the built-in default scene
# (problems/scenes/cantilever.json) and write out/result.json and out/result.vtu.
#
#   bash scripts/demo.sh [SCENE.json]
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
scene=${1:-problems/scenes/cantilever.json}
mkdir -p out
./build/rodnet solve "$scene" -o out/result.json --vtk out/result.vtu
python3 - out/result.json <<'PY'
import json, sys
r = json.load(open(sys.argv[1]))
print(f"demo: status {r['status']}, energy {r['energy']:.10g}, "
      f"|grad| {r['gradient_norm']:.3e}, {r['iterations']} iterations, {r['time_s']:.3f} s")
for rod in r["rods"]:
    v = rod["vertices"]
    print(f"demo: rod '{rod['name']}': {len(v)} vertices, last vertex at "
          f"({v[-1][0]:.6f}, {v[-1][1]:.6f}, {v[-1][2]:.6f})")
PY
echo "demo: wrote out/result.json and out/result.vtu (open the .vtu in ParaView)"
