#!/usr/bin/python3
# SPDX-License-Identifier: MIT
"""Gmsh (Debian gmsh 4.8.4) reads meshmorph's 3D .msh output and finds every cell valid.

Usage: gmsh_reads_output.py WRITE_SAMPLES_EXE OUTDIR

For every 3D .msh sample (MSH 4.1 and 2.2, ASCII and binary; structured meshes of the unit
cube: tetrahedra, hexahedra, prisms of orders 1-4, pyramids), Gmsh merges the file and runs
its AnalyseMeshQuality plugin, whose minJ/maxJ is the ratio of Gmsh's own bounds of the
Jacobian determinant over each cell, from Gmsh's own node ordering. The samples' cells are
straight-sided, so a node in a place other than the one Gmsh expects shows up as a ratio
below 1 (or a cell Gmsh finds inverted); the check is that Gmsh sees as many cells as were
written and that each ratio is above 0.99. Gmsh 4.8.4 reports "FaceClosureFull not
implemented for prisms of order 3" (and 4) while it analyses prisms of those orders, its own
meshes of them included, and analyses them all the same (exiting 1 for the message): that
message is not a failure.
Exits 77 (skipped) without gmsh.
"""
import os
import re
import shutil
import subprocess
import sys

GEO = """Merge "{msh}";
Plugin(AnalyseMeshQuality).JacobianDeterminant = 1;
Plugin(AnalyseMeshQuality).IGEMeasure = 0;
Plugin(AnalyseMeshQuality).ICNMeasure = 0;
Plugin(AnalyseMeshQuality).HidingThreshold = 99;
Plugin(AnalyseMeshQuality).DimensionOfElements = 3;
Plugin(AnalyseMeshQuality).CreateView = 1;
Plugin(AnalyseMeshQuality).Run;
Save View[PostProcessing.NbViews - 1] "{pos}";
"""


def main():
    gmsh = shutil.which("gmsh")
    if gmsh is None:
        print("gmsh is not installed: skipped")
        sys.exit(77)
    exe, outdir = sys.argv[1], sys.argv[2]
    subprocess.run([exe, outdir], check=True)
    failures, checked = [], 0
    work = os.path.join(outdir, "gmsh")
    os.makedirs(work, exist_ok=True)
    for line in open(f"{outdir}/manifest.txt"):
        name, family, order, dim, _, n_cells = line.split()[:6]
        if not name.endswith(".msh") or dim != "3":
            continue
        pos = os.path.join(work, name + ".pos")
        geo = os.path.join(work, name + ".geo")
        with open(geo, "w") as f:
            f.write(GEO.format(msh=os.path.abspath(os.path.join(outdir, name)), pos=os.path.abspath(pos)))
        r = subprocess.run([gmsh, geo, "-0"], stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True,
                           errors="replace", cwd=work)
        lines = [l for l in r.stdout.splitlines() if l.startswith("Error")]
        errors = [l for l in lines if "FaceClosureFull" not in l]
        if (r.returncode != 0 and (errors or not lines)) or errors or not os.path.exists(pos):
            failures.append(f"{name}: gmsh exit {r.returncode}: {' / '.join(errors[:3])}")
            continue
        checked += 1
        ratios = [min(float(v) for v in m.split(","))
                  for m in re.findall(r"^S[SHIY]\([^)]*\)\{([^}]*)\}", open(pos).read(), re.M)]
        if len(ratios) != int(n_cells):
            failures.append(f"{name}: Gmsh sees {len(ratios)} cells, {n_cells} were written")
        elif min(ratios) <= 0.99:
            failures.append(f"{name}: a {family} of order {order} has Gmsh's minJ/maxJ {min(ratios)}")
    print(f"gmsh read {checked} files")
    for f in failures:
        print("FAIL:", f)
    sys.exit(1 if failures or checked == 0 else 0)


if __name__ == "__main__":
    main()
