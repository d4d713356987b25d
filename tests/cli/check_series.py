#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""check_series.py MESHMORPH EXAMPLES WORK: a 10-step morph of the annulus with `dt` and
`output_each_step` writes a VTU series that VTK reads through its .pvd: ten files at the times
k·dt, each with point data `displacement` (from the input: x_k − displacement_k is the same
input for every k) and `mesh_velocity` equal to the finite difference of the positions,
(x_k − x_{k−1})/dt, and cell data `quality` in (0, 1]. The same run with a .msh output carries
the same fields as $NodeData / $ElementData (read by meshio). Skipped (77) without VTK."""
import json
import pathlib
import subprocess
import sys
import xml.etree.ElementTree as ET

import numpy as np

try:
    import vtk
    from vtk.util.numpy_support import vtk_to_numpy
except ImportError:
    print("python3-vtk9 is missing: skipped")
    sys.exit(77)

mm, examples, work = sys.argv[1], pathlib.Path(sys.argv[2]), pathlib.Path(sys.argv[3])
work.mkdir(parents=True, exist_ok=True)
steps, dt = 10, 0.05


def run(output):
    case = {"mesh": str((examples / "meshes" / "annulus.msh").resolve()),
            "boundary": [{"group": "inner", "rotate": {"center": [0, 0], "degrees": 40}},
                         {"group": "outer", "fixed": True}],
            "steps": steps, "dt": dt, "output_each_step": True, "output": output}
    path = work / (output + ".case.json")
    path.write_text(json.dumps(case))
    r = subprocess.run([mm, "morph", str(path), "--quiet"], capture_output=True, text=True)
    if r.returncode != 0:
        sys.exit(f"FAIL: morph exit {r.returncode}: {r.stderr}")


def fail(what):
    sys.exit("FAIL: " + what)


run("series.vtu")
pvd = ET.parse(work / "series.pvd").getroot()
sets = pvd.findall("./Collection/DataSet")
if len(sets) != steps:
    fail(f"{len(sets)} data sets in series.pvd, expected {steps}")
x, disp, vel = [], [], []
for k, ds in enumerate(sets, start=1):
    if abs(float(ds.get("timestep")) - k * dt) > 1e-12:
        fail(f"data set {k} at time {ds.get('timestep')}, expected {k * dt}")
    reader = vtk.vtkXMLUnstructuredGridReader()
    reader.SetFileName(str(work / ds.get("file")))
    reader.Update()
    grid = reader.GetOutput()
    if grid.GetNumberOfPoints() == 0:
        fail(f"VTK read no points from {ds.get('file')}")
    x.append(vtk_to_numpy(grid.GetPoints().GetData()))
    disp.append(vtk_to_numpy(grid.GetPointData().GetArray("displacement")))
    vel.append(vtk_to_numpy(grid.GetPointData().GetArray("mesh_velocity")))
    quality = vtk_to_numpy(grid.GetCellData().GetArray("quality"))
    cells = quality[~np.isnan(quality)]
    if cells.size == 0 or cells.min() <= 0 or cells.max() > 1 + 1e-12:
        fail(f"{ds.get('file')}: cell quality outside (0, 1]")
scale = np.abs(x[0]).max()
x0 = x[0] - disp[0]
for k in range(steps):
    if np.abs(x[k] - disp[k] - x0).max() > 1e-12 * scale:
        fail(f"step {k + 1}: x − displacement is not the input")
    previous = x0 if k == 0 else x[k - 1]
    fd = (x[k] - previous) / dt
    if np.abs(vel[k] - fd).max() > 1e-9 * max(1.0, np.abs(fd).max()):
        fail(f"step {k + 1}: mesh_velocity differs from (x_k − x_(k−1))/dt by {np.abs(vel[k] - fd).max():.3g}")
if np.abs(vel[-1]).max() == 0:
    fail("the last step does not move")

run("series.msh")
try:
    import meshio
except ImportError:
    sys.exit(0)
m = meshio.read(work / "series.msh")
if m.point_data["mesh_velocity"].shape != (len(m.points), 3):
    fail("series.msh: mesh_velocity is not a vector per node")
if np.abs(m.point_data["displacement"][:, :2] - (m.points[:, :2] - x0[:, :2])).max() > 1e-12 * scale:
    fail("series.msh: displacement is not x − input")
if "quality" not in m.cell_data:
    fail("series.msh: no $ElementData quality")
print("ok")
