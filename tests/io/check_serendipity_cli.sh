#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# check_serendipity_cli.sh MESHMORPH DATA WORK: Gmsh's incomplete quadratic cells end to end.
# `quality` reads the 15-node prisms, 20-node hexahedra, 13-node pyramid and 8-node
# quadrilaterals of tests/data/io/gmsh_serendipity_41a.msh as complete cells, says so once
# on stderr and finds them valid; `optimize` moves them and writes complete cells, which read
# back valid with nothing to promote; VTK's file of the same mesh converts to MSH.
set -u
mm=$1 data=$2 work=$3
rm -rf "$work" && mkdir -p "$work"
fail() { echo "FAIL: $*"; exit 1; }
field() { sed -n "s/^  \"$2\": \"\{0,1\}\([^\",]*\)\"\{0,1\},\{0,1\}$/\1/p" "$1"; }
less() { awk -v a="$1" -v b="$2" 'BEGIN { exit !(a + 0 < b + 0) }'; }
mesh=$data/io/gmsh_serendipity_41a.msh

"$mm" quality "$mesh" > "$work/quality.out" 2> "$work/quality.err" || fail "quality: exit $?: $(cat "$work/quality.err")"
note="read 5 8-node quadrilaterals as 9-node ones, 10 15-node prisms as 18-node ones, 2 20-node hexahedra as 27-node ones, 1 13-node pyramid as 14-node one"
[ "$(grep -c "gmsh_serendipity_41a.msh: $note" "$work/quality.err")" = 1 ] || fail "quality: the note, once: $(cat "$work/quality.err")"
grep -Eq "^  nodes +216$" "$work/quality.out" || fail "quality: node count"
grep -Eq "^  inverted elements +0$" "$work/quality.out" || fail "quality: inverted cells"
grep -Eq "^    prism +shape quality min" "$work/quality.out" && grep -Eq "^    pyramid +shape quality min" "$work/quality.out" ||
  fail "quality: no prism or pyramid row"
"$mm" --quiet quality "$mesh" > /dev/null 2> "$work/quiet.err" && [ ! -s "$work/quiet.err" ] || fail "--quiet still notes"

"$mm" optimize "$mesh" -o "$work/optimized.msh" --report "$work/optimized.json" > /dev/null 2> "$work/optimize.err" ||
  fail "optimize: exit $?: $(cat "$work/optimize.err")"
r=$work/optimized.json
[ "$(field "$r" valid)" = true ] && [ "$(field "$r" converged)" = true ] || fail "optimize: not valid and converged"
less "$(field "$r" energy_final)" "$(field "$r" energy_initial)" || fail "optimize: the energy did not drop"
"$mm" quality "$work/optimized.msh" > "$work/optimized.out" 2> "$work/optimized.err" || fail "optimized mesh: exit $?"
[ ! -s "$work/optimized.err" ] || fail "optimized mesh: its cells are complete, yet: $(cat "$work/optimized.err")"
grep -Eq "^  nodes +216$" "$work/optimized.out" && grep -Eq "^  inverted elements +0$" "$work/optimized.out" ||
  fail "optimized mesh: nodes or validity"
grep -q "^\$Elements" "$work/optimized.msh" && ! awk '/^\$Elements/{f=1} f && NF==4 && ($3==16||$3==17||$3==18||$3==19){exit 1}' "$work/optimized.msh" &&
  fail "optimized mesh: incomplete element types written"

"$mm" --quiet convert "$data/io/vtk_serendipity.vtu" "$work/from_vtk.msh" || fail "convert from VTU: exit $?"
"$mm" quality "$work/from_vtk.msh" 2> /dev/null | grep -Eq "^  inverted elements +0$" || fail "VTU mesh: validity"
echo "serendipity CLI checks passed"
