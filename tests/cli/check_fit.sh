#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# check_fit.sh MESHMORPH EXAMPLES WORK: `fit` end to end on the quad channel of example 04 —
# the fitted run writes a valid mesh and a report with fit_error_max below eps_sigma; a
# level set with no zero crossing in the mesh, a background field or distance box that does not
# cover it, a circle that no facet is left on, a level set that is NaN somewhere, an unknown
# key of a distance level set and a metric of the other dimension exit 2 and write nothing;
# the circle through a distance field fits as well; a run out of Newton steps exits 1 and
# writes no mesh; without splits the fit needs flat_edges.
set -u
mm=$1 examples=$2 work=$3
rm -rf "$work" && mkdir -p "$work"
mesh=$(realpath "$examples/meshes/quad_channel.msh")
fail() { echo "FAIL: $*"; exit 1; }
field() { sed -n "s/^  \"$2\": \"\{0,1\}\([^\",]*\)\"\{0,1\},\{0,1\}$/\1/p" "$1"; }
make_case() {  # make_case NAME INTERFACE_JSON [OPTIONS_JSON]
  printf '{"mesh": "%s", "order": 2, "boundary": [{"group": "bottom", "slide": true}], "interface": %s, "options": %s, "output": "%s.vtu", "report": "%s.json"}\n' \
    "$mesh" "$2" "${3:-{\}}" "$1" "$1" > "$work/$1.case.json"
}
expect() {  # expect NAME EXIT [PATTERN]
  "$mm" fit "$work/$1.case.json" --quiet > "$work/$1.out" 2> "$work/$1.err"
  local rc=$?
  [ "$rc" = "$2" ] || fail "$1: exit $rc, expected $2: $(cat "$work/$1.err")"
  [ -z "${3:-}" ] || grep -q "$3" "$work/$1.err" "$work/$1.out" || fail "$1: no '$3' in $(cat "$work/$1.err")"
}
circle='{"sphere": {"center": [1, 0.4], "radius": 0.25}}'

make_case ok "$circle" '{"eps_sigma": 1e-8}'
expect ok 0
[ -s "$work/ok.vtu" ] || fail "ok: no mesh written"
[ "$(field "$work/ok.json" method)" = fit ] || fail "ok: method"
[ "$(field "$work/ok.json" valid)" = true ] || fail "ok: report not valid"
awk -v e="$(field "$work/ok.json" fit_error_max)" 'BEGIN { exit !(e <= 1e-8) }' || fail "ok: fit_error_max"
[ "$(field "$work/ok.json" cells_with_two_interface_facets)" = 0 ] || fail "ok: a cell has two interface facets"
"$mm" --quiet quality "$work/ok.vtu" > /dev/null || fail "ok: output invalid or unreadable"
# What fit picked where the case left it open: the target and the solver, each with a reason.
grep -q '"choices"' "$work/ok.json" && grep -q '"target"' "$work/ok.json" && grep -q '"why"' "$work/ok.json" || fail "ok: no choices in the report"
[ "$(field "$work/ok.json" pillowed_cells)" = 0 ] || fail "ok: a quadrilateral mesh was pillowed by default"

# The same circle through a distance field on a refined background mesh (paper 003 §3.1).
make_case distance '{"distance": {"of": '"$circle"', "lower": [0, 0], "upper": [2, 1], "levels": 3}}' '{"eps_sigma": 1e-8}'
expect distance 0
[ "$(field "$work/distance.json" valid)" = true ] || fail "distance: report not valid"
awk -v e="$(field "$work/distance.json" fit_error_max)" 'BEGIN { exit !(e <= 1e-8) }' || fail "distance: fit_error_max"

# Without the conforming splits, the cells with two interface facets flatten at their shared
# corner: the usual validity test stops the fit short; flat_edges lets it reach eps_sigma, and
# the report counts the cells that are flat at that corner (docs/fit.md).
make_case nosplit "$circle" '{"eps_sigma": 1e-8, "split": false}'
expect nosplit 1 "above eps_sigma"
[ "$(field "$work/nosplit.json" cells_with_two_interface_facets)" -gt 0 ] || fail "nosplit: no cell with two interface facets"
make_case flat "$circle" '{"eps_sigma": 1e-8, "split": false, "flat_edges": true}'
expect flat 0
[ "$(field "$work/flat.json" valid)" = true ] || fail "flat: report not valid"
awk -v e="$(field "$work/flat.json" fit_error_max)" 'BEGIN { exit !(e <= 1e-8) }' || fail "flat: fit_error_max"
[ "$(field "$work/flat.json" flat_edge_cells)" -gt 0 ] || fail "flat: no flat cell reported"

make_case budget "$circle" '{"max_newton": 1}'
expect budget 1 "above eps_sigma"
[ ! -e "$work/budget.vtu" ] || fail "budget: a mesh was written"

make_case no_crossing '{"sphere": {"center": [10, 10], "radius": 0.1}}'
expect no_crossing 2 "interface: the level set has no zero crossing in the mesh"
# A circle around the node (1, 0.5), smaller than the cells: the level set crosses the mesh,
# but eq. 10 puts every cell outside it and no facet is left to fit.
make_case vanished '{"sphere": {"center": [1, 0.5], "radius": 0.01}}'
expect vanished 2 "interface: no node to fit: the material indicators"
[ ! -e "$work/vanished.vtu" ] && [ ! -e "$work/vanished.json" ] || fail "vanished: something was written"
make_case not_a_number '{"expr": "y - 0.5 - sqrt(x - 1)"}'
expect not_a_number 2 "interface: the level set is not a number at node"
make_case wrong_metric "$circle" '{"metric": "mu303"}'
expect wrong_metric 2 "options.metric: mu303 is a 3D metric"
make_case no_group "$circle" '{"materials": "inner"}'
expect no_group 2 'options.materials: no volume group "inner"'

# A background field over [0, 1] x [0, 0.5] only: it does not cover the channel [0, 2] x [0, 1].
awk 'BEGIN {
  print "<?xml version=\"1.0\"?>"
  print "<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\">"
  print "<UnstructuredGrid><Piece NumberOfPoints=\"4\" NumberOfCells=\"2\">"
  print "<Points><DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"ascii\">"
  print "0 0 0 1 0 0 1 0.5 0 0 0.5 0"
  print "</DataArray></Points><Cells><DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">"
  print "0 1 2 0 2 3"
  print "</DataArray><DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">3 6</DataArray>"
  print "<DataArray type=\"UInt8\" Name=\"types\" format=\"ascii\">5 5</DataArray></Cells>"
  print "<PointData><DataArray type=\"Float64\" Name=\"phi\" format=\"ascii\">-0.5 0.5 0.5 -0.5</DataArray></PointData>"
  print "</Piece></UnstructuredGrid></VTKFile>"
}' > "$work/small.vtu"
make_case not_covered '{"mesh": {"file": "small.vtu", "field": "phi"}}'
expect not_covered 2 "small.vtu does not cover the mesh"
make_case distance_small '{"distance": {"of": '"$circle"', "lower": [0, 0], "upper": [1, 1]}}'
expect distance_small 2 "interface.distance: the box \[lower, upper\] does not cover the mesh"
make_case distance_key '{"distance": {"of": '"$circle"', "lower": [0, 0], "upper": [2, 1], "level": 3}}'
expect distance_key 2 'interface.distance.level: unknown key'
for name in no_crossing wrong_metric no_group not_covered distance_small distance_key; do
  [ ! -e "$work/$name.vtu" ] && [ ! -e "$work/$name.json" ] || fail "$name: something was written for bad input"
done
echo "fit CLI checks passed"
