#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# check_morph.sh MESHMORPH EXAMPLES WORK: `morph` end to end on the annulus example — a
# converged run writes a valid mesh and its report (timings included; --verbose prints them),
# the same on one thread as on all cores;
# bad motions, a step file that would replace an input, two outputs on one file and outputs
# that cannot be written exit 2 and write nothing; a run out of budget and a baseline that
# inverts elements exit 1 and write no mesh.
set -u
mm=$1 examples=$2 work=$3
rm -rf "$work" && mkdir -p "$work"
mesh=$(realpath "$examples/meshes/annulus.msh")
fail() { echo "FAIL: $*"; exit 1; }
field() { sed -n "s/^  \"$2\": \"\{0,1\}\([^\",]*\)\"\{0,1\},\{0,1\}$/\1/p" "$1"; }
make_case() {  # make_case NAME BOUNDARY_JSON [OPTIONS_JSON]
  printf '{"mesh": "%s", "boundary": %s, "options": %s, "output": "%s.vtu", "report": "%s.json"}\n' \
    "$mesh" "$2" "${3:-{\}}" "$1" "$1" > "$work/$1.case.json"
}
expect() {  # expect NAME EXIT [PATTERN]: runs the case, checks exit code and stderr
  "$mm" morph "$work/$1.case.json" --quiet > "$work/$1.out" 2> "$work/$1.err"
  local rc=$?
  [ "$rc" = "$2" ] || fail "$1: exit $rc, expected $2: $(cat "$work/$1.err")"
  [ -z "${3:-}" ] || grep -q "$3" "$work/$1.err" "$work/$1.out" || fail "$1: no '$3' in $(cat "$work/$1.err")"
}
rotate='[{"group": "inner", "rotate": {"center": [0, 0], "degrees": 15}}, {"group": "outer", "fixed": true}]'

make_case ok "$rotate"
expect ok 0
[ -s "$work/ok.vtu" ] || fail "ok: no mesh written"
[ "$(field "$work/ok.json" valid)" = true ] || fail "ok: report not valid"
[ "$(field "$work/ok.json" converged)" = true ] || fail "ok: not converged"
awk -v e="$(field "$work/ok.json" boundary_error_max)" 'BEGIN { exit !(e < 1e-8) }' || fail "ok: boundary error"
"$mm" --quiet quality "$work/ok.vtu" > /dev/null || fail "ok: output unreadable"
# On all cores by default, on one with --threads 1, to the same mesh.
cores=$(nproc)
grep -q "on $cores thread" "$work/ok.out" || fail "ok: not on the $cores cores: $(cat "$work/ok.out")"
"$mm" --threads 1 morph "$work/ok.case.json" --quiet -o "$work/ok1.vtu" --report "$work/ok1.json" > "$work/ok1.out" 2>&1 ||
  fail "ok1: exit $?: $(cat "$work/ok1.out")"
grep -q "on 1 thread$" "$work/ok1.out" || fail "ok1: --threads 1 not used: $(cat "$work/ok1.out")"
cmp -s "$work/ok.vtu" "$work/ok1.vtu" || fail "ok1: one thread wrote another mesh than $cores"
# The report's seconds by phase; --verbose prints them after the time line.
grep -q '"timings": {' "$work/ok.json" || fail "ok: no timings in the report"
for phase in assembly validity line_search solver_setup solve io other; do
  grep -q "^    \"$phase\": [0-9]" "$work/ok.json" || fail "ok: no timings.$phase in the report"
done
"$mm" --verbose morph "$work/ok.case.json" -o "$work/okv.vtu" --report "$work/okv.json" > "$work/okv.out" 2> /dev/null ||
  fail "okv: exit $?"
grep -q "^timings  assembly [0-9.]* s, validity [0-9.]* s, line search [0-9.]* s, solver setup [0-9.]* s, solve [0-9.]* s, io [0-9.]* s, other [0-9.]* s$" "$work/okv.out" ||
  fail "okv: no timings line: $(cat "$work/okv.out")"
grep -q "^timings" "$work/ok.out" && fail "ok: a timings line without --verbose"

