#!/usr/bin/python3
# SPDX-License-Identifier: MIT
"""VTK (Debian python3-vtk9, 9.1) reads meshmorph's .vtu output with positive cell volumes.

Usage: vtk_reads_output.py WRITE_SAMPLES_EXE OUTDIR

For every 3D sample (structured meshes of the unit cube: tetrahedra, hexahedra, prisms,
pyramids, every order written), vtkCellSizeFilter's volume of each cell of the mesh's
dimension is positive and the volumes add up to 1. Exits 77 (skipped) without VTK.
"""
import math
import subprocess
import sys

try:
    import vtk
    from vtk.util.numpy_support import vtk_to_numpy
except ImportError:
    print("python3-vtk9 is not installed: skipped")
    sys.exit(77)


def main():
    exe, outdir = sys.argv[1], sys.argv[2]
    subprocess.run([exe, outdir], check=True)
    failures, checked = [], 0
    for line in open(f"{outdir}/manifest.txt"):
        name, family, order, dim = line.split()[:4]
        if not name.endswith(".vtu") or dim != "3":
            continue
        reader = vtk.vtkXMLUnstructuredGridReader()
        reader.SetFileName(f"{outdir}/{name}")
        reader.Update()
        grid = reader.GetOutput()
        sizes = vtk.vtkCellSizeFilter()
        sizes.SetInputData(grid)
        sizes.Update()
        volume = vtk_to_numpy(sizes.GetOutput().GetCellData().GetArray("Volume"))
        cells = [i for i in range(grid.GetNumberOfCells()) if grid.GetCell(i).GetCellDimension() == 3]
        if not cells:
            failures.append(f"{name}: VTK finds no 3D cell")
            continue
        checked += 1
        lowest = min(volume[i] for i in cells)
        total = sum(volume[i] for i in cells)
        if lowest <= 0:
            failures.append(f"{name}: a {family} of order {order} has volume {lowest}")
        if not math.isclose(total, 1.0, rel_tol=1e-9):
            failures.append(f"{name}: the volumes add up to {total}, not 1")
    print(f"VTK {vtk.vtkVersion.GetVTKVersion()} read {checked} files")
    for f in failures:
        print("FAIL:", f)
    sys.exit(1 if failures or checked == 0 else 0)


if __name__ == "__main__":
    main()
