#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""check_series.py MESHMORPH EXAMPLES WORK: a 10-step morph of the annulus with `dt` and
`output_each_step` writes a VTU series that VTK reads through its .pvd: ten files at the times
k·dt, each with point data `displacement` (from the input: x_k − displacement_k is the same
input for every k) and `mesh_velocity` equal to the finite difference of the positions,
(x_k − x_{k−1})/dt, and cell data `quality` in (0, 1]. The same run with a .cgns and an .exo
output holds its steps in that one file: VTK 9.1's readers (vtkCGNSReader, vtkExodusIIReader)
find ten time steps at k·dt at the VTU steps' positions (Exodus: the input's coordinates plus
the nodal vector displacement_, which the reader adds), with the same fields, and meshmorph
reads each file as its last step; a run that misses its goal writes neither. The same run
with a .msh output carries the same fields as $NodeData / $ElementData (read by meshio).
Skipped (77) without VTK."""
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


def run(output, degrees=40, extra=None, expect=0):
    case = {"mesh": str((examples / "meshes" / "annulus.msh").resolve()),
            "boundary": [{"group": "inner", "rotate": {"center": [0, 0], "degrees": degrees}},
                         {"group": "outer", "fixed": True}],
            "steps": steps, "dt": dt, "output_each_step": True, "output": output, **(extra or {})}
    path = work / (output + ".case.json")
    path.write_text(json.dumps(case))
    r = subprocess.run([mm, "morph", str(path), "--quiet"], capture_output=True, text=True)
    if r.returncode != expect:
        fail(f"morph to {output}: exit {r.returncode}, expected {expect}: {r.stderr}")


def fail(what):
    sys.exit("FAIL: " + what)


def vtu_points(path):
    reader = vtk.vtkXMLUnstructuredGridReader()
    reader.SetFileName(str(path))
    reader.Update()
    return vtk_to_numpy(reader.GetOutput().GetPoints().GetData())


def arrays(data):
    return {data.GetArrayName(i): vtk_to_numpy(data.GetArray(i)) for i in range(data.GetNumberOfArrays())}


def in_file_order(grid):
    """The points and point arrays of an Exodus block in the file's node order (VTK's reader
    lists the nodes as the cells meet them)."""
    order = np.empty(grid.GetNumberOfPoints(), dtype=int)
    order[vtk_to_numpy(grid.GetPointData().GetArray("ImplicitNodeId")) - 1] = np.arange(len(order))
    return vtk_to_numpy(grid.GetPoints().GetData())[order], {n: a[order] for n, a in arrays(grid.GetPointData()).items()}


def check_steps(name, times, x, point, cell, disp, vel, tolerance):
    """x, point and cell per step as the reader gives them (x to `tolerance` · scale); disp and
    vel: the vectors' names."""
    if len(times) != steps or np.abs(np.array(times) - dt * np.arange(1, steps + 1)).max() > 1e-12:
        fail(f"{name}: time steps {times}, expected k·{dt} for k = 1..{steps}")
    for k in range(steps):
        where = f"{name}, step {k + 1}"
        if np.abs(x[k] - reference[k]).max() > tolerance * scale:
            fail(f"{where}: the positions differ from the VTU series' by {np.abs(x[k] - reference[k]).max():.3g}")
        for v in (disp, vel):
            if v not in point[k] or point[k][v].shape != (len(x[k]), 3):
                fail(f"{where}: no point vector {v} (arrays: {list(point[k])})")
        # The file's positions in double precision: the input plus the displacement.
        if np.abs(x0 + point[k][disp] - reference[k]).max() > 1e-12 * scale:
            fail(f"{where}: input + {disp} is not the step's positions")
        fd = (point[k][disp] - (0 if k == 0 else point[k - 1][disp])) / dt
        if np.abs(point[k][vel] - fd).max() > 1e-9 * max(1.0, np.abs(fd).max()):
            fail(f"{where}: {vel} differs from (x_k − x_(k−1))/dt by {np.abs(point[k][vel] - fd).max():.3g}")
        quality = cell[k].get("quality")
        if quality is None or quality.min() <= 0 or quality.max() > 1 + 1e-12:
            fail(f"{where}: no cell quality in (0, 1]")


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

# The same morph in one .exo and one .cgns file: the VTU steps' positions at each step.
reference = x
run("series.exo")
exo = vtk.vtkExodusIIReader()
exo.SetFileName(str(work / "series.exo"))
exo.UpdateInformation()
exo.SetAllArrayStatus(exo.NODAL, 1)
exo.SetAllArrayStatus(exo.ELEM_BLOCK, 1)
exo.SetGenerateImplicitNodeIdArray(1)

x, point, cell = [], [], []
for k in range(exo.GetNumberOfTimeSteps()):
    exo.SetTimeStep(k)
    exo.Update()
    grid = exo.GetOutput().GetBlock(0).GetBlock(0)
    xk, pk = in_file_order(grid)
    x.append(xk)
    point.append(pk)
    cell.append(arrays(grid.GetCellData()))
times = exo.GetOutputInformation(0).Get(vtk.vtkStreamingDemandDrivenPipeline.TIME_STEPS())
# VTK 9.1 names the vector of displacement_x/_y by its prefix, the underscore kept, and gives
# an Exodus file's points in single precision.
check_steps("series.exo", times, x, point, cell, "displacement_", "mesh_velocity_", 1e-6)
exo.ApplyDisplacementsOff()
exo.Update()
if np.abs(in_file_order(exo.GetOutput().GetBlock(0).GetBlock(0))[0] - x0).max() > 1e-6 * scale:
    fail("series.exo: the coordinates are not the input's")

run("series.cgns")
cgns = vtk.vtkCGNSReader()
cgns.SetFileName(str(work / "series.cgns"))
cgns.UpdateInformation()
cgns.EnableAllPointArrays()
cgns.EnableAllCellArrays()
times = cgns.GetOutputInformation(0).Get(vtk.vtkStreamingDemandDrivenPipeline.TIME_STEPS())
x, point, cell = [], [], []
for t in times:
    cgns.UpdateTimeStep(t)
    zone = cgns.GetOutput().GetBlock(0).GetBlock(0)
    x.append(vtk_to_numpy(zone.GetPoints().GetData()).copy())
    point.append(arrays(zone.GetPointData()))
    cell.append(arrays(zone.GetCellData()))
check_steps("series.cgns", times, x, point, cell, "Displacement", "GridVelocity", 1e-12)

# meshmorph reads a series as its last step (Exodus: to rounding).
for name in ("series.exo", "series.cgns"):
    r = subprocess.run([mm, "convert", str(work / name), str(work / (name + ".vtu"))], capture_output=True, text=True)
    if r.returncode != 0:
        fail(f"convert {name}: exit {r.returncode}: {r.stderr}")
    if np.abs(vtu_points(work / (name + ".vtu")) - reference[-1]).max() > 1e-12 * scale:
        fail(f"{name} does not read as its last step")

# A run that misses its goal writes no series file (a mesh only where the goal is reached),
# though an increment was valid, and no step file beside it; its report says why.
# (The Laplacian baseline in three steps of 50°: the first is valid, the second inverts cells.)
run("missed.exo", degrees=150, extra={"steps": 3, "options": {"method": "laplace"}, "report": "missed.json"}, expect=1)
left = sorted(p.name for p in work.glob("missed*"))
if left != ["missed.exo.case.json", "missed.json"]:
    fail(f"a run that missed its goal left {left}")

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
