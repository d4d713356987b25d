#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# check_bad_inputs.sh MESHMORPH DIR WORK: every file (or OpenFOAM case folder) of DIR, given to `quality` and to
# `convert`, must give exit code 2, a stderr message naming the file and a line or byte
# offset (CGNS, Exodus II: a node path, block or set), and no output file.
set -u
mm=$1 dir=$2 work=$3
rm -rf "$work" && mkdir -p "$work/out"
failures=0 count=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }
for f in "$dir"/*; do
  count=$((count + 1))
  for cmd in "quality $f --json $work/out/q.json -o $work/out/q.vtu" "convert $f $work/out/c.vtu" \
             "convert $f $work/out/c.msh --order 2"; do
    # shellcheck disable=SC2086
    "$mm" $cmd >"$work/stdout" 2>"$work/stderr"
    rc=$?
    [ "$rc" -eq 2 ] || fail "meshmorph $cmd: exit $rc, expected 2"
    # An OpenFOAM case (a folder) may be named by its polyMesh file and line, or a cell or face;
    # CGNS and Exodus II by a CGNS node path, an Exodus block or set, the coordinates or header.
    grep -Eq "^meshmorph: error: $f(/constant/polyMesh(/[a-z]+)?)?(:[0-9]+|: (line|byte offset|cell|face) [0-9]+|: node /|: (element block|side set|node set) -?[0-9]+|: (coordinates|header):)" "$work/stderr" ||
      fail "meshmorph $cmd: stderr does not name the file and a line/offset: $(head -c 300 "$work/stderr")"
    if [ -n "$(ls -A "$work/out")" ]; then
      fail "meshmorph $cmd: wrote $(ls -A "$work/out")"
      rm -f "$work/out"/*
    fi
  done
done
[ "$count" -ge 1 ] || fail "no files in $dir"
echo "$count bad inputs checked, $failures failures"
[ "$failures" -eq 0 ]
