#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# check_bad_cases.sh MESHMORPH DIR EXAMPLES: every case file of DIR given to `check` must give
# exit code 2 and a stderr message naming a file of DIR with a line, column or key path;
# every example case must pass with exit 0.
set -u
mm=$1 dir=$2 examples=$3
failures=0 count=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }
for f in "$dir"/*.json; do
  count=$((count + 1))
  err=$("$mm" check "$f" 2>&1 >/dev/null)
  rc=$?
  [ "$rc" -eq 2 ] || fail "check $f: exit $rc, expected 2"
  echo "$err" | grep -Eq "^meshmorph: error: $dir/[^:]+:( ?[0-9]+| [a-z_\[\]0-9.]+:| )" ||
    fail "check $f: message does not name the file and a line or key: $err"
done
for f in "$examples"/*/case.json; do
  "$mm" check "$f" >/dev/null 2>&1 || fail "check $f: exit $?, expected 0"
done
[ "$count" -ge 12 ] || fail "only $count bad case files in $dir"
echo "$count bad case files checked, $failures failures"
[ "$failures" -eq 0 ]
