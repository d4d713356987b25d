#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# check_cgns_exodus.sh MESHMORPH EXAMPLES WORK: `quality`, `convert` and `morph` take CGNS and
# Exodus II meshes by their extension: the annulus converted to .cgns and .exo, its quality
# read from both, the rotation example morphed from one format into the other, and both
# results converted back to MSH with the same nodes; an order Exodus cannot hold is exit 2
# with no file written.
set -u
mm=$1 examples=$2 work=$3
rm -rf "$work" && mkdir -p "$work"
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }
run() { "$mm" "$@" >"$work/stdout" 2>"$work/stderr" || fail "meshmorph $*: exit $? ($(head -c 300 "$work/stderr"))"; }
run convert "$examples/meshes/annulus.msh" "$work/annulus.cgns"
run convert "$examples/meshes/annulus.msh" "$work/annulus.exo"
for f in annulus.cgns annulus.exo; do
  run quality "$work/$f"
  grep -q "elements  *2366 (2366 triangle P1)" "$work/stdout" || fail "quality $f: $(head -5 "$work/stdout")"
done
for pair in "cgns e" "exo cgns"; do
  set -- $pair
  cat >"$work/case_$1.json" <<CASE
{"mesh": "annulus.$1", "boundary": [{"group": "inner", "rotate": {"center": [0, 0], "degrees": 60}},
 {"group": "outer", "fixed": true}], "steps": 1, "output": "out_$1.$2", "report": "report_$1.json"}
CASE
  run morph "$work/case_$1.json"
  grep -q "boundary reached, mesh valid" "$work/stdout" || fail "morph from .$1 to .$2: $(tail -3 "$work/stdout")"
  run convert "$work/out_$1.$2" "$work/out_$1.msh"
done
# The same morph from either side: the same nodes (the $Nodes sections), bit for bit.
nodes() { sed -n '/^\$Nodes/,/^\$EndNodes/p' "$1"; }
[ "$(nodes "$work/out_cgns.msh")" == "$(nodes "$work/out_exo.msh")" ] || fail "the two morphs' nodes differ"
"$mm" convert "$examples/meshes/annulus.msh" "$work/p3.exo" --order 3 >/dev/null 2>"$work/stderr"
rc=$?
[ "$rc" -eq 2 ] || fail "convert --order 3 to .exo: exit $rc, expected 2"
grep -q "Exodus II has no triangle of order 3" "$work/stderr" || fail "convert --order 3 to .exo: $(cat "$work/stderr")"
ls -A "$work" | grep -q "p3.exo" && fail "convert --order 3 to .exo left $(ls -A "$work" | grep p3)"
echo "$failures failures"
[ "$failures" -eq 0 ]
