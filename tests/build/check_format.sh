#!/usr/bin/env bash
# check_format.sh SOURCE_DIR [CLANG_FORMAT]
# Checks that every C/C++ source of rodnet follows .clang-format (no file is changed).
# To fix: clang-format -i on the files listed (or scripts/format.sh).
set -uo pipefail
src=$1
cf=${2:-clang-format}
command -v "$cf" >/dev/null 2>&1 || { echo "check_format: $cf not found"; exit 1; }
[ -f "$src/.clang-format" ] || { echo "check_format: $src/.clang-format missing"; exit 1; }
mapfile -t files < <(cd "$src" && find kernels c_api shim_cxx problems tests benchmarks \
  -type f \( -name '*.c' -o -name '*.h' -o -name '*.cpp' -o -name '*.hpp' \) 2>/dev/null | sort)
[ ${#files[@]} -gt 0 ] || { echo "check_format: no sources found under $src"; exit 1; }
bad=()
for f in "${files[@]}"; do
  if ! (cd "$src" && "$cf" --dry-run -Werror --style=file "$f" >/dev/null 2>&1); then
    bad+=("$f")
  fi
done
if [ ${#bad[@]} -gt 0 ]; then
  echo "check_format: ${#bad[@]} of ${#files[@]} files differ from .clang-format:"
  printf '  %s\n' "${bad[@]}"
  echo "check_format: first differences:"
  (cd "$src" && "$cf" --dry-run --style=file "${bad[0]}" 2>&1 | head -n 20)
  exit 1
fi
echo "check_format: ${#files[@]} files ok"
