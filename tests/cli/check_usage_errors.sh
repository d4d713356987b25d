#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# check_usage_errors.sh MESHMORPH EXAMPLES WORK: usage mistakes give exit 2, a
# "meshmorph: error:" line and no output file.
set -u
mm=$1 examples=$2 work=$3
rm -rf "$work" && mkdir -p "$work/out"
mesh=$examples/meshes/annulus.msh
quads=$examples/meshes/quad_channel.msh
failures=0
while IFS='|' read -r args expected; do
  # shellcheck disable=SC2086
  eval "\"$mm\" $args" >/dev/null 2>"$work/stderr"
  rc=$?
  if [ $rc -ne 2 ] || ! grep -q "^meshmorph: error: .*$expected" "$work/stderr" || [ -n "$(ls -A "$work/out")" ]; then
    echo "FAIL: meshmorph $args: exit $rc, stderr: $(cat "$work/stderr"), out: $(ls -A "$work/out")"
    failures=$((failures + 1))
    rm -f "$work/out"/*
  fi
done <<CASES
|A subcommand is required
frobnicate $mesh|unknown subcommand 'frobnicate' (expected one of: quality, convert, check, morph
convert $mesh|OUT is required
convert $mesh $work/out/a.stl|unknown output format ".stl"
convert $mesh $work/out/a.vtu --msh22|--msh22 needs a .msh output file
convert $mesh $work/out/a.mesh --binary|--binary is not available
convert $mesh $work/out/a.msh --order 5|--order: Value 5 not in range
convert $quads $work/out/a.msh --order 4|--order 4 is above the highest for quadrilateral cells (3)
convert $mesh $work/out/a.mesh --order 2|out/a.mesh: Medit .mesh holds linear cells only
convert $work/none.msh $work/out/a.msh|none.msh
quality|MESH is required
quality $mesh -o $work/out/q.msh|expected a .vtu file
quality $mesh --threads 0|--threads: Value 0 not in range 1 to 1024
quality $mesh --threads 65536|--threads: Value 65536 not in range 1 to 1024
quality $mesh --json $work/out/q.json -o $work/nodir/q.vtu|nodir/q.vtu: no folder
quality $mesh --quiet --verbose|
morph $examples/01_rotate_annulus/case.json -o /proc/sys/out.vtu --report $work/out/r.json|output: /proc/sys/out.vtu: cannot write in /proc/sys
CASES
echo "$failures failures"
[ "$failures" -eq 0 ]
