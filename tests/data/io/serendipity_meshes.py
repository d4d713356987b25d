# SPDX-License-Identifier: MIT
# Writes the incomplete (serendipity) quadratic fixtures with Gmsh 4.8.4 and VTK 9.1 (Debian
# python3-gmsh, python3-vtk9): /usr/bin/python3 serendipity_meshes.py, in this folder.
#  - gmsh_serendipity_{41a,41b,22a,22b}.msh: serendipity_hybrid.geo meshed at order 2 with
#    Mesh.SecondOrderIncomplete (types 9, 11, 16, 17, 18, 19), MSH 4.1/2.2, ASCII/binary.
#  - vtk_serendipity.vtu: the same mesh written by VTK's own writer, as VTK 22, 23, 24, 25,
#    26 and 27 cells, each cell's points found from VTK's parametric coordinates (the wedge's
#    base triangle the other way round, as VTK_WEDGE's); checked here: every volume is
#    positive under vtkCellSizeFilter, and VTK's geometry of each cell is Gmsh's.
#  - gmsh_serendipity_basis.json: Gmsh's basis functions of types 16-19 at points on each of
#    the cells' faces and inside, where the complete cells read from them must have the same
#    geometry.
import json

import gmsh
import numpy as np
import vtk

gmsh.initialize()
gmsh.option.setNumber("General.Terminal", 0)
gmsh.open("serendipity_hybrid.geo")
gmsh.model.mesh.generate(3)
gmsh.option.setNumber("Mesh.SecondOrderIncomplete", 1)
gmsh.model.mesh.setOrder(2)
for name, version, binary in [("41a", 4.1, 0), ("41b", 4.1, 1), ("22a", 2.2, 0), ("22b", 2.2, 1)]:
    gmsh.option.setNumber("Mesh.MshFileVersion", version)
    gmsh.option.setNumber("Mesh.Binary", binary)
    gmsh.write(f"gmsh_serendipity_{name}.msh")

# Gmsh type -> (VTK type, VTK parametric coordinates -> Gmsh's reference coordinates).
vtk_cells = {
    9: (22, vtk.vtkQuadraticTriangle, lambda r, s, t: (r, s, 0)),
    16: (23, vtk.vtkQuadraticQuad, lambda r, s, t: (2 * r - 1, 2 * s - 1, 0)),
    11: (24, vtk.vtkQuadraticTetra, lambda r, s, t: (r, s, t)),
    17: (25, vtk.vtkQuadraticHexahedron, lambda r, s, t: (2 * r - 1, 2 * s - 1, 2 * t - 1)),
    18: (26, vtk.vtkQuadraticWedge, lambda r, s, t: (s, r, 2 * t - 1)),  # VTK_WEDGE's orientation
    # VTK's pyramid has its apex above corner 0 in its parametric space, Gmsh's above the centre.
    19: (27, vtk.vtkQuadraticPyramid, lambda r, s, t: ((2 * r - 1) * (1 - t) if t < 1 else 0,
                                                        (2 * s - 1) * (1 - t) if t < 1 else 0, t)),
}


def vtk_to_gmsh(gmsh_type):
    vtk_type, cls, to_gmsh = vtk_cells[gmsh_type]
    _, dim, _, n, ref, _ = gmsh.model.mesh.getElementProperties(gmsh_type)
    ref = np.array(ref).reshape(n, dim)
    cell = cls()
    pc = cell.GetParametricCoords()
    perm = []
    for i in range(cell.GetNumberOfPoints()):
        p = np.array(to_gmsh(*[pc[3 * i + k] for k in range(3)]))[:dim]
        perm.append(int(np.argmin(np.linalg.norm(ref - p, axis=1))))
        assert np.linalg.norm(ref[perm[-1]] - p) < 1e-12, (gmsh_type, i)
    assert sorted(perm) == list(range(n))
    return vtk_type, perm


