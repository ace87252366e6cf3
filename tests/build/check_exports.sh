#!/usr/bin/env bash
# check_exports.sh NM LIBRARY [HEADER]
# A shared library of rodnet exports its C API and nothing else: every defined
# dynamic symbol of LIBRARY is an rn_* name (librodnet.so: cmake/librodnet.map).
# With HEADER, the exported names are exactly the functions HEADER declares
# (librodnet_scene.so and rodnet_scene.h: problems/scene/librodnet_scene.map).  Prints
# the differences (at most 20 each) and exits 1 if there is any; exits 1 too if
# fewer than 10 rn_ symbols are exported (an emptied library or the wrong file).
set -uo pipefail
nm=$1
lib=$2
header=${3:-}
syms=$("$nm" -D --defined-only "$lib") || { echo "exports: cannot read $lib"; exit 1; }
names=$(printf '%s\n' "$syms" | awk 'NF >= 3 { print $3 }' | sort -u)
bad=0
other=$(printf '%s\n' "$names" | grep -v '^rn_' | grep -v '^$')
if [ -n "$other" ]; then
  echo "exports: $lib exports $(printf '%s\n' "$other" | wc -l) symbols outside the C API, e.g.:"
  printf '%s\n' "$other" | head -20 | sed 's/^/  /'
  bad=1
fi
api=$(printf '%s\n' "$names" | grep -c '^rn_')
if [ "$api" -lt 10 ]; then
  echo "exports: $lib exports only $api rn_* symbols (expected its whole C API)"
  bad=1
fi
if [ -n "$header" ]; then
  declared=$(grep -oE '\brn_[a-z0-9_]+\(' "$header" | tr -d '(' | sort -u)
  extra=$(comm -23 <(printf '%s\n' "$names") <(printf '%s\n' "$declared"))
  missing=$(comm -13 <(printf '%s\n' "$names") <(printf '%s\n' "$declared"))
  if [ -n "$extra" ]; then
    echo "exports: $lib exports names $header does not declare:"
    printf '%s\n' "$extra" | head -20 | sed 's/^/  /'
    bad=1
  fi
  if [ -n "$missing" ]; then
    echo "exports: $lib does not export names $header declares:"
    printf '%s\n' "$missing" | head -20 | sed 's/^/  /'
    bad=1
  fi
fi
[ "$bad" = 0 ] && echo "exports: $lib exports $api symbols, all of its C API"
exit "$bad"
