#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# check_optimize.sh MESHMORPH EXAMPLES DATA WORK: `optimize` end to end — a bare P2 mesh is
# optimized with its boundary fixed and written next to itself; the sphere-in-a-box P2 mesh
# with its sphere sliding keeps the sphere's nodes on it to 1e-10 and ends with a lower energy
# and a better worst quality (max μ) than with the sphere fixed; the P2 sphere sliding on its
# own facets stays on them to 1e-10 and beats the fixed sphere too; a bare tangled mesh is
# untangled, then optimized; CHOLMOD reaches the matrix-free solver's F; a run out of Newton
# steps exits 1 and writes its valid, improved mesh; bad input exits 2 and writes nothing. The P3 cases are in
# check_optimize_p3.sh.
set -u
mm=$1 examples=$2 data=$3 work=$4
rm -rf "$work" && mkdir -p "$work"
fail() { echo "FAIL: $*"; exit 1; }
field() { sed -n "s/^  \"$2\": \"\{0,1\}\([^\",]*\)\"\{0,1\},\{0,1\}$/\1/p" "$1"; }
less() { awk -v a="$1" -v b="$2" 'BEGIN { exit !(a + 0 < b + 0) }'; }
sphere_mesh=$(realpath "$examples/meshes/sphere_in_box_p2.msh")
make_case() {  # make_case NAME BOUNDARY_JSON [OPTIONS_JSON]
  printf '{"mesh": "%s", "boundary": %s, "options": %s, "output": "%s.vtu", "report": "%s.json"}\n' \
    "$sphere_mesh" "$2" "${3:-{\}}" "$1" "$1" > "$work/$1.case.json"
}
expect() {  # expect NAME EXIT [PATTERN] [ARGS...]: optimize NAME.case.json, or the path NAME
  local name=$1 rc_want=$2 pattern=${3:-}
  shift 3 2> /dev/null || shift $#
  local input="$work/$name.case.json" tag
  [ -e "$input" ] || input=$name
  tag=$(basename "$name")
  "$mm" optimize "$input" --quiet "$@" > "$work/$tag.out" 2> "$work/$tag.err"
  local rc=$?
  [ "$rc" = "$rc_want" ] || fail "$name: exit $rc, expected $rc_want: $(cat "$work/$tag.err")"
  [ -z "$pattern" ] || grep -q "$pattern" "$work/$tag.err" "$work/$tag.out" || fail "$name: no '$pattern' in $(cat "$work/$tag.err")"
}

# A bare P2 tet mesh, boundary fixed: written next to it, the energy lower, valid.
cp "$sphere_mesh" "$work/bare.msh"
expect "$work/bare.msh" 0 "" --report "$work/bare.json"
[ -s "$work/bare_optimized.msh" ] || fail "bare: no bare_optimized.msh"
r=$work/bare.json
[ "$(field "$r" method)" = optimize ] || fail "bare: method"
[ "$(field "$r" valid)" = true ] && [ "$(field "$r" converged)" = true ] || fail "bare: not valid and converged"
[ "$(field "$r" metric)" = mu303 ] || fail "bare: metric $(field "$r" metric)"
less "$(field "$r" energy_final)" "$(field "$r" energy_initial)" || fail "bare: the energy did not drop"
less 0 "$(field "$r" min_det_final)" || fail "bare: min det J"
[ -n "$(field "$r" mu_max)" ] && [ -n "$(field "$r" mu_mean)" ] || fail "bare: no mu statistics"
"$mm" --quiet quality "$work/bare_optimized.msh" > /dev/null || fail "bare: output invalid or unreadable"
# MFEM's unit-size target: every cell weighs the same, so F starts elsewhere and still drops.
expect "$work/bare.msh" 0 "" --target ideal_unit -o "$work/bare_unit.msh" --report "$work/bare_unit.json"
r=$work/bare_unit.json
[ "$(field "$r" target)" = ideal_unit ] && [ "$(field "$r" converged)" = true ] || fail "bare_unit: target or convergence"
less "$(field "$r" energy_final)" "$(field "$r" energy_initial)" || fail "bare_unit: the energy did not drop"
[ "$(field "$r" energy_initial)" != "$(field "$work/bare.json" energy_initial)" ] || fail "bare_unit: the same F as ideal"

