#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# check_foam.sh MESHMORPH DATA WORK: an OpenFOAM case (DATA/foam/hybrid_layer, gmshToFoam's) morphed
# through a case file into the time folder 0.01, without OpenFOAM: the points go to
# 0.01/polyMesh/points and nothing else, the time folder reads back as the moved mesh, a second
# run replaces it, another mesh and a time folder not named by a number exit 2
# and write nothing; `convert` takes the case to SU2 and back into a time folder.
set -u
mm=$1 data=$2 work=$3
rm -rf "$work" && mkdir -p "$work"
fail() { echo "FAIL: $*"; exit 1; }
cp -r "$data/foam/hybrid_layer" "$work/case"
cat >"$work/case/morph.json" <<'JSON'
{
  "mesh": ".",
  "boundary": [{"group": "bottom", "translate": [0, 0, 0.02]}, {"group": "defaultFaces", "fixed": true}],
  "output": "0.01"
}
JSON
for run in 1 2; do
  "$mm" morph "$work/case/morph.json" >"$work/morph.out" 2>&1 || fail "morph run $run: $(cat "$work/morph.out")"
done
[ "$(ls "$work/case/0.01")" = polyMesh ] && [ "$(ls "$work/case/0.01/polyMesh")" = points ] ||
  fail "0.01 holds $(ls -R "$work/case/0.01")"
"$mm" quality "$work/case/0.01" --json "$work/q.json" >"$work/q.out" 2>&1 || fail "quality of 0.01: $(cat "$work/q.out")"
grep -q "nodes  *126$" "$work/q.out" || fail "quality of 0.01: $(head -5 "$work/q.out")"
"$mm" convert "$work/case" "$work/case.su2" >/dev/null 2>&1 || fail "convert to SU2"
"$mm" convert "$work/case.su2" "$work/case/0.02" >/dev/null 2>&1 || fail "convert SU2 into the time folder 0.02"
cmp -s <(tail -n +10 "$work/case/0.02/polyMesh/points") <(tail -n +10 "$work/case/0.01/polyMesh/points") &&
  fail "0.02 should hold the unmoved points"
"$mm" convert "$work/case" "$work/case/0.03" >/dev/null 2>&1 || fail "convert into the time folder 0.03"
cmp -s <(tail -n +10 "$work/case/0.03/polyMesh/points") <(tail -n +10 "$work/case/0.02/polyMesh/points") ||
  fail "0.02 (through SU2) and 0.03 differ"
# gmshToFoam kept Gmsh's nodes: the MSH file is the same mesh and may go into a time folder.
"$mm" convert "$data/hybrid_layer.msh" "$work/case/0.035" >/dev/null 2>"$work/err" || fail "the MSH mesh: $(cat "$work/err")"
"$mm" convert "$data/bl_circle_coarse.msh" "$work/case/0.04" >/dev/null 2>"$work/err"
[ $? -eq 2 ] && grep -q "only a mesh read from this case's polyMesh" "$work/err" || fail "another mesh: $(cat "$work/err")"
"$mm" convert "$work/case" "$work/case/later" >/dev/null 2>"$work/err"
[ $? -eq 2 ] && grep -q "unknown output format.*an OpenFOAM case's time folder" "$work/err" ||
  fail "a time folder not named by a number: $(cat "$work/err")"
[ ! -e "$work/case/0.04" ] && [ ! -e "$work/case/later" ] || fail "a refused write left a folder"
echo "OpenFOAM case morphed into 0.01 and converted through SU2"
