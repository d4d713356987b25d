# SPDX-License-Identifier: MIT
"""meshmorph's Python module: meshes in and out, quality, and the errors of bad input."""
import copy
import os
import pathlib
import tempfile
import unittest

import numpy as np

import meshmorph

ROOT = pathlib.Path(__file__).resolve().parents[2]
ANNULUS = ROOT / "examples" / "meshes" / "annulus.msh"
SPHERE_P2 = ROOT / "examples" / "meshes" / "sphere_in_box_p2.msh"
FOLDED = ROOT / "tests" / "data" / "folded"


class MeshTest(unittest.TestCase):
    def setUp(self):
        self.mesh = meshmorph.read_mesh(str(ANNULUS))
        self.tmp = tempfile.TemporaryDirectory()
        self.dir = pathlib.Path(self.tmp.name)

    def tearDown(self):
        self.tmp.cleanup()

    def test_reads_sizes_groups_and_cells(self):
        m = self.mesh
        self.assertEqual((m.dim, m.order, m.n_nodes, m.n_cells), (2, 1, 1265, 2366))
        self.assertEqual(m.points.shape, (1265, 2))
        self.assertEqual([(g["name"], g["dim"]) for g in m.groups], [("outer", 1), ("inner", 1), ("domain", 2)])
        inner = m.group_nodes("inner")
        # The inner circle has radius 0.4 (examples/meshes/annulus.geo).
        np.testing.assert_allclose(np.linalg.norm(m.points[inner], axis=1), 0.4, rtol=1e-12)
        self.assertTrue(np.array_equal(m.group_nodes("2"), inner))  # a group by number
        (block,) = m.cell_blocks
        self.assertEqual((block["type"], block["order"], block["nodes"].shape), ("triangle", 1, (2366, 3)))
        self.assertEqual(m.node_tags.shape, (1265,))

    def test_points_are_read_only_and_round_trip_through_every_format(self):
        m = self.mesh
        moved = m.points * 2.0 + np.array([1.0, -3.0])
        with self.assertRaises(ValueError):  # a read-only view: no edit is lost silently
            m.points[0, 0] = 99.0
        self.assertNotEqual(m.points[0, 0], 99.0)
        m.points = moved
        self.assertTrue(np.array_equal(m.points, moved))
        for name, binary in [("a.msh", False), ("b.msh", True), ("c.vtu", False), ("d.vtu", True), ("e.mesh", False)]:
            with self.subTest(name=name, binary=binary):
                m.write(str(self.dir / name), binary=binary)
                back = meshmorph.read_mesh(str(self.dir / name))
                self.assertTrue(np.array_equal(back.points, moved))
                self.assertTrue(np.array_equal(back.cell_blocks[0]["nodes"], m.cell_blocks[0]["nodes"]))
        self.assertEqual(sorted(os.listdir(self.dir)), ["a.msh", "b.msh", "c.vtu", "d.vtu", "e.mesh"])

    def test_a_high_order_mesh_keeps_its_nodes(self):
        m = meshmorph.read_mesh(str(SPHERE_P2))
        self.assertEqual((m.dim, m.order), (3, 2))
        m.write(str(self.dir / "p2.vtu"))  # VTK's Lagrange ordering on the way, Gmsh's back
        back = meshmorph.read_mesh(str(self.dir / "p2.vtu"))
        self.assertTrue(np.array_equal(back.points, m.points))
        self.assertTrue(np.array_equal(back.cell_blocks[0]["nodes"], m.cell_blocks[0]["nodes"]))

    def test_quality_with_and_without_a_reference(self):
        q = meshmorph.quality(self.mesh)
        self.assertTrue(q["valid"])
        self.assertEqual(q["inverted_elements"], 0)
        self.assertNotIn("min_quality", q)
        self.assertEqual(q["shape_quality"].shape, (2366,))
        self.assertGreater(q["min_shape_quality"], 0.3)
        self.assertLessEqual(q["min_shape_quality"], q["mean_shape_quality"])
        same = meshmorph.quality(self.mesh, self.mesh)
        self.assertAlmostEqual(same["min_quality"], 1.0, places=12)
        # A similarity (rotation, scaling) of the whole mesh distorts nothing.
        turned = self.mesh.copy()
        c, s = np.cos(0.3), np.sin(0.3)
        turned.points = 2.5 * self.mesh.points @ np.array([[c, s], [-s, c]])
        self.assertAlmostEqual(meshmorph.quality(turned, self.mesh)["min_quality"], 1.0, places=12)
        # Folding one node across its neighbours inverts cells.
        folded = self.mesh.copy()
        p = folded.points.copy()
        interior = np.setdiff1d(np.arange(p.shape[0]), np.union1d(folded.group_nodes("inner"), folded.group_nodes("outer")))
        p[interior[0]] = -p[interior[0]]
        folded.points = p
        q = meshmorph.quality(folded, self.mesh)
        self.assertFalse(q["valid"])
        self.assertGreater(q["inverted_elements"], 0)

    def test_elevate(self):
        p2 = meshmorph.elevate(self.mesh, 2)
        self.assertEqual(p2.order, 2)
        self.assertTrue(np.array_equal(p2.points[: self.mesh.n_nodes], self.mesh.points))
        self.assertTrue(meshmorph.quality(p2)["valid"])
        with self.assertRaisesRegex(meshmorph.InputError, "expected an order from 1 to 4, found 5"):
            meshmorph.elevate(self.mesh, 5)


