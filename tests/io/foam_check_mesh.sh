#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# foam_check_mesh.sh MESHMORPH DATA WORK: a channel with a cylinder (DATA/channel_cylinder.geo,
# one layer of prisms) meshed by Gmsh and made an OpenFOAM case by gmshToFoam, morphed by
# meshmorph through a case file (the cylinder moved, the walls fixed, front and back sliding)
# into the time folder 0.001; and a channel of hexahedra made by blockMesh, its outlet moved
# downstream into the time folder 0.5. OpenFOAM's checkMesh on each new time must say "Mesh OK".
# Exits 77 (skipped) without gmsh or OpenFOAM (Debian openfoam).
set -u
mm=$1 data=$2 work=$3
for tool in gmsh gmshToFoam blockMesh checkMesh; do
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
# check CASE TIME: the points moved into CASE/TIME, the topology stayed, and checkMesh says Mesh OK.
check() {
  local points=$1/$2/polyMesh/points log=$1/checkMesh.log
  [ -f "$points" ] || fail "no $points"
  [ ! -e "$1/$2/polyMesh/faces" ] || fail "the topology was written into $1/$2"
  cmp -s "$points" "$1/constant/polyMesh/points" && fail "the points of $1 did not move"
  checkMesh -case "$1" -time "$2" >"$log" 2>&1 || fail "checkMesh: $(tail -20 "$log")"
  grep -q "^Time = $2\$" "$log" || fail "checkMesh did not check time $2"
  grep -q "Mesh OK" "$log" || fail "checkMesh on $1: $(grep -E '\*\*\*|Failed' "$log")"
  echo "checkMesh -case $1 -time $2: Mesh OK"
}
check "$work/case" 0.001

mkdir -p "$work/block/system"
cp "$data/channel_hex/system/"{controlDict,fvSchemes,fvSolution} "$work/block/system/"
cat >"$work/block/system/blockMeshDict" <<'DICT'
FoamFile { version 2.0; format ascii; class dictionary; object blockMeshDict; }
convertToMeters 1;
vertices ((0 0 0) (2 0 0) (2 1 0) (0 1 0) (0 0 0.2) (2 0 0.2) (2 1 0.2) (0 1 0.2));
blocks (hex (0 1 2 3 4 5 6 7) (8 4 2) simpleGrading (1 1 1));
boundary
(
  inlet { type patch; faces ((0 4 7 3)); }
  outlet { type patch; faces ((1 2 6 5)); }
  bottom { type wall; faces ((0 1 5 4)); }
  top { type wall; faces ((3 7 6 2)); }
  back { type patch; faces ((0 3 2 1)); }
  front { type patch; faces ((4 5 6 7)); }
);
DICT
(cd "$work/block" && blockMesh >../blockMesh.log 2>&1) || fail "blockMesh: $(tail -3 "$work/blockMesh.log")"
cat >"$work/block/morph.json" <<'JSON'
{
  "mesh": ".",
  "boundary": [
    {"group": "outlet", "translate": [0.3, 0, 0]},
    {"group": "inlet", "fixed": true},
    {"group": "bottom", "slide": true},
    {"group": "top", "slide": true},
    {"group": "back", "slide": true},
    {"group": "front", "slide": true}
  ],
  "output": "0.5"
}
JSON
"$mm" morph "$work/block/morph.json" >"$work/block_morph.log" 2>&1 || fail "meshmorph morph: $(cat "$work/block_morph.log")"
check "$work/block" 0.5
