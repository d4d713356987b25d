#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# check_optimize_p3.sh MESHMORPH EXAMPLES WORK: `optimize` on the sphere-in-a-box linear mesh
# elevated to P3 (11k nodes; ctest label "slow"): its sphere nodes are moved onto the sphere
# and kept there to 1e-10 with no inverted element and a better worst quality (max μ) than
# with the sphere fixed; then the sphere slides on its own P3 facets, stays on them to 1e-10
# and beats the fixed sphere too.
set -u
mm=$1 examples=$2 work=$3
rm -rf "$work" && mkdir -p "$work"
fail() { echo "FAIL: $*"; exit 1; }
field() { sed -n "s/^  \"$2\": \"\{0,1\}\([^\",]*\)\"\{0,1\},\{0,1\}$/\1/p" "$1"; }
less() { awk -v a="$1" -v b="$2" 'BEGIN { exit !(a + 0 < b + 0) }'; }
expect() {  # expect NAME: optimize NAME.case.json, exit 0
  "$mm" optimize "$work/$1.case.json" --quiet > "$work/$1.out" 2> "$work/$1.err" || fail "$1: exit $?: $(cat "$work/$1.err")"
}

sphere='{"sphere": {"center": [0, 0, 0], "radius": 0.4}}'

# P3 from the linear mesh: the elevated sphere nodes are moved onto the sphere, then slide on it.
printf '{"mesh": "%s", "order": 3, "boundary": [{"group": "box", "fixed": true}, {"group": "sphere", "project": %s}], "output": "p3.vtu", "report": "p3.json"}\n' \
  "$(realpath "$examples/meshes/sphere_in_box.msh")" "$sphere" > "$work/p3.case.json"
# The same with the sphere fixed after the projection ("fixed" wins over "project").
printf '{"mesh": "%s", "order": 3, "boundary": [{"group": "box", "fixed": true}, {"group": "sphere", "project": %s}, {"group": "sphere", "fixed": true}], "output": "p3fixed.msh", "report": "p3fixed.json"}\n' \
  "$(realpath "$examples/meshes/sphere_in_box.msh")" "$sphere" > "$work/p3fixed.case.json"
expect p3
expect p3fixed
[ "$(field "$work/p3.json" order)" = 3 ] || fail "p3: order"
less "$(field "$work/p3.json" boundary_error_max)" 1e-10 || fail "p3: nodes left the sphere"
[ "$(field "$work/p3.json" inverted_elements)" = 0 ] || fail "p3: inverted elements"
[ "$(field "$work/p3fixed.json" slide_nodes)" = 0 ] || fail "p3fixed: sliding nodes"
less "$(field "$work/p3.json" mu_max)" "$(field "$work/p3fixed.json" mu_max)" ||
  fail "p3: max mu $(field "$work/p3.json" mu_max) not below fixed $(field "$work/p3fixed.json" mu_max)"

# The sphere sliding on its own P3 facets (`slide` on a curved group, no level set), from
# p3fixed (the elevated sphere moved onto the sphere, then optimized with it fixed): its nodes
# stay on that discrete surface to 1e-10, and the worst quality and the energy end better
# than with the sphere fixed from the same start (the ideal targets take the start's sizes).
printf '{"mesh": "%s", "boundary": [{"group": "box", "fixed": true}, {"group": "sphere", "slide": true}], "output": "p3own.vtu", "report": "p3own.json"}\n' \
  "$work/p3fixed.msh" > "$work/p3own.case.json"
printf '{"mesh": "%s", "boundary": [{"group": "box", "fixed": true}, {"group": "sphere", "fixed": true}], "output": "p3ownfixed.vtu", "report": "p3ownfixed.json"}\n' \
  "$work/p3fixed.msh" > "$work/p3ownfixed.case.json"
expect p3ownfixed
expect p3own
less 0 "$(field "$work/p3own.json" slide_nodes)" || fail "p3own: no sliding node"
less "$(field "$work/p3own.json" boundary_error_max)" 1e-10 || fail "p3own: nodes left the input's surface"
less "$(field "$work/p3own.json" mu_max)" "$(field "$work/p3ownfixed.json" mu_max)" ||
  fail "p3own: max mu $(field "$work/p3own.json" mu_max) not below p3ownfixed $(field "$work/p3ownfixed.json" mu_max)"
less "$(field "$work/p3own.json" energy_final)" "$(field "$work/p3ownfixed.json" energy_final)" || fail "p3own: energy not below p3ownfixed"
echo "optimize P3 CLI checks passed"
