#!/usr/bin/env bash
# setup.sh: install what rodnet needs on Debian bookworm (as root) and build it.
#
#   bash scripts/setup.sh            # installs missing packages, builds ./build
#
# Idempotent: apt is skipped when every package is already installed, and the
# build is incremental.  Needs no input (DEBIAN_FRONTEND=noninteractive).
# Environment: RN_BUILD_DIR (default build), RN_BUILD_TYPE (RelWithDebInfo),
# RN_JOBS (2), RN_CMAKE_ARGS (extra configure arguments), RN_SKIP_BUILD=1.
set -euo pipefail
cd "$(dirname "$0")/.."

# The working Trilinos 13.2 set (shared/design/TRILINOS.md) and the rest of the tools.
packages=(
  cmake make gcc g++ libopenmpi-dev openmpi-bin
  libmetis-dev libptscotch-dev liblapack-dev libopenblas0-serial libcjson-dev
  libsuitesparse-dev
  libtrilinos-rol-dev libtrilinos-belos-dev libtrilinos-tpetra-dev libtrilinos-nox-dev
  libtrilinos-teuchos-dev libtrilinos-trilinosss-dev libtrilinos-kokkos-dev
  libtrilinos-kokkos-kernels-dev libtrilinos-epetra-dev libtrilinos-epetraext-dev
  libtrilinos-thyra-dev libtrilinos-rtop-dev libtrilinos-xpetra-dev libtrilinos-aztecoo-dev
  libtrilinos-triutils-dev libtrilinos-stratimikos-dev libtrilinos-teko-dev
  libtrilinos-anasazi-dev libtrilinos-amesos-dev libtrilinos-amesos2-dev
  libtrilinos-ifpack-dev libtrilinos-ifpack2-dev libtrilinos-ml-dev libtrilinos-muelu-dev
  libtrilinos-intrepid-dev libtrilinos-intrepid2-dev libtrilinos-shylu-dev
  libtrilinos-zoltan-dev libtrilinos-zoltan2-dev libtrilinos-galeri-dev
  libtrilinos-isorropia-dev libtrilinos-shards-dev libtrilinos-sacado-dev
  pkg-config libblas-dev binutils git
  python3 python3-vtk9 python3-numpy python3-matplotlib python3-scipy python3-pytest
  clang libclang-rt-14-dev clang-format
)

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q 'install ok installed'; then
    missing+=("$p")
  fi
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "setup: installing ${#missing[@]} missing packages: ${missing[*]}"
  if [ "$(id -u)" -ne 0 ]; then
    echo "setup: run as root to install packages (or install them yourself)" >&2
    exit 1
  fi
  export DEBIAN_FRONTEND=noninteractive
  apt-get update -q </dev/null
  apt-get install -y -q --no-install-recommends "${missing[@]}" </dev/null
else
  echo "setup: all ${#packages[@]} system packages are installed"
fi

[ "${RN_SKIP_BUILD:-0}" = 1 ] && exit 0

build=${RN_BUILD_DIR:-build}
# shellcheck disable=SC2086
cmake -S . -B "$build" -DCMAKE_BUILD_TYPE="${RN_BUILD_TYPE:-RelWithDebInfo}" -DRN_WERROR=ON \
  ${RN_CMAKE_ARGS:-} </dev/null
cmake --build "$build" -j"${RN_JOBS:-2}" </dev/null
echo "setup: built $build"