# The sphere sliding (a `project` level set) against the sphere fixed; the box fixed in both.
sphere='{"sphere": {"center": [0, 0, 0], "radius": 0.4}}'
make_case fixed '[{"group": "box", "fixed": true}, {"group": "sphere", "fixed": true}]'
make_case slide "[{\"group\": \"box\", \"fixed\": true}, {\"group\": \"sphere\", \"project\": $sphere}]"
expect fixed 0
expect slide 0
[ -s "$work/slide.vtu" ] || fail "slide: no mesh written"
less 0 "$(field "$work/slide.json" slide_nodes)" || fail "slide: no sliding node"
less "$(field "$work/slide.json" boundary_error_max)" 1e-10 || fail "slide: nodes left the sphere"
# Worst quality = largest μ over the quadrature points.
less "$(field "$work/slide.json" mu_max)" "$(field "$work/fixed.json" mu_max)" ||
  fail "slide: max mu $(field "$work/slide.json" mu_max) not below fixed $(field "$work/fixed.json" mu_max)"
less "$(field "$work/slide.json" energy_final)" "$(field "$work/fixed.json" energy_final)" || fail "slide: energy not below fixed"

# The fixed case with CHOLMOD (the option, and --solver on the bare mesh): 3D runs are
# matrix-free unless asked, and both reach one minimum.
close() { awk -v a="$1" -v b="$2" -v t="$3" 'BEGIN { d = a - b; if (d < 0) d = -d; exit !(d <= t * b) }'; }
make_case fixed_ch '[{"group": "box", "fixed": true}, {"group": "sphere", "fixed": true}]' '{"solver": "cholesky"}'
expect fixed_ch 0
[ "$(field "$work/fixed.json" solver)" = matrix-free ] || fail "fixed: solver $(field "$work/fixed.json" solver)"
[ "$(field "$work/fixed_ch.json" solver)" = cholmod ] || fail "fixed_ch: solver $(field "$work/fixed_ch.json" solver)"
close "$(field "$work/fixed_ch.json" energy_final)" "$(field "$work/fixed.json" energy_final)" 1e-9 ||
  fail "fixed_ch: F $(field "$work/fixed_ch.json" energy_final), matrix-free $(field "$work/fixed.json" energy_final)"
expect "$work/bare.msh" 0 "" --solver cholesky --report "$work/bare_ch.json" -o "$work/bare_ch.msh"
[ "$(field "$work/bare_ch.json" solver)" = cholmod ] || fail "bare --solver cholesky: solver"
close "$(field "$work/bare_ch.json" energy_final)" "$(field "$work/bare.json" energy_final)" 1e-9 || fail "bare cholesky: F"

# The sphere sliding on its own curved facets (`slide` on a curved group, no level set): its
# nodes stay on the input's discrete surface to 1e-10, and the worst quality and the energy
# end better than with the sphere fixed (rtol 1e-8: Newton stalls near 1e-8 on its C⁰
# surface, docs/optimize.md).
make_case own '[{"group": "box", "fixed": true}, {"group": "sphere", "slide": true}]' '{"rtol": 1e-8}'
expect own 0
less 0 "$(field "$work/own.json" slide_nodes)" || fail "own: no sliding node"
less "$(field "$work/own.json" boundary_error_max)" 1e-10 || fail "own: nodes left the input's surface"
less "$(field "$work/own.json" mu_max)" "$(field "$work/fixed.json" mu_max)" ||
  fail "own: max mu $(field "$work/own.json" mu_max) not below fixed $(field "$work/fixed.json" mu_max)"
less "$(field "$work/own.json" energy_final)" "$(field "$work/fixed.json" energy_final)" || fail "own: energy not below fixed"

