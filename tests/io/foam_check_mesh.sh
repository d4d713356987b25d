#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# foam_check_mesh.sh MESHMORPH DATA WORK: a channel with a cylinder (DATA/channel_cylinder.geo,
# one layer of prisms) meshed by Gmsh and made an OpenFOAM case by gmshToFoam, morphed by
# meshmorph through a case file (the cylinder moved, the walls fixed, front and back sliding)
# into the time folder 0.001; OpenFOAM's checkMesh on that time must say "Mesh OK".
# Exits 77 (skipped) without gmsh or OpenFOAM (Debian openfoam).
set -u
mm=$1 data=$2 work=$3
for tool in gmsh gmshToFoam checkMesh; do
  command -v "$tool" >/dev/null || { echo "skipped: no $tool"; exit 77; }
done
export WM_PROJECT_DIR=${WM_PROJECT_DIR:-/usr/share/openfoam}
[ -d "$WM_PROJECT_DIR/etc" ] || { echo "skipped: no OpenFOAM etc folder in $WM_PROJECT_DIR"; exit 77; }
fail() { echo "FAIL: $*"; exit 1; }
rm -rf "$work" && mkdir -p "$work/case/system"
cp "$data/channel_hex/system/"{controlDict,fvSchemes,fvSolution} "$work/case/system/"
gmsh -3 "$data/channel_cylinder.geo" -format msh22 -o "$work/channel_cylinder.msh" >"$work/gmsh.log" 2>&1 ||
  fail "gmsh: $(tail -3 "$work/gmsh.log")"
(cd "$work/case" && gmshToFoam ../channel_cylinder.msh >../gmshToFoam.log 2>&1) || fail "gmshToFoam: $(tail -3 "$work/gmshToFoam.log")"
cat >"$work/case/morph.json" <<'JSON'
{
  "mesh": ".",
  "boundary": [
    {"group": "cylinder", "translate": [0.02, 0.01, 0]},
    {"group": "walls", "fixed": true},
    {"group": "inlet", "fixed": true},
    {"group": "outlet", "fixed": true},
    {"group": "front", "slide": true},
    {"group": "back", "slide": true}
  ],
  "output": "0.001"
}
JSON
"$mm" morph "$work/case/morph.json" >"$work/morph.log" 2>&1 || fail "meshmorph morph: $(cat "$work/morph.log")"
points=$work/case/0.001/polyMesh/points
[ -f "$points" ] || fail "no $points"
[ ! -e "$work/case/0.001/polyMesh/faces" ] || fail "the topology was written into the time folder"
cmp -s "$points" "$work/case/constant/polyMesh/points" && fail "the points did not move"
checkMesh -case "$work/case" -time 0.001 >"$work/checkMesh.log" 2>&1 || fail "checkMesh: $(tail -20 "$work/checkMesh.log")"
grep -q "^Time = 0.001$" "$work/checkMesh.log" || fail "checkMesh did not check time 0.001"
grep -q "Mesh OK" "$work/checkMesh.log" || fail "checkMesh: $(grep -E '\*\*\*|Failed' "$work/checkMesh.log")"
echo "checkMesh -time 0.001: Mesh OK"
