# solve_env.sh: the common set-up of the whole-solve benchmark scripts (precond.sh,
# targets.sh, large.sh), sourced from the repository root after `cd`:
#   . benchmarks/solve_env.sh BUILD_DIR
# Sets build (the build directory), res (benchmarks/results, created), py (a
# Python 3), tmp (a scratch directory removed on exit) and exports RODNET_MPI=1
# (MueLu, the DD's multigrid coarse solve, needs the MPI runtime in Trilinos 13.2).
build=${1:-build}
res=benchmarks/results
py=/usr/bin/python3
[ -x "$py" ] || py=python3
mkdir -p "$res"
export RODNET_MPI=1
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