# A bare tangled mesh: untangled with its boundary fixed, then optimized.
cp "$data/tangled_quads.msh" "$work/"
expect "$work/tangled_quads.msh" 0 "untangled first" --report "$work/tangled.json"
less 0 "$(field "$work/tangled.json" initial_inverted_elements)" || fail "tangled: the input was not tangled"
[ "$(field "$work/tangled.json" inverted_elements)" = 0 ] || fail "tangled: inverted elements left"
[ -s "$work/tangled_quads_optimized.msh" ] || fail "tangled: no mesh written"

# Out of Newton steps from a valid mesh: exit 1 and a report that says so, and the improved
# mesh written (DESIGN §3.1): valid, its F below the input's. The same with --max-newton on
# the bare mesh.
make_case budget '[{"group": "box", "fixed": true}]' '{"max_newton": 1}'
expect budget 1 "stopped after 1 Newton"
[ "$(field "$work/budget.json" converged)" = false ] || fail "budget: report says converged"
[ -s "$work/budget.vtu" ] || fail "budget: the improved mesh was not written"
[ "$(field "$work/budget.json" valid)" = true ] && [ "$(field "$work/budget.json" improved)" = true ] || fail "budget: not valid and improved"
less "$(field "$work/budget.json" energy_final)" "$(field "$work/budget.json" energy_initial)" || fail "budget: F did not drop"
"$mm" --quiet quality "$work/budget.vtu" > /dev/null || fail "budget: the written mesh is invalid"
expect "$work/bare.msh" 1 "valid and better than the input" --max-newton 1 -o "$work/bare_budget.msh" --report "$work/bare_budget.json"
[ "$(field "$work/bare_budget.json" converged)" = false ] || fail "--max-newton 1: converged"
less "$(field "$work/bare_budget.json" energy_final)" "$(field "$work/bare_budget.json" energy_initial)" || fail "--max-newton 1: F"
"$mm" --quiet quality "$work/bare_budget.msh" > /dev/null || fail "--max-newton 1: the written mesh is invalid"

# A det floor that F's minimiser lies beyond: the run ends on the floor, valid, exit 0.
printf '{"mesh": "%s", "order": 2, "options": {"det_floor": 0.9}, "output": "floor.vtu", "report": "floor.json"}\n' \
  "$(realpath "$data/annulus_coarse.msh")" > "$work/floor.case.json"
expect floor 0 "min det A on the det floor (0.9 of its initial value)"
[ -s "$work/floor.vtu" ] || fail "floor: no mesh written"
awk -v a="$(field "$work/floor.json" min_det_final)" -v b="$(field "$work/floor.json" min_det_initial)" \
  'BEGIN { exit !(a >= 0.9 * b && a < 0.91 * b) }' || fail "floor: min det not on the floor"

# Bad input: exit 2, nothing written.
make_case unknown_option '[]' '{"delta0": 1}'
expect unknown_option 2 "options.delta0"
make_case wrong_metric '[]' '{"metric": "mu2"}'
expect wrong_metric 2 "options.metric"
make_case off_surface '[{"group": "sphere", "project": {"sphere": {"center": [0, 0, 0], "radius": 0.9}}}]'
expect off_surface 2 "boundary\[0\].project: moving the group's nodes onto the level set"
make_case bad_motion '[{"group": "sphere", "translate": [1, 0, 0]}]'
expect bad_motion 2 "boundary\[0\]"
for name in unknown_option wrong_metric off_surface bad_motion; do
  [ ! -e "$work/$name.vtu" ] && [ ! -e "$work/$name.json" ] || fail "$name: something was written for bad input"
done
expect "$work/bare.msh" 2 "metric" --metric mu9 -o "$work/never.vtu"
expect "$work/missing.msh" 2 "missing.msh" -o "$work/never.vtu"
[ ! -e "$work/never.vtu" ] || fail "usage error: a mesh was written"
echo "optimize CLI checks passed"
