#!/usr/bin/env bash
# check_install.sh BUILD_DIR SOURCE_DIR C_COMPILER HAVE_CLI(0|1)
# Installs the build tree into a temporary prefix, checks the installed files, then
# builds and runs an outside C program (tests/build/consumer/) against it twice:
# through find_package(rodnet) and through pkg-config.  Neither may need Trilinos,
# MPI or METIS.
set -euo pipefail
build=$1
src=$2
cc=${3:-cc}
have_cli=${4:-0}
work=$(mktemp -d "${TMPDIR:-/tmp}/rodnet-install.XXXXXX")
trap 'rm -rf "$work"' EXIT
prefix=$work/prefix
fail() { echo "check_install: FAIL: $*" >&2; exit 1; }

cmake --install "$build" --prefix "$prefix" >"$work/install.log" 2>&1 ||
  { cat "$work/install.log" >&2; fail "cmake --install"; }

libdir=$(cd "$prefix" && dirname "$(find . -name 'librodnet.so' | head -n1)")
[ "$libdir" != "." ] && [ -n "$libdir" ] || fail "librodnet.so not installed"
libdir=$prefix/${libdir#./}
for f in include/rodnet.h include/rodnet_solve.h include/rodnet_contact.h include/rodnet_model.h \
         include/rodnet_couple.h include/rodnet_ring.h include/rodnet_ramp.h \
         include/rodnet_registry.h; do
  [ -f "$prefix/$f" ] || fail "$f not installed"
done
for f in "$libdir/cmake/rodnet/rodnetConfig.cmake" \
         "$libdir/cmake/rodnet/rodnetConfigVersion.cmake" \
         "$libdir/cmake/rodnet/rodnetTargets.cmake" "$libdir/pkgconfig/rodnet.pc"; do
  [ -f "$f" ] || fail "${f#"$prefix"/} not installed"
done
ls "$prefix"/share/rodnet/scenes/*.json >/dev/null 2>&1 || fail "no scenes in share/rodnet/scenes"
# The exported package must not drag Trilinos/MPI into consumers.
if grep -Eiq 'trilinos|\bmpi|metis|lapack' "$libdir/cmake/rodnet/rodnetTargets.cmake" \
     "$libdir"/pkgconfig/rodnet*.pc; then
  fail "the installed package names Trilinos/MPI/METIS/LAPACK (they must stay private)"
fi
if [ "$have_cli" = 1 ]; then
  [ -x "$prefix/bin/rodnet" ] || fail "the rodnet command is not installed"
  "$prefix/bin/rodnet" --version >/dev/null || fail "installed 'rodnet --version' does not run"
  echo "check_install: installed rodnet command runs: $("$prefix/bin/rodnet" --version | head -n1)"
fi

echo "check_install: consumer via find_package(rodnet)"
cmake -S "$src/tests/build/consumer" -B "$work/consumer-cmake" \
  -DCMAKE_PREFIX_PATH="$prefix" -DCMAKE_C_COMPILER="$cc" \
  -DCMAKE_BUILD_TYPE=Release >"$work/configure.log" 2>&1 ||
  { cat "$work/configure.log" >&2; fail "configure the consumer with find_package"; }
cmake --build "$work/consumer-cmake" >"$work/build.log" 2>&1 ||
  { cat "$work/build.log" >&2; fail "build the consumer with find_package"; }
"$work/consumer-cmake/consumer" || fail "run the find_package consumer"
# The scene library: a shipped scene read, solved and written by an outside program.
scene=$prefix/share/rodnet/scenes/cantilever.json
if [ -f "$libdir/pkgconfig/rodnet-scene.pc" ]; then
  [ -f "$prefix/include/rodnet_scene.h" ] || fail "include/rodnet_scene.h not installed"
  [ -x "$work/consumer-cmake/consumer_scene" ] || fail "consumer_scene not built by find_package"
  "$work/consumer-cmake/consumer_scene" "$scene" "$work/out-cmake" ||
    fail "run the find_package scene consumer"
fi

echo "check_install: consumer via pkg-config"
export PKG_CONFIG_PATH=$libdir/pkgconfig
flags=$(pkg-config --cflags --libs rodnet) || fail "pkg-config rodnet"
echo "check_install: pkg-config --cflags --libs rodnet = $flags"
# shellcheck disable=SC2086
"$cc" -std=c11 -Wall -Wextra -Wpedantic -Werror "$src/tests/build/consumer/main.c" \
  -o "$work/consumer-pc" $flags -lm -Wl,-rpath,"$libdir" ||
  fail "build the consumer with pkg-config"
"$work/consumer-pc" || fail "run the pkg-config consumer"
if [ -f "$libdir/pkgconfig/rodnet-scene.pc" ]; then
  flags=$(pkg-config --cflags --libs rodnet-scene) || fail "pkg-config rodnet-scene"
  echo "check_install: pkg-config --cflags --libs rodnet-scene = $flags"
  # shellcheck disable=SC2086
  "$cc" -std=c11 -Wall -Wextra -Wpedantic -Werror "$src/tests/build/consumer/scene.c" \
    -o "$work/consumer-scene-pc" $flags -Wl,-rpath,"$libdir" ||
    fail "build the scene consumer with pkg-config"
  "$work/consumer-scene-pc" "$scene" "$work/out-pc" || fail "run the pkg-config scene consumer"
fi
# The Python package beside the library (docs/python.md): imported from the prefix
# alone (no build tree, no RODNET_LIBRARY), it loads the installed libraries.
# (not under a sanitizer: its runtime cannot be loaded into an uninstrumented python3)
if [ -f "$libdir/pkgconfig/rodnet-scene.pc" ] &&
   ldd "$libdir/librodnet.so" | grep -Eq 'lib(asan|ubsan|tsan)'; then
  echo "check_install: Python import skipped: the library is built with a sanitizer"
elif [ -f "$libdir/pkgconfig/rodnet-scene.pc" ]; then
  init=$(find "$prefix" -path '*/dist-packages/rodnet/__init__.py' | head -n1)
  [ -n "$init" ] || fail "the Python package rodnet is not installed"
  pydir=$(dirname "$(dirname "$init")")
  echo "check_install: Python package in ${pydir#"$prefix"/}"
  (cd "$work" && env -u RODNET_LIBRARY -u RODNET_SCENE_LIBRARY PYTHONPATH="$pydir" \
     /usr/bin/python3 -c "
import sys, rodnet
assert rodnet.lib_path.startswith('$prefix'), rodnet.lib_path
assert rodnet.scene_lib_path.startswith('$prefix'), rodnet.scene_lib_path
r = rodnet.solve(rodnet.load_scene('$scene'))
assert r.converged and r.stability['verified_minimum'], r
print('check_install: python3 -c \'import rodnet\' from the prefix:', rodnet.lib_path, r)
") || fail "import rodnet from the installed prefix"
fi
echo "check_install: ok"
