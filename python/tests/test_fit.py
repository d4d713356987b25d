# SPDX-License-Identifier: MIT
"""meshmorph.fit: the command line's fit bit for bit, a trim that returns another mesh, and the
errors of bad level sets."""
import json
import os
import pathlib
import subprocess
import tempfile
import unittest

import numpy as np

import meshmorph

ROOT = pathlib.Path(__file__).resolve().parents[2]
CHANNEL = ROOT / "examples" / "meshes" / "quad_channel.msh"
CIRCLE = {"sphere": {"center": [1, 0.4], "radius": 0.25}}
SLIDE = [{"group": "bottom", "slide": True}]


class FitTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.channel = meshmorph.read_mesh(str(CHANNEL))

    def test_the_same_mesh_as_the_command_line(self):
        options = {"eps_sigma": 1e-8}
        report, fitted = meshmorph.fit(self.channel, interface=CIRCLE, boundary=SLIDE, options=options, order=2, threads=1)
        self.assertTrue(report["converged"], report["message"])
        self.assertLessEqual(report["fit_error_max"], 1e-8)
        self.assertEqual(report["cells_with_two_interface_facets"], 0)
        self.assertEqual(fitted.order, 2)
        self.assertTrue(meshmorph.quality(fitted)["valid"])
        with tempfile.TemporaryDirectory() as tmp:
            case = pathlib.Path(tmp) / "case.json"
            case.write_text(json.dumps({"mesh": str(CHANNEL), "order": 2, "boundary": SLIDE, "interface": CIRCLE,
                                        "options": options, "output": "out.vtu", "report": "r.json"}))
            subprocess.run([os.environ["MESHMORPH_BIN"], "--threads", "1", "--quiet", "fit", str(case)], check=True,
                           stdout=subprocess.DEVNULL)
            cli = meshmorph.read_mesh(str(pathlib.Path(tmp) / "out.vtu"))
            cli_report = json.loads((pathlib.Path(tmp) / "r.json").read_text())
        self.assertTrue(np.array_equal(fitted.points, cli.points))
        self.assertTrue(np.array_equal(fitted.cell_blocks[0]["nodes"], cli.cell_blocks[0]["nodes"]))
        for key in ("iterations", "history", "fit_error_max", "fitted_nodes", "split_cells", "message"):
            self.assertEqual(report[key], cli_report[key], key)

    def test_a_trim_returns_the_cells_inside(self):
        report, fitted = meshmorph.fit(self.channel, trim={"sphere": {"center": [1, 0.5], "radius": 0.45}},
                                       options={"eps_sigma": 1e-8})
        self.assertTrue(report["converged"], report["message"])
        self.assertLess(fitted.n_cells, self.channel.n_cells)
        self.assertLessEqual(report["fit_error_max"], 1e-8)
        self.assertTrue(meshmorph.quality(fitted)["valid"])

    def test_bad_level_sets(self):
        cases = [
            ({"interface": {"sphere": {"center": [10, 10], "radius": 0.1}}},
             "fit: interface: the level set has no zero crossing in the mesh"),
            ({"interface": {"expr": "y - 0.5 - sqrt(x - 1)"}}, "fit: interface: the level set is not a number at node"),
            ({"boundary": SLIDE}, 'fit: nothing to fit: give "interface", "trim" or a boundary entry with "project"'),
            ({"interface": CIRCLE, "options": {"metric": "mu303"}}, "fit: options.metric: mu303 is a 3D metric"),
            ({"interface": {"sphere": {"center": [1, 0.5]}}}, r"fit: interface\.sphere: missing key \"radius\""),
        ]
        for kwargs, message in cases:
            with self.subTest(message=message):
                with self.assertRaisesRegex(meshmorph.InputError, message):
                    meshmorph.fit(self.channel, **kwargs)


if __name__ == "__main__":
    unittest.main()