make_case unknown_group '[{"group": "rotor", "translate": [1, 0]}]'
expect unknown_group 2 "rotor"
make_case unreachable '[{"group": "inner", "project": {"expr": "x^2 + y^2 + 1"}}]'
expect unreachable 2 "cannot reach"
# One row, for a node of the inner circle (physical group 2): the other nodes of the group have none.
"$mm" --quiet convert "$mesh" "$work/annulus22.msh" --msh22 || fail "convert to MSH 2.2"
first_node() {  # first_node TAG: the first node of a line element of physical group TAG
  awk -v tag="$1" '/^\$Elements/ {on=1; next} on && $2 == 1 && $4 == tag {print $6; exit}' "$work/annulus22.msh"
}
inner_node=$(first_node 2)
printf 'node,dx,dy\n%s,0.1,0\n' "$inner_node" > "$work/short.csv"
make_case missing_row "[{\"group\": \"inner\", \"displace\": {\"file\": \"short.csv\"}}]"
expect missing_row 2 "has no row for node"
# A row for a node of the fixed outer circle: an error, not a motion of a fixed node.
outer_node=$(first_node 1)
printf 'node,dx,dy\n%s,0.1,0\n' "$outer_node" > "$work/other_group.csv"
make_case other_group "[{\"group\": \"inner\", \"displace\": {\"file\": \"other_group.csv\"}}]"
expect other_group 2 "node $outer_node is not in group \"inner\""
make_case bad_finish "$rotate" '{"finish": "sideways"}'
expect bad_finish 2 "finish"
make_case budget "$rotate" '{"max_outer": 1}'
expect budget 1 "augmented-Lagrangian iterations"
[ "$(field "$work/budget.json" converged)" = false ] || fail "budget: report says converged"
make_case laplace '[{"group": "inner", "rotate": {"center": [0, 0], "degrees": 120}}]' '{"method": "laplace"}'
expect laplace 1 "inverted elements"
# A baseline in increments: one solve each on the mesh the last one left, every step written.
printf '{"mesh": "%s", "boundary": %s, "options": {"method": "laplace"}, "steps": 3, "output_each_step": true, "output": "inc.vtu", "report": "inc.json"}\n' \
  "$mesh" "$rotate" > "$work/inc.case.json"
expect inc 0
[ -s "$work/inc_0001.vtu" ] && [ -s "$work/inc_0002.vtu" ] && [ -s "$work/inc.vtu" ] || fail "inc: step files missing"
grep -q '"linear": 3' "$work/inc.json" || fail "inc: not three solves: $(grep -A4 iterations "$work/inc.json")"
# A key morph would ignore (fit's trim): exit 2.
printf '{"mesh": "%s", "boundary": %s, "trim": {"expr": "x"}, "output": "trim.vtu"}\n' "$mesh" "$rotate" > "$work/trim.case.json"
expect trim 2 "trim: morph does not use this key"
[ ! -e "$work/trim.vtu" ] || fail "trim: a mesh was written"
for name in unknown_group unreachable missing_row other_group bad_finish budget laplace; do
  [ ! -e "$work/$name.vtu" ] || fail "$name: a mesh was written"
done
for name in unknown_group unreachable missing_row other_group bad_finish; do
  [ ! -e "$work/$name.json" ] || fail "$name: a report was written for bad input"
done
# A file written by the run never replaces an input that the user did not name as the output
# mesh (DESIGN 3.1): the step files of output_each_step, a report. Nor do two outputs share a
# file. Exit 2, nothing written, the inputs unchanged.
cp "$mesh" "$work/own_0001.msh"
own() {  # own NAME OUTPUT REPORT [EXTRA]: a case on the copy own_0001.msh of the mesh
  printf '{"mesh": "own_0001.msh", "boundary": %s, %s"output": "%s", "report": "%s"}\n' "$rotate" "${4:-}" "$2" "$3" \
    > "$work/$1.case.json"
}
own steps own.msh steps.json '"steps": 2, "output_each_step": true, '
own reportover reportover.vtu own_0001.msh  # a report over the input mesh
own twice twice.vtu ./twice.vtu
# An output that cannot be written stops the run before the others are: a report in a missing
# folder, a report path that is a folder, a step file that is a folder.
own nofolder nofolder.vtu nodir/nofolder.json
mkdir -p "$work/afolder.json" "$work/sf_0001.vtu"
own folder folder.vtu afolder.json
own stepfolder sf.vtu stepfolder.json '"steps": 2, "output_each_step": true, '
before=$(cksum < "$work/own_0001.msh")
expect steps 2 "only an output mesh you name"
expect reportover 2 "report: .*own_0001.msh is a file this run reads"
expect twice 2 "a path of its own"
expect nofolder 2 "nodir/nofolder.json: no folder"
expect folder 2 "afolder.json is a folder"
expect stepfolder 2 "sf_0001.vtu is a folder"
[ "$(cksum < "$work/own_0001.msh")" = "$before" ] || fail "the input mesh was changed"
for f in own.msh steps.json reportover.vtu twice.vtu nofolder.vtu folder.vtu sf.vtu stepfolder.json; do
  [ ! -e "$work/$f" ] || fail "$f was written"
