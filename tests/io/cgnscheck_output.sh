#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# cgnscheck_output.sh MESHMORPH DATA WORK: the CGNS project's checker (cgnscheck, Debian
# cgns-convert) finds no error in what meshmorph writes: a hybrid mesh (prisms, pyramids,
# hexahedra, tetrahedra and its facet groups), a P2 hybrid sphere, a P3 hexahedral box and a
# morph's time series with its fields (a moving grid); skipped (77) without cgnscheck.
set -u
mm=$1 data=$2 work=$3
command -v cgnscheck >/dev/null || { echo "cgnscheck (cgns-convert) is missing: skipped"; exit 77; }
rm -rf "$work" && mkdir -p "$work"
fail() { echo "FAIL: $*"; exit 1; }
"$mm" convert "$data/hybrid_layer.msh" "$work/hybrid.cgns" --quiet || fail "convert hybrid_layer.msh"
"$mm" convert "$data/hybrid_layer.msh" "$work/hybrid_p2.cgns" --order 2 --quiet || fail "convert to order 2"
"$mm" convert "$data/io/gmsh_tet4_22a.msh" "$work/tet_p3.cgns" --order 3 --quiet || fail "convert to order 3"
cat > "$work/series.json" <<CASE
{"mesh": "$data/../../examples/meshes/annulus.msh", "boundary": [{"group": "inner", "rotate": {"center": [0, 0], "degrees": 30}},
 {"group": "outer", "fixed": true}], "steps": 3, "dt": 0.1, "output_each_step": true, "output": "series.cgns"}
CASE
"$mm" morph "$work/series.json" --quiet || fail "morph into series.cgns"
for f in "$work"/*.cgns; do
  cgnscheck "$f" > "$f.check" 2>&1 || fail "cgnscheck $f: exit $?: $(tail -5 "$f.check")"
  grep -qi "error" "$f.check" && fail "cgnscheck $f: $(grep -i error "$f.check" | head -3)"
done
echo ok
