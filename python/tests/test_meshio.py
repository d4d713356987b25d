# SPDX-License-Identifier: MIT
"""Mesh.from_meshio and Mesh.to_meshio: meshio's node orders converted for every cell meshmorph
reads, and Mesh(...) refusing arrays in VTK's order."""
import pathlib
import tempfile
import unittest
import warnings

import numpy as np

import meshmorph

try:
    import meshio
except ImportError:  # scripts/install-deps installs python3-meshio
    meshio = None

ROOT = pathlib.Path(__file__).resolve().parents[2]
DATA = ROOT / "tests" / "data"
MESHES = ROOT / "examples" / "meshes"


def hexahedra(n=2):
    """n × n × n unit hexahedra in Gmsh's corner order, the boundary's quadrilaterals tagged 2."""
    k = n + 1
    grid = np.stack(np.meshgrid(*[np.arange(k)] * 3, indexing="ij"), -1).reshape(-1, 3).astype(float)
    at = lambda i, j, l: (i * k + j) * k + l  # noqa: E731
    cells = [[at(i, j, l), at(i + 1, j, l), at(i + 1, j + 1, l), at(i, j + 1, l),
              at(i, j, l + 1), at(i + 1, j, l + 1), at(i + 1, j + 1, l + 1), at(i, j + 1, l + 1)]
             for i in range(n) for j in range(n) for l in range(n)]
    bottom = [[at(i, j, 0), at(i, j + 1, 0), at(i + 1, j + 1, 0), at(i + 1, j, 0)] for i in range(n) for j in range(n)]
    return meshmorph.Mesh(grid, [{"type": "hexahedron", "nodes": np.array(cells), "physical": np.ones(len(cells), int)}],
                          [{"type": "quadrilateral", "nodes": np.array(bottom), "physical": np.full(len(bottom), 2)}],
                          [{"name": "solid", "dim": 3, "tag": 1}, {"name": "bottom", "dim": 2, "tag": 2}])


def read_with_meshio(path):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # meshio warns of what it leaves out of a MSH 4.1 file
        return meshio.read(str(path))


