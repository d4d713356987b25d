# SPDX-License-Identifier: MIT
"""Mesh.from_meshio and Mesh.to_meshio: meshio's cell blocks in meshio's node orders, and
meshmorph's in Gmsh's (docs/node-ordering.md).

meshio names a cell by its family and node count ("tetra10", "quad16") or, for the VTK
Lagrange cells it reads from VTU files, by VTK's name ("VTK_LAGRANGE_TETRAHEDRON"). Its node
order is its own per name: VTK's classic quadratic cells for the five names its Gmsh reader
and writer reorder, VTK's Lagrange cells for the VTK_LAGRANGE names, and Gmsh's for every
other name (the linear wedge included, meshio's exception to VTK, and every cell of order 3
or more, which meshio passes through unchanged). The permutations are the library's
(io/vtk_ordering.h).
"""
import re

import numpy as np

from . import _meshmorph as _core

# meshio's families (meshio/_common.py) and meshmorph's.
_FAMILIES = {"vertex": "point", "line": "line", "triangle": "triangle", "quad": "quadrilateral",
             "tetra": "tetrahedron", "hexahedron": "hexahedron", "wedge": "prism", "pyramid": "pyramid"}
_MESHIO_FAMILY = {ours: theirs for theirs, ours in _FAMILIES.items()}
# The names meshio's Gmsh reader and writer reorder (meshio/gmsh/common.py): held in the order
# of VTK's classic cell of that VTK type.
_VTK_CLASSIC = {"tetra10": 24, "hexahedron20": 25, "hexahedron27": 29, "wedge15": 26, "pyramid13": 27}
# meshio's names of VTK's Lagrange cells (VTK types 68-74).
_VTK_LAGRANGE = {"VTK_LAGRANGE_CURVE": ("line", 68), "VTK_LAGRANGE_TRIANGLE": ("triangle", 69),
                 "VTK_LAGRANGE_QUADRILATERAL": ("quadrilateral", 70), "VTK_LAGRANGE_TETRAHEDRON": ("tetrahedron", 71),
                 "VTK_LAGRANGE_HEXAHEDRON": ("hexahedron", 72), "VTK_LAGRANGE_WEDGE": ("prism", 73),
                 "VTK_LAGRANGE_PYRAMID": ("pyramid", 74)}
_DIM = {"point": 0, "line": 1, "triangle": 2, "quadrilateral": 2, "tetrahedron": 3, "hexahedron": 3, "prism": 3,
        "pyramid": 3}
_PHYSICAL_KEYS = ("gmsh:physical", "group", "cell_tags")


def _cell_type(name, n_nodes, where):
    """(family, order, incomplete, perm) of meshio's cell type `name` with `n_nodes` nodes a
    cell; perm: meshio_nodes[i] = gmsh_nodes[perm[i]] (None: the same order)."""
    vtk = None
    if name in _VTK_LAGRANGE:
        family, vtk = _VTK_LAGRANGE[name]
    else:
        match = re.fullmatch(r"([a-z]+)(\d*)", name)
        if not match or match[1] not in _FAMILIES:
            raise _core.InputError(f"{where}: meshio cell type \"{name}\" is not one meshmorph reads")
        family = _FAMILIES[match[1]]
        vtk = _VTK_CLASSIC.get(name)
    order, incomplete = _core._cell_order(family, n_nodes)
    if order == 0:
        raise _core.InputError(f"{where}: {n_nodes}-node {family} cells (meshio \"{name}\") are not cells meshmorph "
                               "reads (complete Lagrange cells, and the 8-, 20-, 15- and 13-node serendipity ones)")
    perm = None if vtk is None else _core._vtk_permutation(vtk, family, order)[:n_nodes]
    return family, order, incomplete, perm


def _meshio_name(family, order):
    nodes = _core._cell_nodes(family, order)
    return _MESHIO_FAMILY[family] + ("" if order == 1 else str(nodes))


def _physical(mesh, k, n_cells):
    for key in _PHYSICAL_KEYS:
        if key in mesh.cell_data and k < len(mesh.cell_data[key]):
            tags = np.asarray(mesh.cell_data[key][k])
            if tags.shape == (n_cells,) and tags.dtype.kind in "iu":
                return tags
    return np.zeros(n_cells, dtype=np.int64)