class MeshFromArraysTest(unittest.TestCase):
    def test_the_blocks_of_a_mesh_make_the_same_mesh(self):
        m = meshmorph.read_mesh(str(ANNULUS))
        again = meshmorph.Mesh(m.points, m.cell_blocks, m.facet_blocks, m.groups)
        self.assertEqual((again.dim, again.n_nodes, again.n_cells), (m.dim, m.n_nodes, m.n_cells))
        self.assertEqual(again.groups, m.groups)
        for group in ("inner", "outer", "domain"):
            self.assertTrue(np.array_equal(again.group_nodes(group), m.group_nodes(group)))
        self.assertEqual(meshmorph.quality(again)["min_shape_quality"], meshmorph.quality(m)["min_shape_quality"])
        turn = [{"group": "inner", "rotate": {"center": [0, 0], "degrees": 30}}, {"group": "outer", "fixed": True}]
        a = meshmorph.Morpher(m, turn, threads=1).solve()
        b = meshmorph.Morpher(again, turn, threads=1).solve()
        self.assertTrue(np.array_equal(a["points"], b["points"]))

    def test_a_mesh_by_hand(self):
        # The unit square as two triangles, its bottom edge the group "bottom".
        square = meshmorph.Mesh(np.array([[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]]),
                                [{"type": "triangle", "nodes": [[0, 1, 2], [0, 2, 3]]}],
                                [{"type": "line", "nodes": [[0, 1]], "physical": [7]}],
                                [{"name": "bottom", "dim": 1, "tag": 7}])
        self.assertEqual((square.dim, square.order, square.n_cells), (2, 1, 2))
        self.assertTrue(np.array_equal(square.group_nodes("bottom"), [0, 1]))
        self.assertTrue(meshmorph.quality(square)["valid"])
        with tempfile.TemporaryDirectory() as tmp:
            square.write(tmp + "/square.msh")
            back = meshmorph.read_mesh(tmp + "/square.msh")
        self.assertTrue(np.array_equal(back.points, square.points))
        self.assertTrue(np.array_equal(back.group_nodes("bottom"), [0, 1]))

    def test_2d_points_with_a_zero_z_column(self):
        # meshio and VTK hold 2D points with z = 0.
        points = np.array([[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]])
        tri = [{"type": "triangle", "nodes": [[0, 1, 2]]}]
        m = meshmorph.Mesh(points, tri)
        self.assertEqual(m.dim, 2)
        self.assertTrue(np.array_equal(m.points, points[:, :2]))
        points[2, 2] = 0.5
        with self.assertRaisesRegex(meshmorph.InputError, "Mesh: points: z is not 0 but the cells are 2D"):
            meshmorph.Mesh(points, tri)

    def test_numbers_of_the_wrong_kind_are_not_truncated(self):
        points = np.array([[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]])
        tri = {"type": "triangle", "nodes": [[0, 1, 2]]}
        cases = [
            ([dict(tri, nodes=np.array([[0, 1, 2]]) + 0.7)], [], r"cells\[0\]\.nodes: expected integers"),
            ([dict(tri, nodes=np.array([[True, False, True]]))], [], r"cells\[0\]\.nodes: expected integers"),
            ([dict(tri, physical=[2**33 + 3])], [], r"cells\[0\]\.physical: tag 8589934595 of cell 0 is not in \[0, 2\^31\)"),
            ([dict(tri, physical=[3.9])], [], r"cells\[0\]\.physical: expected integers"),
            ([dict(tri, order="2")], [], r"cells\[0\]\.order: expected an integer"),
            ([dict(tri, type=5)], [], r"cells\[0\]\.type: expected a string, found int"),
            (["triangle"], [], r"cells\[0\]: expected a dict"),
            ([tri], [{"dim": 1}], r'groups\[0\]: needs "dim" and "tag"'),
            ([tri], [{"dim": "1", "tag": 1}], r"groups\[0\]\.dim: expected an integer, found str"),
            ([tri], [{"dim": 7, "tag": 1}], r"groups\[0\]\.dim: 7 is not in \[0, 2\]"),
            ([tri], [{"dim": 1, "tag": 1, "colour": "red"}], r"groups\[0\]\.colour: unknown key"),
            ([tri], [{"dim": 1, "tag": 1, "name": 'a "b"'}], r"groups\[0\]\.name: a group name holds no quote"),
            ([tri], [{"dim": 1, "tag": 1, "name": "a\x01b"}], r"groups\[0\]\.name: the name holds the control byte 0x01 at byte 1"),
            ([tri], [{"dim": 1, "tag": 1, "name": "a"}, {"dim": 1, "tag": 2, "name": "a"}], r'groups\[1\]: group "a" is given twice'),
        ]
        for cells, groups, message in cases:
            with self.subTest(message=message):
                with self.assertRaisesRegex(meshmorph.InputError, message):
                    meshmorph.Mesh(points, cells, [], groups)

    def test_bad_blocks(self):
        points = np.array([[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]])
        cases = [
            ([{"type": "triangle", "nodes": [[0, 1, 2], [0, 2, 7]]}], [], r"Mesh: cells\[0\]\.nodes: node 7 of cell 1 is not in \[0, 4\)"),
            ([{"type": "triangle", "nodes": [[0, 1, 2, 3]]}], [], r"cells\[0\]\.nodes: expected an array of 3 columns"),
            ([{"type": "triangle", "nodes": [[0, 1, 2], [0, 3, 3]]}], [],
             r"cells\[0\]\.nodes: cell 1 lists node 3 twice \(a degenerate cell\)"),
            ([{"type": "pyramid", "nodes": [[0, 1, 2]]}], [], r'cells\[0\]\.type: "pyramid" is not a cell type'),
            ([{"type": "tetrahedron", "nodes": [[0, 1, 2, 3]]}], [], r'cells\[0\]\.type: "tetrahedron" is not a cell type'),
            ([{"type": "triangle", "order": 5, "nodes": [[0, 1, 2]]}], [], r"cells\[0\]\.order: 5 is not an order"),
            ([{"type": "triangle", "nodes": [[0, 1, 2]], "colour": 1}], [], r"cells\[0\]\.colour: unknown key"),
            ([{"type": "triangle", "nodes": [[0, 1, 2]], "physical": [1, 2]}], [], r"physical: expected one tag per cell"),
            ([{"type": "triangle", "nodes": [[0, 1, 2]]}], [{"type": "triangle", "nodes": [[0, 1, 2]]}],
             r'facets\[0\]\.type: "triangle" is not a facet type'),
            ([], [], "Mesh: cells: no cell block"),
            ([{"type": "triangle", "nodes": np.zeros((0, 3), dtype=np.int64)}], [], r"Mesh: cells: no cell \(every block is empty\)"),
        ]
        for cells, facets, message in cases:
            with self.subTest(message=message):
                with self.assertRaisesRegex(meshmorph.InputError, message):
                    meshmorph.Mesh(points, cells, facets)
        with self.assertRaisesRegex(meshmorph.InputError, r"Mesh: points: row 2 is not finite"):
            meshmorph.Mesh(np.array([[0.0, 0], [1, 0], [np.nan, 1]]), [{"type": "triangle", "nodes": [[0, 1, 2]]}])


