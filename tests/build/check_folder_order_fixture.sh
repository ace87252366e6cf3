#!/usr/bin/env bash
# check_folder_order_fixture.sh BUILD_TEST_DIR
# check_folder_order.sh must fail on the fixture tree folder_order_fixture/ and
# name exactly its two violations (an upward include, one between independent
# folders), not the include its order file excepts.
set -uo pipefail
dir=$1
fx=$dir/folder_order_fixture
out=$(bash "$dir/check_folder_order.sh" "$fx" "$fx/order.txt")
rc=$?
echo "$out"
fail() { echo "folder order fixture: $*"; exit 1; }
[ $rc -eq 1 ] || fail "exit status $rc, expected 1"
grep -q 'problems/io/low.h:2: problems/io includes "cli/high.h" of the higher folder problems/cli' <<<"$out" ||
  fail "the upward include io -> cli is not reported"
grep -q 'shim_cxx/factor/f.hpp:2: .*of shim_cxx/krylov, at the same level' <<<"$out" ||
  fail "the include between independent folders factor -> krylov is not reported"
! grep -q 'system/s.hpp' <<<"$out" || fail "the excepted include is reported"
[ "$(grep -c '^folder order: .*:[0-9]*: ' <<<"$out")" -eq 2 ] || fail "not exactly two violations"
echo "folder order fixture: ok (the check fails on the violations)"
