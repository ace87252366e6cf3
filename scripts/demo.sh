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
# Progress lines and the summary come from the command itself.
./build/rodnet solve "$scene" -o out/result.json --vtk out/result.vtu
echo "demo: wrote out/result.json and out/result.vtu (open the .vtu in ParaView)"
