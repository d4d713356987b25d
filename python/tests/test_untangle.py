# SPDX-License-Identifier: MIT
"""meshmorph.Untangler: a tangled mesh made valid as by `meshmorph untangle`, a boundary motion
followed, an exact scaling, and the errors of bad options."""
import json
import os
import pathlib
import subprocess
import tempfile
import unittest

import numpy as np

import meshmorph

ROOT = pathlib.Path(__file__).resolve().parents[2]
TANGLED = ROOT / "tests" / "data" / "tangled_quads.msh"
ANNULUS = ROOT / "examples" / "meshes" / "annulus.msh"


class UntanglerTest(unittest.TestCase):
    def test_a_tangled_mesh_as_the_command_line_untangles_it(self):
        tangled = meshmorph.read_mesh(str(TANGLED))
        self.assertEqual(meshmorph.quality(tangled)["inverted_elements"], 3)
        r = meshmorph.Untangler(tangled, threads=1).solve()
        self.assertTrue(r["converged"], r["message"])
        self.assertTrue(r["valid"])
        self.assertEqual(r["initial_inverted_elements"], 3)
        self.assertEqual(r["reference"], "regular")
        with tempfile.TemporaryDirectory() as tmp:
            out, report = pathlib.Path(tmp) / "out.vtu", pathlib.Path(tmp) / "r.json"
            subprocess.run([os.environ["MESHMORPH_BIN"], "--threads", "1", "--quiet", "untangle", str(TANGLED), "-o",
                            str(out), "--report", str(report)], check=True, stdout=subprocess.DEVNULL)
            cli = meshmorph.read_mesh(str(out))
            cli_report = json.loads(report.read_text())
        self.assertTrue(np.array_equal(r["points"], cli.points))
        for key in ("iterations", "history", "message", "min_shape_quality", "initial_inverted_elements", "predictor",
                    "reference"):
            self.assertEqual(r[key], cli_report[key], key)
        # Its boundary stays where it was.
        moved = np.abs(r["points"] - tangled.points).max(axis=1) > 0
        for g in tangled.groups:
            if g["dim"] == 1:
                self.assertFalse(moved[tangled.group_nodes(str(g["tag"]))].any())

    def test_a_boundary_motion_and_an_exact_scaling(self):
        annulus = meshmorph.read_mesh(str(ANNULUS))
        x = annulus.points
        turn = [{"group": "inner", "rotate": {"center": [0, 0], "degrees": 40}}, {"group": "outer", "fixed": True}]
        r = meshmorph.Untangler(annulus, turn).solve()
        self.assertTrue(r["converged"], r["message"])
        self.assertEqual(r["reference"], "input")
        self.assertEqual(r["boundary_error_max"], 0.0)  # prescribed nodes are placed, not penalized
        # The predictor's mesh is the exact answer to a scaling of the whole boundary.
        grow = [{"group": g, "scale": {"center": [0, 0], "factor": 1.5}} for g in ("inner", "outer")]
        r = meshmorph.Untangler(annulus, grow).solve()
        self.assertTrue(r["converged"], r["message"])
        self.assertLess(np.abs(r["points"] - 1.5 * x).max(), 1e-12)

    def test_bad_options(self):
        tangled = meshmorph.read_mesh(str(TANGLED))
        with self.assertRaisesRegex(meshmorph.InputError,
                                    r'Untangler: options\.reference: "input" needs a valid input mesh, and 3 cells'):
            meshmorph.Untangler(tangled, options={"reference": "input"})
        with self.assertRaisesRegex(meshmorph.InputError, r"Untangler: options\.speed: unknown option"):
            meshmorph.Untangler(tangled, options={"speed": 1})
        with self.assertRaisesRegex(meshmorph.InputError, r"Untangler\.solve: t must be in \[0, 1\]"):
            meshmorph.Untangler(tangled).solve(-0.5)


if __name__ == "__main__":
    unittest.main()
