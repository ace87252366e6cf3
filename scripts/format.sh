#!/usr/bin/env bash
# format.sh: reformat every C/C++ source of rodnet in place with .clang-format.
set -euo pipefail
cd "$(dirname "$0")/.."
find kernels c_api shim_cxx problems tests benchmarks -type f \
  \( -name '*.c' -o -name '*.h' -o -name '*.cpp' -o -name '*.hpp' \) -print0 2>/dev/null |
  xargs -0 -r clang-format -i --style=file
echo "format.sh: done"
