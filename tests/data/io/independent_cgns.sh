#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Regenerates tecplot_to_cgns_tet4.cgns, a CGNS file written by another program than
# meshmorph: the tetrahedra of gmsh_tet4_22a.msh as a Tecplot FEPOINT zone (meshio reads the
# .msh), converted by tecplot_to_cgns of Debian's cgns-convert (the CGNS project's own tools).
set -eu
cd "$(dirname "$0")"
/usr/bin/python3 - <<'PY'
import meshio
m = meshio.read("gmsh_tet4_22a.msh")
tets = next(c.data for c in m.cells if c.type == "tetra")
with open("/tmp/tecplot_tet4.dat", "w") as f:
    f.write('TITLE="gmsh_tet4_22a"\nVARIABLES="X","Y","Z"\n')
    f.write(f"ZONE N={len(m.points)}, E={len(tets)}, F=FEPOINT, ET=TETRAHEDRON\n")
    for p in m.points:
        f.write(f"{p[0]!r} {p[1]!r} {p[2]!r}\n")
    for t in tets:
        f.write(" ".join(str(i + 1) for i in t) + "\n")
PY
tecplot_to_cgns /tmp/tecplot_tet4.dat tecplot_to_cgns_tet4.cgns