def from_meshio(mesh):
    """The meshmorph.Mesh of a meshio.Mesh: its cells of the highest dimension as cells, the
    others as facets, their physical tags from cell_data "gmsh:physical" (or "group",
    "cell_tags"), the groups from field_data ({name: [tag, dim]}), every node order converted
    from meshio's to Gmsh's; serendipity cells are completed as read_mesh completes them."""
    blocks = []
    for k, block in enumerate(mesh.cells):
        where = f"Mesh.from_meshio: cells[{k}]"
        data = np.asarray(block.data)
        if data.ndim != 2:
            raise _core.InputError(f"{where}: cells of \"{block.type}\" of different node counts (meshmorph reads "
                                   "cells of one order a block)")
        family, order, incomplete, perm = _cell_type(block.type, data.shape[1], where)
        nodes = np.full((data.shape[0], _core._cell_nodes(family, order)), -1, dtype=np.int64)
        nodes[:, np.arange(data.shape[1]) if perm is None else perm] = data
        blocks.append([family, order, incomplete, nodes, _physical(mesh, k, data.shape[0])])
    points = np.asarray(mesh.points, dtype=float)
    if any(b[2] for b in blocks):
        three = np.zeros((len(points), 3))
        three[:, :points.shape[1]] = points[:, :3]
        completed, nodes = _core._complete_cells(three, [(b[0], b[1], b[3]) for b in blocks])
        points = completed if points.shape[1] == 3 else completed[:, :points.shape[1]]
        for b, n in zip(blocks, nodes):
            b[3] = n
    dim = max((_DIM[b[0]] for b in blocks), default=0)
    cells, facets = [], []
    for family, order, _, nodes, physical in blocks:
        (cells if _DIM[family] == dim else facets).append(
            {"type": family, "order": order, "nodes": nodes, "physical": physical})
    groups = []
    for name, value in mesh.field_data.items():
        value = np.asarray(value)
        if value.shape == (2,) and value.dtype.kind in "iu" and 0 <= value[1] <= dim:
            groups.append({"name": name, "tag": int(value[0]), "dim": int(value[1])})
    return _core.Mesh(points, _merged(cells), _merged(facets), groups)


def _merged(blocks):
    """Blocks of one family and order joined, in the order they first come."""
    joined = {}
    for b in blocks:
        key = (b["type"], b["order"])
        if key in joined:
            joined[key]["nodes"] = np.concatenate([joined[key]["nodes"], b["nodes"]])
            joined[key]["physical"] = np.concatenate([joined[key]["physical"], b["physical"]])
        else:
            joined[key] = dict(b)
    return list(joined.values())


def to_meshio(mesh):
    """A meshio.Mesh of `mesh` in meshio's node orders, as meshio.read gives a Gmsh file: points
    (n_nodes, 3), one block per cell type and physical tag (cells, then facets), cell_data
    "gmsh:physical" and "gmsh:geometrical", field_data {name: [tag, dim]}. Needs meshio."""
    import meshio

    points = mesh.points
    if points.shape[1] == 2:
        points = np.column_stack([points, np.zeros(len(points))])
    cells, physical, entity = [], [], []
    for b in mesh.cell_blocks + mesh.facet_blocks:
        name = _meshio_name(b["type"], b["order"])
        _, _, _, perm = _cell_type(name, b["nodes"].shape[1], "Mesh.to_meshio")
        nodes = b["nodes"] if perm is None else b["nodes"][:, perm]
        for tag in np.unique(b["physical"]):
            rows = b["physical"] == tag
            cells.append((name, nodes[rows].astype(np.int64)))
            physical.append(np.full(int(rows.sum()), tag, dtype=np.int64))
            entity.append(np.full(int(rows.sum()), len(entity) + 1, dtype=np.int64))
    field_data = {g["name"] or str(g["tag"]): np.array([g["tag"], g["dim"]]) for g in mesh.groups}
    return meshio.Mesh(points, cells, cell_data={"gmsh:physical": physical, "gmsh:geometrical": entity},
                       field_data=field_data)