done
# output_each_step names its step files after -o where the case gives no "output", and
# without either it is bad input.
printf '{"mesh": "%s", "boundary": %s, "steps": 2, "output_each_step": true}\n' "$mesh" "$rotate" > "$work/each.case.json"
"$mm" --quiet morph "$work/each.case.json" -o "$work/each.vtu" > /dev/null 2>&1 || fail "each: exit $?"
[ -s "$work/each_0001.vtu" ] && [ -s "$work/each.vtu" ] || fail "each: the step files were not written after -o"
expect each 2 'output_each_step: needs "output" (or -o)'
own named own_0001.msh named.json  # named by the user: replaced
expect named 0
[ "$(cksum < "$work/own_0001.msh")" != "$before" ] || fail "named: the output was not written"

# Projection onto a `mesh` level set read from a file: P2 triangles over [-1.2, 1.2]² with
# the point data phi = |x| − 0.44, so the inner circle (r = 0.4) grows to about r = 0.44.
awk 'BEGIN {
  n = 24; h = 2.4 / n; m = 2 * n + 1
  print "<?xml version=\"1.0\"?>"
  print "<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\">"
  printf "<UnstructuredGrid><Piece NumberOfPoints=\"%d\" NumberOfCells=\"%d\">\n", m * m, 2 * n * n
  print "<Points><DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"ascii\">"
  for (j = 0; j < m; j++) for (i = 0; i < m; i++) printf "%.17g %.17g 0\n", -1.2 + i * h / 2, -1.2 + j * h / 2
  print "</DataArray></Points><Cells><DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">"
  for (b = 0; b < n; b++) for (a = 0; a < n; a++) {
    i = 2 * a; j = 2 * b
    printf "%d %d %d %d %d %d\n", j*m+i, j*m+i+2, (j+2)*m+i+2, j*m+i+1, (j+1)*m+i+2, (j+1)*m+i+1
    printf "%d %d %d %d %d %d\n", j*m+i, (j+2)*m+i+2, (j+2)*m+i, (j+1)*m+i+1, (j+2)*m+i+1, (j+1)*m+i
  }
  print "</DataArray><DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">"
  for (c = 1; c <= 2 * n * n; c++) printf "%d\n", 6 * c
  print "</DataArray><DataArray type=\"UInt8\" Name=\"types\" format=\"ascii\">"
  for (c = 1; c <= 2 * n * n; c++) print 22
  print "</DataArray></Cells><PointData><DataArray type=\"Float64\" Name=\"phi\" format=\"ascii\">"
  for (j = 0; j < m; j++) for (i = 0; i < m; i++) {
    x = -1.2 + i * h / 2; y = -1.2 + j * h / 2; printf "%.17g\n", sqrt(x * x + y * y) - 0.44
  }
  print "</DataArray></PointData></Piece></UnstructuredGrid></VTKFile>"
}' > "$work/background.vtu"
make_case mesh_field '[{"group": "inner", "project": {"mesh": {"file": "background.vtu", "field": "phi"}}}, {"group": "outer", "fixed": true}]'
expect mesh_field 0
[ "$(field "$work/mesh_field.json" valid)" = true ] || fail "mesh_field: report not valid"
make_case mesh_field_missing '[{"group": "inner", "project": {"mesh": {"file": "background.vtu", "field": "psi"}}}]'
expect mesh_field_missing 2 'boundary\[0\].project.mesh.field: .*background.vtu has no nodal field "psi" (its nodal fields: "phi")'
[ ! -e "$work/mesh_field_missing.vtu" ] || fail "mesh_field_missing: a mesh was written"

echo "morph CLI checks passed"