@unittest.skipIf(meshio is None, "meshio is not installed")
class MeshioTest(unittest.TestCase):
    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory()
        self.dir = pathlib.Path(self.tmp.name)

    def tearDown(self):
        self.tmp.cleanup()

    def assertSameMesh(self, a, b, ordered=True):
        """The same points, cells (node for node) and groups; with ordered=False the cells of a
        block may come in another order (to_meshio's blocks are one a physical tag)."""
        self.assertEqual((a.dim, a.order, a.n_nodes, a.n_cells), (b.dim, b.order, b.n_nodes, b.n_cells))
        np.testing.assert_array_equal(a.points, b.points)
        rows = lambda c: np.column_stack([c["physical"], c["nodes"]])  # noqa: E731
        for blocks in ("cell_blocks", "facet_blocks"):
            x, y = getattr(a, blocks), getattr(b, blocks)
            self.assertEqual([(c["type"], c["order"]) for c in x], [(c["type"], c["order"]) for c in y])
            for c, d in zip(x, y):
                if ordered:
                    np.testing.assert_array_equal(rows(c), rows(d))
                else:
                    self.assertEqual(sorted(map(tuple, rows(c))), sorted(map(tuple, rows(d))))
        self.assertEqual(sorted((g["name"], g["dim"], g["tag"]) for g in a.groups),
                         sorted((g["name"], g["dim"], g["tag"]) for g in b.groups))

    def meshes(self):
        """Gmsh's files, and ours of P1-P3 triangles, quadrilaterals, tetrahedra, hexahedra and
        P1-P2 prisms and pyramids."""
        yield MESHES / "sphere_in_box_p2.msh"
        yield DATA / "io" / "gmsh_tet20_41b.msh"
        for mesh, orders in ((DATA / "annulus_coarse.msh", (1, 2, 3)), (MESHES / "quad_channel.msh", (1, 2, 3)),
                             (DATA / "io" / "gmsh_tet4_22a.msh", (1, 2, 3)), (hexahedra(), (1, 2, 3)),
                             (DATA / "hybrid_layer.msh", (1, 2))):
            m = mesh if isinstance(mesh, meshmorph.Mesh) else meshmorph.read_mesh(mesh)
            for p in orders:
                path = self.dir / f"{m.cell_blocks[0]['type']}_{len(m.cell_blocks)}_p{p}.msh"
                meshmorph.elevate(m, p).write(path)
                yield path

    def test_from_meshio_of_a_gmsh_file_is_read_mesh(self):
        for path in self.meshes():
            with self.subTest(path=path.name):
                m = meshmorph.Mesh.from_meshio(read_with_meshio(path))
                self.assertSameMesh(m, meshmorph.read_mesh(path))
                self.assertEqual(meshmorph.quality(m)["inverted_elements"], 0)

    def test_to_meshio_is_what_meshio_reads(self):
        for path in self.meshes():
            with self.subTest(path=path.name):
                ours = meshmorph.read_mesh(path).to_meshio()
                theirs = read_with_meshio(path)
                self.assertEqual(sorted({c.type for c in ours.cells}), sorted({c.type for c in theirs.cells if len(c.data)}))
                self.assertSameMesh(meshmorph.Mesh.from_meshio(ours), meshmorph.read_mesh(path), ordered=False)

    def test_to_meshio_written_by_meshio_reads_back(self):
        for path in self.meshes():
            mesh = meshmorph.read_mesh(path)
            # meshio's VTU writer knows no cell of order 3 or more and no 14-node pyramid (KeyError), and
            # writes an 18-node prism as VTK's in Gmsh's order: MSH only for those.
            vtu = mesh.order == 1 or all(b["type"] in ("triangle", "quadrilateral", "tetrahedron", "hexahedron")
                                         for b in mesh.cell_blocks) and mesh.order == 2
            for suffix in (".msh", ".vtu") if vtu else (".msh",):
                with self.subTest(path=path.name, suffix=suffix):
                    out = self.dir / ("meshio" + suffix)
                    with warnings.catch_warnings():
                        warnings.simplefilter("ignore")
                        meshio.write(str(out), mesh.to_meshio(), **({"file_format": "gmsh22", "binary": False}
                                                                    if suffix == ".msh" else {}))
                    back = meshmorph.read_mesh(out)
                    np.testing.assert_array_equal(back.points, mesh.points)
                    for a, b in zip(back.cell_blocks, mesh.cell_blocks):
                        self.assertEqual((a["type"], a["order"]), (b["type"], b["order"]))
                        self.assertEqual(sorted(map(tuple, a["nodes"])), sorted(map(tuple, b["nodes"])))
                    self.assertEqual(meshmorph.quality(back)["inverted_elements"], 0)

    def test_serendipity_cells_are_completed_as_read_mesh_completes_them(self):
        quads = meshmorph.elevate(meshmorph.read_mesh(MESHES / "quad_channel.msh"), 2)
        m = quads.to_meshio()
        m.cells = [meshio.CellBlock("quad8", c.data[:, :8]) if c.type == "quad9" else c for c in m.cells]
        used = np.unique(np.concatenate([c.data.ravel() for c in m.cells]))  # all but the cell centres
        number = np.full(len(m.points), -1)
        number[used] = np.arange(len(used))
        m.points = m.points[used]
        m.cells = [meshio.CellBlock(c.type, number[c.data]) for c in m.cells]
        serendipity = meshmorph.Mesh.from_meshio(m)
        self.assertEqual((serendipity.n_nodes, serendipity.order), (quads.n_nodes, 2))
        # The same points, the centres completed last.
        np.testing.assert_allclose(np.sort(serendipity.points, axis=0), np.sort(quads.points, axis=0), atol=1e-14)
        self.assertEqual(meshmorph.quality(serendipity)["inverted_elements"], 0)

    def test_vtk_order_given_to_mesh_is_refused_naming_the_cause(self):
        for mesh in (meshmorph.elevate(meshmorph.read_mesh(DATA / "io" / "gmsh_tet4_22a.msh"), 2),
                     meshmorph.elevate(hexahedra(), 2)):
            m = mesh.to_meshio()
            (block,) = [c for c in m.cells if c.type in ("tetra10", "hexahedron27")]
            family = mesh.cell_blocks[0]["type"]
            with self.subTest(family=family):
                with self.assertRaisesRegex(meshmorph.InputError, r"cells are inverted.*VTK.*from_meshio"):
                    meshmorph.Mesh(m.points, [{"type": family, "order": 2, "nodes": block.data}])
                self.assertEqual(meshmorph.Mesh.from_meshio(m).n_cells, mesh.n_cells)

    def test_a_cell_meshmorph_does_not_read_is_named(self):
        m = meshio.Mesh(np.zeros((4, 3)), [("polygon", np.array([[0, 1, 2, 3]]))])
        with self.assertRaisesRegex(meshmorph.InputError, r"cells\[0\]: meshio cell type \"polygon\""):
            meshmorph.Mesh.from_meshio(m)


if __name__ == "__main__":
    unittest.main()
