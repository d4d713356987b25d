#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# check_deform.sh MESHMORPH EXAMPLES WORK: `deform` end to end — the obstacle of example 06
# under a large normal bump ends valid, with its mesh and report, and the CVT step lowers the
# design's spacing ratio below the unrepaired update's; projected onto a larger circle, the
# nodes end on it; translate, scale and rotate stay valid; the Laplacian baseline runs and
# writes no invalid mesh; bad input
# (a design group that does not exist, a displacement row for a node off the design, an
# unknown option, no moving group) exits 2 and writes nothing.
set -u
mm=$1 examples=$2 work=$3
rm -rf "$work" && mkdir -p "$work"
fail() { echo "FAIL: $*"; exit 1; }
field() { sed -n "s/^  \"$2\": \"\{0,1\}\([^\",]*\)\"\{0,1\},\{0,1\}$/\1/p" "$1"; }
ex="$examples/06_deform_obstacle"
mesh=$(realpath "$examples/meshes/obstacle_2d.msh")
cp "$ex/bump.csv" "$work/"
make_case() {  # make_case NAME BOUNDARY_JSON [OPTIONS_JSON]
  printf '{"mesh": "%s", "boundary": %s, "options": %s, "output": "%s.vtu", "report": "%s.json"}\n' \
    "$mesh" "$2" "${3:-{\}}" "$1" "$1" > "$work/$1.case.json"
}
expect() {  # expect NAME EXIT [PATTERN]
  "$mm" deform "$work/$1.case.json" --quiet > "$work/$1.out" 2> "$work/$1.err"
  local rc=$?
  [ "$rc" = "$2" ] || fail "$1: exit $rc, expected $2: $(cat "$work/$1.err")"
  [ -z "${3:-}" ] || grep -q "$3" "$work/$1.err" "$work/$1.out" || fail "$1: no '$3' in $(cat "$work/$1.err")"
}
design='{"group": "obstacle", "displace": {"file": "bump.csv"}}, {"group": "farfield", "fixed": true}'

make_case bump "[$design]"
expect bump 0
[ -s "$work/bump.vtu" ] || fail "bump: no mesh written"
[ "$(field "$work/bump.json" method)" = deform ] || fail "bump: method"
[ "$(field "$work/bump.json" inverted_elements)" = 0 ] || fail "bump: inverted elements"
[ "$(field "$work/bump.json" converged)" = true ] || fail "bump: not converged"
awk -v a="$(field "$work/bump.json" spacing_ratio)" -v b="$(field "$work/bump.json" spacing_ratio_unrepaired)" \
  'BEGIN { exit !(a < b) }' || fail "bump: the CVT step did not lower the spacing ratio"
awk -v e="$(field "$work/bump.json" boundary_error_max)" 'BEGIN { exit !(e < 1e-9) }' ||
  fail "bump: design nodes off the moved surface"
"$mm" --quiet quality "$work/bump.vtu" > /dev/null || fail "bump: output invalid or unreadable"

# project: the obstacle grows onto the circle of radius 0.6; with the exact projection the
# repaired nodes stay on it to rounding.
make_case project '[{"group": "obstacle", "project": {"sphere": {"center": [0, 0], "radius": 0.6}}}, {"group": "farfield", "fixed": true}]'
expect project 0
awk -v e="$(field "$work/project.json" boundary_error_max)" 'BEGIN { exit !(e < 1e-10) }' ||
  fail "project: design nodes off the circle ($(field "$work/project.json" boundary_error_max))"

# The rigid and scaling motions of the case file move the design too.
make_case translate '[{"group": "obstacle", "translate": [0.3, 0.1]}, {"group": "farfield", "fixed": true}]'
expect translate 0
make_case scale '[{"group": "obstacle", "scale": {"center": [0, 0], "factor": 1.6}}, {"group": "farfield", "fixed": true}]' \
  '{"method": "eikonal", "density": "input"}'
expect scale 0
make_case rotate '[{"group": "obstacle", "rotate": {"center": [0, 0], "degrees": 30}}, {"group": "farfield", "fixed": true}]'
expect rotate 0
for name in translate scale rotate; do
  [ "$(field "$work/$name.json" inverted_elements)" = 0 ] || fail "$name: inverted elements"
done

make_case laplace "[$design]" '{"method": "laplace", "cvt": false}'
"$mm" deform "$work/laplace.case.json" --quiet > /dev/null 2>&1
rc=$?
[ "$rc" = 0 ] || [ "$rc" = 1 ] || fail "laplace: exit $rc"
[ "$rc" = 0 ] || [ ! -e "$work/laplace.vtu" ] || fail "laplace: an invalid mesh was written"
# The same in five increments, each written: the fourth inverts cells, so exit 1, no result
# mesh, and the summary names the three step files that were written before it.
printf '{"mesh": "%s", "steps": 5, "output_each_step": true, "boundary": [%s], "options": {"method": "laplace", "cvt": false}, "output": "inc.vtu"}\n' \
  "$mesh" "$design" > "$work/inc.case.json"
"$mm" deform "$work/inc.case.json" > "$work/inc.out" 2>&1
rc=$?
[ "$rc" = 1 ] || fail "inc: exit $rc, expected 1: $(cat "$work/inc.out")"
[ ! -e "$work/inc.vtu" ] && [ -s "$work/inc_0003.vtu" ] && [ ! -e "$work/inc_0004.vtu" ] || fail "inc: files: $(ls "$work")"
grep -q "no result mesh (the goal was not reached); the 3 increments before: .*inc_0001.vtu ... .*inc_0003.vtu" "$work/inc.out" ||
  fail "inc: summary: $(cat "$work/inc.out")"

# Bad input: exit 2, nothing written.
make_case no_group '[{"group": "cylinder", "displace": {"file": "bump.csv"}}, {"group": "farfield", "fixed": true}]'
expect no_group 2 'no physical group "cylinder"'
first_far=$(awk '/^\$Elements/ {on=1; next} on && $2 == 1 && $4 == 2 {print $6; exit}' "$mesh")
{ cat "$work/bump.csv"; echo "$first_far,0.1,0"; } > "$work/off_design.csv"
make_case off_design '[{"group": "obstacle", "displace": {"file": "off_design.csv"}}, {"group": "farfield", "fixed": true}]'
expect off_design 2 "node $first_far is not in group \"obstacle\""
make_case unknown_option "[$design]" '{"gamma": 1}'
expect unknown_option 2 "options.gamma"
make_case nothing_moves '[{"group": "farfield", "fixed": true}]'
expect nothing_moves 2 "no group moves"
for name in no_group off_design unknown_option nothing_moves; do
  [ ! -e "$work/$name.vtu" ] && [ ! -e "$work/$name.json" ] || fail "$name: something was written"
done
echo "deform: all checks passed"
