#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# check_repair.sh MESHMORPH SCRIPTS WORK: `meshmorph untangle MESH` repairs a P2 tetrahedral mesh
# of a sphere in a box as Gmsh makes it (scripts/repair_meshes.py), whose inverted cell has all
# its corners on the sphere: the boundary slides along its own surface (the report and the
# summary say so), the result is valid, its boundary nodes stay on the input's surface to 1e-12
# and the repair is that of a patch around the cell. Skipped (77) without python3-gmsh or where
# this Gmsh makes no inverted cell.
set -u
mm=$1 scripts=$2 work=$3
rm -rf "$work" && mkdir -p "$work"
fail() { echo "FAIL: $*"; exit 1; }
field() { sed -n "s/^  \"$2\": \"\{0,1\}\([^\",]*\)\"\{0,1\},\{0,1\}$/\1/p" "$1"; }
less() { awk -v a="$1" -v b="$2" 'BEGIN { exit !(a + 0 < b + 0) }'; }
/usr/bin/python3 -c "import gmsh" 2> /dev/null || { echo "no python3-gmsh: skipped"; exit 77; }
/usr/bin/python3 "$scripts/repair_meshes.py" "$work" sphere_p2tet_0.4 > "$work/gmsh.json" || fail "repair_meshes.py"
mesh=$work/sphere_p2tet_0.4.msh
"$mm" --quiet quality "$mesh" --json "$work/input.json" > /dev/null
[ "$(field "$work/input.json" inverted_elements)" != 0 ] || { echo "this Gmsh makes no inverted cell: skipped"; exit 77; }

"$mm" untangle "$mesh" --report "$work/r.json" > "$work/out" 2> "$work/err" || fail "exit $?: $(cat "$work/out" "$work/err")"
grep -q "boundary slides along itself" "$work/out" || fail "the summary does not say the boundary slides"
[ "$(field "$work/r.json" boundary)" = slide ] || fail "report: boundary $(field "$work/r.json" boundary)"
[ "$(field "$work/r.json" inverted_elements)" = 0 ] && [ "$(field "$work/r.json" valid)" = true ] || fail "not valid"
less "$(field "$work/r.json" boundary_deviation_max)" 1e-12 || fail "boundary nodes left the surface"
less 0 "$(field "$work/r.json" patch_cells)" || fail "no patch"
"$mm" --quiet quality "$work/sphere_p2tet_0.4_untangled.msh" > /dev/null || fail "the written mesh is invalid"
echo "repair CLI checks passed"
