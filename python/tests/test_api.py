# SPDX-License-Identifier: MIT
"""The module as Python users expect it: read-only arrays, __repr__, docstrings, standard
exceptions with the command line's messages, groups by number, progress callbacks."""
import errno
import inspect
import pathlib
import tempfile
import unittest

import numpy as np

import meshmorph

ROOT = pathlib.Path(__file__).resolve().parents[2]
ANNULUS = ROOT / "tests" / "data" / "annulus_coarse.msh"
ROTATE = [{"group": "inner", "rotate": {"center": [0, 0], "degrees": 10}}, {"group": "outer", "fixed": True}]


class ApiTest(unittest.TestCase):
    def setUp(self):
        self.mesh = meshmorph.read_mesh(ANNULUS)
        self.tmp = tempfile.TemporaryDirectory()
        self.dir = pathlib.Path(self.tmp.name)

    def tearDown(self):
        self.tmp.cleanup()

    def test_points_are_a_read_only_view_that_follows_the_mesh(self):
        view = self.mesh.points
        with self.assertRaises(ValueError):
            view[0, 0] = 1.0
        moved = view + 1.0
        self.mesh.points = moved
        self.assertTrue(np.array_equal(view, moved))  # the same storage, set in place
        for array in (self.mesh.node_tags, self.mesh.cell_blocks[0]["nodes"], self.mesh.group_nodes("inner"),
                      meshmorph.Morpher(self.mesh, ROTATE).points):
            self.assertFalse(array.flags.writeable)

    def test_repr_names_sizes_cells_and_groups(self):
        self.assertEqual(repr(self.mesh), "<meshmorph.Mesh 2D: 196 nodes, 332 triangle P1; groups outer (1), "
                                          "inner (2), domain (3)>")

    def test_every_public_function_class_and_property_has_a_docstring(self):
        for name in meshmorph.__all__:
            value = getattr(meshmorph, name)
            if callable(value):
                self.assertTrue(inspect.getdoc(value), name)
        for cls in (meshmorph.Mesh, meshmorph.Morpher, meshmorph.Untangler):
            for name, member in vars(cls).items():
                if not name.startswith("_") and (isinstance(member, property) or callable(member)):
                    self.assertTrue(inspect.getdoc(member), f"{cls.__name__}.{name}")

    def test_a_missing_file_is_a_file_not_found_error_with_the_command_lines_message(self):
        missing = self.dir / "none.msh"
        with self.assertRaises(FileNotFoundError) as e:
            meshmorph.read_mesh(missing)
        self.assertEqual((e.exception.errno, e.exception.filename), (errno.ENOENT, str(missing)))
        self.assertEqual(str(e.exception), f"{missing}: cannot open for reading")
        self.assertIsInstance(e.exception, meshmorph.IoError)
        for write in (lambda: self.mesh.write(self.dir / "no" / "x.msh"),
                      lambda: meshmorph.write_mesh(self.mesh, self.dir / "no" / "x.vtu"),
                      lambda: meshmorph.convert(missing, self.dir / "x.vtu")):
            with self.assertRaises(FileNotFoundError):
                write()
        with self.assertRaises(ValueError):  # bad content: InputError, a ValueError
            meshmorph.read_mesh(ROOT / "tests" / "data" / "annulus_coarse.msh").write(self.dir / "x.unknown")

    def test_groups_by_number_or_name(self):
        self.assertTrue(np.array_equal(self.mesh.group_nodes(2), self.mesh.group_nodes("inner")))
        with self.assertRaises(TypeError):
            self.mesh.group_nodes(2.0)
        with self.assertRaisesRegex(ValueError, 'no physical group "7"'):
            self.mesh.group_nodes(7)

    def test_progress_lines_reach_the_callback_and_its_exception_is_raised(self):
        lines = []
        report, _ = meshmorph.morph(self.mesh, ROTATE, threads=1, progress=lines.append)
        self.assertEqual(len([l for l in lines if "AL iteration" in l]), report["iterations"]["outer"])
        solved = meshmorph.Morpher(self.mesh, ROTATE, threads=1).solve(progress=lines.append)
        self.assertTrue(solved["converged"])

        def stop(line):
            raise KeyboardInterrupt

        with self.assertRaises(KeyboardInterrupt):
            meshmorph.morph(self.mesh, ROTATE, threads=1, progress=stop)
        with self.assertRaisesRegex(ValueError, "progress: expected a callable"):
            meshmorph.morph(self.mesh, ROTATE, progress=3)


if __name__ == "__main__":
    unittest.main()