# Elements as the MSH files list them: by dimension, entity and type, physical entities only.
elements = []
for dim in range(4):
    for _, tag in gmsh.model.getEntities(dim):
        groups = gmsh.model.getPhysicalGroupsForEntity(dim, tag)
        if len(groups) == 0:
            continue
        types, _, nodes = gmsh.model.mesh.getElements(dim, tag)
        for t, conn in zip(types, nodes):
            elements.append((dim, tag, int(groups[0]), t, np.array(conn, dtype=np.int64).reshape(len(conn) // len(vtk_to_gmsh(t)[1]), -1)))
# The points: the nodes of those elements, by tag.
node_tags, xyz, _ = gmsh.model.mesh.getNodes()
used = np.unique(np.concatenate([e[4].ravel() for e in elements]))
where = {int(t): i for i, t in enumerate(node_tags)}
index = {int(t): i for i, t in enumerate(used)}
coords = np.array(xyz).reshape(-1, 3)[[where[int(t)] for t in used]]
points = vtk.vtkPoints()
points.SetDataTypeToDouble()
for p in coords:
    points.InsertNextPoint(*p)
grid = vtk.vtkUnstructuredGrid()
grid.SetPoints(points)
physical = vtk.vtkIntArray()
physical.SetName("gmsh:physical")
entity = vtk.vtkIntArray()
entity.SetName("gmsh:geometrical")
volume_cells = []
for dim, tag, group, t, conn in elements:
    vtk_type, perm = vtk_to_gmsh(t)
    for c in conn:
        ids = vtk.vtkIdList()
        for k in perm:
            ids.InsertNextId(index[int(c[k])])
        if dim == 3:
            volume_cells.append(grid.GetNumberOfCells())
        grid.InsertNextCell(vtk_type, ids)
        physical.InsertNextValue(group)
        entity.InsertNextValue(tag)
grid.GetCellData().AddArray(physical)
grid.GetCellData().AddArray(entity)
for dim, tag in gmsh.model.getPhysicalGroups():
    named = vtk.vtkIntArray()
    named.SetName(gmsh.model.getPhysicalName(dim, tag))
    named.InsertNextValue(tag)
    named.InsertNextValue(dim)
    grid.GetFieldData().AddArray(named)

sizes = vtk.vtkCellSizeFilter()
sizes.SetInputData(grid)
sizes.Update()
volumes = sizes.GetOutput().GetCellData().GetArray("Volume")
assert min(volumes.GetValue(i) for i in volume_cells) > 0
# VTK's geometry of each cell equals Gmsh's at random points: on the faces for the pyramids
# (VTK's and Gmsh's 13-node pyramids are other spaces inside), everywhere for the others.
rng = np.random.default_rng(35)
worst = 0.0
for i in range(grid.GetNumberOfCells()):
    cell = grid.GetCell(i)
    gmsh_type = next(t for t, v in vtk_cells.items() if v[0] == cell.GetCellType())
    vtk_type, perm = vtk_to_gmsh(gmsh_type)
    ids = [cell.GetPointId(k) for k in range(cell.GetNumberOfPoints())]
    gmsh_nodes = np.zeros((len(ids), 3))
    for k, j in enumerate(perm):
        gmsh_nodes[j] = coords[ids[k]]
    for _ in range(4):
        r = rng.uniform(0, 1, 3)
        if gmsh_type in (9, 11):
            r = r / (1 + r.sum())
        if gmsh_type == 18:
            r[1] *= 1 - r[0]
        if gmsh_type == 19:  # the base, or the triangle on VTK's edge 0-1
            r[1 + _ % 2] = 0
        if gmsh_type in (9, 16):
            r[2] = 0
        weights = [0.0] * len(ids)
        x = [0.0] * 3
        cell.EvaluateLocation(vtk.mutable(0), list(r), x, weights)
        _, f, _ = gmsh.model.mesh.getBasisFunctions(gmsh_type, list(vtk_cells[gmsh_type][2](*r)), "Lagrange")
        worst = max(worst, np.abs(np.array(f) @ gmsh_nodes - np.array(x)).max())
assert worst < 1e-13, worst
print("VTK's and Gmsh's geometry agree to", worst)

writer = vtk.vtkXMLUnstructuredGridWriter()
writer.SetFileName("vtk_serendipity.vtu")
writer.SetInputData(grid)
writer.SetDataModeToAppended()
writer.EncodeAppendedDataOff()
writer.SetCompressorTypeToNone()
writer.Write()

# Points on every face of each incomplete type's reference cell (Gmsh's coordinates).
faces = {
    16: [lambda a, b: (2 * a - 1, 2 * b - 1, 0)],
    17: [(lambda k, s: lambda a, b: tuple(np.insert([2 * a - 1, 2 * b - 1], k, s)))(k, s)
         for k in range(3) for s in (-1, 1)],
    18: [lambda a, b: (a * (1 - b), b, -1), lambda a, b: (a * (1 - b), b, 1),
         lambda a, b: (a, 0, 2 * b - 1), lambda a, b: (0, a, 2 * b - 1), lambda a, b: (1 - a, a, 2 * b - 1)],
    19: [lambda a, b: (2 * a - 1, 2 * b - 1, 0),
         lambda a, b: ((2 * a - 1) * (1 - b), -(1 - b), b), lambda a, b: (1 - b, (2 * a - 1) * (1 - b), b),
         lambda a, b: ((2 * a - 1) * (1 - b), 1 - b, b), lambda a, b: (-(1 - b), (2 * a - 1) * (1 - b), b)],
}
inside = {16: lambda a, b, c: (2 * a - 1, 2 * b - 1, 0), 17: lambda a, b, c: (2 * a - 1, 2 * b - 1, 2 * c - 1),
          18: lambda a, b, c: (a * (1 - b), b, 2 * c - 1),
          19: lambda a, b, c: ((2 * a - 1) * (1 - c), (2 * b - 1) * (1 - c), c)}
table = {"_about": "Gmsh 4.8.4's Lagrange basis functions (gmsh.model.mesh.getBasisFunctions) of the "
                   "incomplete types 16 (QUA_8), 17 (HEX_20), 18 (PRI_15) and 19 (PYR_13) at 3 points "
                   "on each face of the reference cell and at 4 points inside (Gmsh's coordinates, Gmsh's "
                   "node order); written by serendipity_meshes.py."}
for t, fs in faces.items():
    pts = [f(*rng.uniform(0.05, 0.95, 2)) for f in fs for _ in range(3)]
    pts = [[float(v) for v in p] for p in pts]
    _, values, _ = gmsh.model.mesh.getBasisFunctions(t, [v for p in pts for v in p], "Lagrange")
    n = len(values) // len(pts)
    table[str(t)] = {"points": pts, "values": [list(values[i * n:(i + 1) * n]) for i in range(len(pts))]}
    pts = [inside[t](*rng.uniform(0.05, 0.95, 3)) for _ in range(4)]
    pts = [[float(v) for v in p] for p in pts]
    _, values, _ = gmsh.model.mesh.getBasisFunctions(t, [v for p in pts for v in p], "Lagrange")
    table[str(t)]["inside"] = {"points": pts, "values": [list(values[i * n:(i + 1) * n]) for i in range(len(pts))]}
with open("gmsh_serendipity_basis.json", "w") as f:
    json.dump(table, f, indent=0)
    f.write("\n")
gmsh.finalize()
