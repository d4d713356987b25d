#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# check_orientation.sh MESHMORPH DATA WORK: valid means injective. DATA/folded holds a unit
# square of 8 triangles with one listed clockwise (folded_square.mesh), what untangle and
# optimize once made of it by folding the mesh (folded_square_untangled/_optimized.mesh: every
# cell positive, areas adding up to 1.0658 and 1.0542), and a cube of 12 tetrahedra with one
# listed mirrored. Every method refuses a flipped input with exit 2, naming the cell and
# writing nothing; with --reorient (or the case's "reorient") untangle and optimize give
# meshes whose volumes add up to the enclosed 1 to 1e-12; `quality` calls the folded outputs
# invalid (overlap) with exit 1; `check` refuses the case. DATA/folded/crossing moves the
# hole of a mesh so that its boundary passes through itself, every cell still positive: morph
# exits 1 and writes nothing, and `quality` calls the mesh a build once wrote there invalid.
set -u
mm=$1 data=$(realpath "$2/folded") work=$3
rm -rf "$work" && mkdir -p "$work/out"
fail() { echo "FAIL: $*"; exit 1; }
field() { sed -n "s/^  \"$2\": \"\{0,1\}\([^\",]*\)\"\{0,1\},\{0,1\}$/\1/p" "$1"; }
near_one() { awk -v v="$1" 'BEGIN { d = v - 1; exit !(d < 1e-12 && d > -1e-12) }'; }
refused() {  # refused NAME ARGS...: exit 2 naming the first flipped cell, nothing written
  local name=$1
  shift
  "$mm" --quiet "$@" > "$work/$name.out" 2> "$work/$name.err"
  local rc=$?
  [ "$rc" = 2 ] || fail "$name: exit $rc, expected 2: $(cat "$work/$name.err")"
  grep -q "listed mirrored against its neighbours, first cell [0-9]" "$work/$name.err" ||
    fail "$name: the message does not name the cell: $(cat "$work/$name.err")"
  [ -z "$(ls -A "$work/out")" ] || fail "$name: wrote $(ls -A "$work/out")"
}
injective() {  # injective NAME MESH: quality exit 0, cells and boundary both enclose 1
  "$mm" --quiet quality "$2" --json "$work/$1.quality.json" > /dev/null || fail "$1: quality calls the result invalid"
  [ "$(field "$work/$1.quality.json" flipped_elements)" = 0 ] || fail "$1: flipped elements left"
  near_one "$(field "$work/$1.quality.json" cell_volume)" || fail "$1: cell volumes add up to $(field "$work/$1.quality.json" cell_volume)"
  near_one "$(field "$work/$1.quality.json" enclosed_volume)" || fail "$1: encloses $(field "$work/$1.quality.json" enclosed_volume)"
}

square=$data/folded_square.mesh cube=$data/folded_cube.mesh
refused untangle_square untangle "$square" -o "$work/out/u.mesh"
refused optimize_square optimize "$square" -o "$work/out/o.mesh"
refused untangle_cube untangle "$cube" -o "$work/out/u.mesh"
refused optimize_cube optimize "$cube" -o "$work/out/o.mesh"

# Curved: the case raises the square to order 3; the flipped cell stays flipped.
printf '{"mesh": "%s", "order": 3, "output": "%s"}\n' "$square" "$work/out/p3.vtu" > "$work/p3.case.json"
refused untangle_p3 untangle "$work/p3.case.json"
printf '{"mesh": "%s", "order": 3, "reorient": true, "output": "%s/p3.vtu"}\n' "$square" "$work" > "$work/p3r.case.json"
"$mm" --quiet untangle "$work/p3r.case.json" > /dev/null 2>&1 || fail "p3 reorient: untangle failed"
injective p3 "$work/p3.vtu"

# The other methods and `check` refuse it as well.
printf '{"mesh": "%s", "boundary": [{"group": "1", "translate": [0.01, 0]}], "output": "%s"}\n' "$square" \
  "$work/out/m.mesh" > "$work/morph.case.json"
refused morph morph "$work/morph.case.json"
refused check check "$work/morph.case.json"

# --reorient: untangle and optimize repair the listing, not the geometry.
for cmd in untangle optimize; do
  for mesh in "$square" "$cube"; do
    name=${cmd}_$(basename "$mesh" .mesh)
    "$mm" --quiet $cmd "$mesh" --reorient -o "$work/$name.mesh" > /dev/null 2> "$work/$name.err" ||
      fail "$name --reorient: $(cat "$work/$name.err")"
    injective "$name" "$work/$name.mesh"
  done
done

# The folded results of a build that untangled by folding: invalid, with the overlap named.
for folded in folded_square_untangled folded_square_optimized; do
  "$mm" --quiet quality "$data/$folded.mesh" --json "$work/$folded.json" > "$work/$folded.out"
  rc=$?
  [ "$rc" = 1 ] || fail "quality $folded: exit $rc, expected 1"
  [ "$(field "$work/$folded.json" valid)" = false ] || fail "quality $folded: called valid"
  [ "$(field "$work/$folded.json" inverted_elements)" = 0 ] || fail "quality $folded: the cells should all be positive"
  [ "$(field "$work/$folded.json" flipped_elements)" = 1 ] || fail "quality $folded: the flipped cell is not counted"
  grep -q '"message": "the mesh overlaps itself' "$work/$folded.json" || fail "quality $folded: message"
  near_one "$(field "$work/$folded.json" enclosed_volume)" || fail "quality $folded: enclosed volume"
  near_one "$(field "$work/$folded.json" cell_volume)" && fail "quality $folded: the cells add up to 1"
done
# A boundary motion that drives the boundary through itself.
"$mm" --quiet morph "$data/crossing/case.json" -o "$work/out/crossing.msh" --report "$work/crossing.json" > "$work/crossing.out"
rc=$?
[ "$rc" = 1 ] || fail "morph crossing: exit $rc, expected 1"
[ ! -e "$work/out/crossing.msh" ] || fail "morph crossing: wrote the overlapping mesh"
grep -q "boundary passes through itself" "$work/crossing.json" || fail "morph crossing: the report does not say why"
"$mm" --quiet quality "$data/crossing_morphed.mesh" --json "$work/crossing_quality.json" > /dev/null
rc=$?
[ "$rc" = 1 ] || fail "quality crossing_morphed: exit $rc, expected 1"
[ "$(field "$work/crossing_quality.json" inverted_elements)" = 0 ] || fail "quality crossing_morphed: inverted cells"
[ "$(field "$work/crossing_quality.json" boundary_crossings)" -ge 1 ] || fail "quality crossing_morphed: no crossing"
echo "orientation checks passed"
