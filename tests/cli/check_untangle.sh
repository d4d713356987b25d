#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# check_untangle.sh MESHMORPH EXAMPLES DATA WORK: `untangle` end to end — the squeezed quad channel
# (example 05) starts tangled and ends valid with its mesh and report; a run out of Newton
# steps exits 1 without a mesh; a bare tangled mesh (DATA/tangled_quads.msh) is untangled with
# its boundary fixed and written next to itself; bad options and an input reference on a
# tangled mesh exit 2 and write nothing; a wall pushed through the other exits 1, no mesh; a
# sphere's group slides along its level set and the box along its own facets.
set -u
mm=$1 examples=$2 data=$3 work=$4
rm -rf "$work" && mkdir -p "$work"
fail() { echo "FAIL: $*"; exit 1; }
field() { sed -n "s/^  \"$2\": \"\{0,1\}\([^\",]*\)\"\{0,1\},\{0,1\}$/\1/p" "$1"; }
channel="$examples/05_untangle_squeezed_channel"
make_case() {  # make_case NAME BOUNDARY_JSON [OPTIONS_JSON]
  printf '{"mesh": "%s", "boundary": %s, "options": %s, "output": "%s.vtu", "report": "%s.json"}\n' \
    "$(realpath "$examples/meshes/quad_channel.msh")" "$2" "${3:-{\}}" "$1" "$1" > "$work/$1.case.json"
}
expect() {  # expect NAME EXIT [PATTERN] [ARGS...]: runs untangle on NAME.case.json or a path
  local name=$1 rc_want=$2 pattern=${3:-}
  shift 3 2> /dev/null || shift $#
  local input="$work/$name.case.json"
  [ -e "$input" ] || input=$name
  "$mm" untangle "$input" --quiet "$@" > "$work/$(basename "$name").out" 2> "$work/$(basename "$name").err"
  local rc=$?
  [ "$rc" = "$rc_want" ] || fail "$name: exit $rc, expected $rc_want: $(cat "$work/$(basename "$name").err")"
  [ -z "$pattern" ] || grep -q "$pattern" "$work/$(basename "$name").err" "$work/$(basename "$name").out" ||
    fail "$name: no '$pattern' in $(cat "$work/$(basename "$name").err")"
}

# Example 05: tangled once the top wall is in place, valid at the end.
cp "$channel/squeeze.csv" "$work/"
make_case squeeze '[{"group": "top", "displace": {"file": "squeeze.csv"}}, {"group": "bottom", "fixed": true}]'
expect squeeze 0
[ -s "$work/squeeze.vtu" ] || fail "squeeze: no mesh written"
[ "$(field "$work/squeeze.json" method)" = untangle ] || fail "squeeze: method"
[ "$(field "$work/squeeze.json" initial_inverted_elements)" -gt 0 ] || fail "squeeze: the case did not start tangled"
[ "$(field "$work/squeeze.json" inverted_elements)" = 0 ] || fail "squeeze: inverted elements left"
[ "$(field "$work/squeeze.json" converged)" = true ] || fail "squeeze: not converged"
"$mm" --quiet quality "$work/squeeze.vtu" > /dev/null || fail "squeeze: output invalid or unreadable"

# A run out of Newton steps: exit 1, no mesh.
make_case budget '[{"group": "top", "displace": {"file": "squeeze.csv"}}, {"group": "bottom", "fixed": true}]' \
  '{"max_newton": 1, "predictor": false}'
expect budget 1 "still tangled after max_newton"
[ ! -e "$work/budget.vtu" ] || fail "budget: a mesh was written by a run that missed its goal"

# A bare tangled mesh: untangled with its boundary fixed, written next to it as NAME_untangled.
cp "$data/tangled_quads.msh" "$work/"
expect "$work/tangled_quads.msh" 0 "reference regular"
[ -s "$work/tangled_quads_untangled.msh" ] || fail "bare mesh: no tangled_quads_untangled.msh written"
"$mm" --quiet quality "$work/tangled_quads_untangled.msh" > /dev/null || fail "bare mesh: output invalid"
printf '{"mesh": "tangled_quads.msh", "boundary": [], "options": {"reference": "input"}, "output": "ref.vtu"}\n' \
  > "$work/ref_input.case.json"
expect ref_input 2 "needs a valid input mesh"
[ ! -e "$work/ref.vtu" ] || fail "ref_input: a mesh was written"

# Bad input: exit 2, nothing written.
make_case unknown_option '[{"group": "bottom", "fixed": true}]' '{"delta0": 1}'
expect unknown_option 2 "options.delta0"
make_case bad_rule '[{"group": "bottom", "fixed": true}]' '{"delta_rule": "fast"}'
expect bad_rule 2 "options.delta_rule"
for name in unknown_option bad_rule; do
  [ ! -e "$work/$name.vtu" ] && [ ! -e "$work/$name.json" ] || fail "$name: something was written for bad input"
done

# The top wall pushed through the bottom one: no valid mesh exists; exit 1, no mesh.
awk -F, 'NR == 1 { print; next } { printf "%s,%s,%.17g\n", $1, $2, $3 - 1.5 }' "$channel/squeeze.csv" > "$work/through.csv"
make_case folded '[{"group": "top", "displace": {"file": "through.csv"}}, {"group": "bottom", "fixed": true}]'
expect folded 1 "no valid mesh\|no interior motion"
[ ! -e "$work/folded.vtu" ] || fail "folded: a mesh was written"
[ "$(field "$work/folded.json" converged)" = false ] || fail "folded: report says converged"
# "boundary": "slide": a `project` group slides along its level set, the other boundary nodes
# along the input's facets; the report says so and measures their distance from the surfaces.
printf '{"mesh": "%s", "boundary": [{"group": "sphere", "project": {"sphere": {"center": [0, 0, 0], "radius": 0.4}}}], "options": {"boundary": "slide"}, "output": "slide.vtu", "report": "slide.json"}\n' \
  "$(realpath "$examples/meshes/sphere_in_box_p2.msh")" > "$work/slide.case.json"
expect slide 0 "boundary slides along itself"
[ "$(field "$work/slide.json" boundary)" = slide ] || fail "slide: boundary $(field "$work/slide.json" boundary)"
awk -v a="$(field "$work/slide.json" boundary_deviation_max)" 'BEGIN { exit !(a + 0 < 1e-10) }' || fail "slide: nodes left their surfaces"
"$mm" --quiet quality "$work/slide.vtu" > /dev/null || fail "slide: output invalid"
echo "untangle CLI checks passed"