class MeshErrorTest(unittest.TestCase):
    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory()
        self.dir = pathlib.Path(self.tmp.name)
        self.mesh = meshmorph.read_mesh(str(ANNULUS))

    def tearDown(self):
        self.tmp.cleanup()

    def test_a_missing_file_is_an_os_error(self):
        with self.assertRaises(OSError) as e:
            meshmorph.read_mesh(str(self.dir / "none.msh"))
        self.assertIsInstance(e.exception, meshmorph.IoError)
        self.assertIn("none.msh", str(e.exception))

    def test_a_truncated_file_names_its_line(self):
        lines = ANNULUS.read_text().splitlines(keepends=True)
        cut = self.dir / "cut.msh"
        cut.write_text("".join(lines[: len(lines) // 2]))
        with self.assertRaises(ValueError) as e:
            meshmorph.read_mesh(str(cut))
        self.assertIsInstance(e.exception, meshmorph.InputError)
        self.assertRegex(str(e.exception), r"cut\.msh.*line \d+")

    def test_points_of_the_wrong_shape_or_not_finite(self):
        with self.assertRaisesRegex(meshmorph.InputError, r"Mesh.points: expected an array of shape \(1265, 2\), found \(1265, 3\)"):
            self.mesh.points = np.zeros((1265, 3))
        bad = self.mesh.points.copy()
        bad[7, 1] = np.nan
        with self.assertRaisesRegex(meshmorph.InputError, "Mesh.points: row 7 is not finite"):
            self.mesh.points = bad
        self.assertTrue(np.isfinite(self.mesh.points).all())  # unchanged

    def test_an_unknown_group(self):
        with self.assertRaisesRegex(meshmorph.InputError, 'no physical group "wall"'):
            self.mesh.group_nodes("wall")

    def test_writing_into_a_missing_folder_writes_nothing(self):
        with self.assertRaises(OSError):
            self.mesh.write(str(self.dir / "no" / "out.msh"))
        self.assertEqual(os.listdir(self.dir), [])

    def test_paths_copies_and_mismatches(self):
        m = meshmorph.read_mesh(ANNULUS)  # a pathlib.Path
        m.write(self.dir / "a.vtu")
        self.assertEqual(meshmorph.read_mesh(self.dir / "a.vtu").n_nodes, m.n_nodes)
        with self.assertRaisesRegex(meshmorph.InputError, "binary is not available for Medit"):
            m.write(self.dir / "a.mesh", binary=True)
        c = copy.deepcopy(m)
        c.points = c.points * 2
        self.assertFalse(np.array_equal(c.points, m.points))
        with self.assertRaisesRegex(meshmorph.InputError, "quality: reference: not the same cells and nodes"):
            meshmorph.quality(m, meshmorph.elevate(m, 2))
        quads = meshmorph.read_mesh(str(ROOT / "examples" / "meshes" / "quad_channel.msh"))
        with self.assertRaisesRegex(meshmorph.InputError, "elevate: expected an order from 1 to 3, found 4"):
            meshmorph.elevate(quads, 4)
        with self.assertRaisesRegex(meshmorph.InputError, r"Mesh.points: row 3: coordinate 2e\+150 is beyond"):
            p = m.points.copy()
            p[3, 0] = 2e150
            m.points = p

    def test_an_unknown_log_level(self):
        with self.assertRaisesRegex(meshmorph.InputError, "expected \"quiet\""):
            meshmorph.set_log_level("loud")
        meshmorph.set_log_level("quiet")

class InjectivityTest(unittest.TestCase):
    """A cell listed clockwise among counter-clockwise ones folds the mesh (docs/metrics.md)."""

    def test_quality_calls_a_folded_mesh_invalid(self):
        q = meshmorph.quality(meshmorph.read_mesh(str(FOLDED / "folded_square_untangled.mesh")))
        self.assertEqual((q["valid"], q["inverted_elements"], q["flipped_elements"]), (False, 0, 1))
        self.assertAlmostEqual(q["cell_volume"], 1.0657558622307, places=12)
        self.assertAlmostEqual(q["enclosed_volume"], 1.0, places=12)

    def test_methods_refuse_a_flipped_cell_or_reorient_it(self):
        mesh = meshmorph.read_mesh(str(FOLDED / "folded_square.mesh"))
        with self.assertRaisesRegex(meshmorph.InputError, "1 cell is listed mirrored against its neighbours, first cell 3"):
            meshmorph.untangle(mesh)
        with self.assertRaisesRegex(meshmorph.InputError, "listed mirrored"):
            meshmorph.Untangler(mesh)
        report, untangled = meshmorph.untangle(mesh, reorient=True)
        self.assertTrue(report["valid"])
        self.assertEqual(report["flipped_elements"], 0)
        q = meshmorph.quality(untangled)
        self.assertTrue(q["valid"])
        self.assertAlmostEqual(q["cell_volume"], 1.0, places=12)


if __name__ == "__main__":
    unittest.main()
