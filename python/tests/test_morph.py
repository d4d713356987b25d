# SPDX-License-Identifier: MIT
"""meshmorph.Morpher: exact affine motions, the same result as `meshmorph morph`, time series,
explicit targets, and the errors of bad input."""
import json
import os
import pathlib
import subprocess
import sys
import tempfile
import threading
import unittest

import numpy as np

import meshmorph

ROOT = pathlib.Path(__file__).resolve().parents[2]
ANNULUS = ROOT / "examples" / "meshes" / "annulus.msh"
SPHERE = ROOT / "examples" / "meshes" / "sphere_in_box.msh"
FOLDED = ROOT / "tests" / "data" / "folded"
ROTATE = [{"group": "inner", "rotate": {"center": [0, 0], "degrees": 60}}, {"group": "outer", "fixed": True}]


def rotation(degrees):
    a = np.radians(degrees)
    return np.array([[np.cos(a), -np.sin(a)], [np.sin(a), np.cos(a)]])


class MorpherTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.annulus = meshmorph.read_mesh(str(ANNULUS))

    def test_affine_motions_of_the_whole_boundary_are_exact(self):
        x = self.annulus.points
        R = rotation(35.0)
        affine = {"rotate": (x @ R.T, [{"group": g, "rotate": {"center": [0, 0], "degrees": 35}} for g in ("inner", "outer")]),
                  "scale": ((x - 0.5) * 1.7 + 0.5, [{"group": g, "scale": {"center": [0.5, 0.5], "factor": 1.7}} for g in ("inner", "outer")]),
                  "translate": (x + [3.0, -1.0], [{"group": g, "translate": [3.0, -1.0]} for g in ("inner", "outer")])}
        for name, (expected, boundary) in affine.items():
            with self.subTest(motion=name):
                r = meshmorph.Morpher(self.annulus, boundary).solve()
                self.assertTrue(r["converged"], r["message"])
                self.assertLess(np.abs(r["points"] - expected).max(), 1e-10)
                self.assertAlmostEqual(r["min_quality"], 1.0, places=9)

    def test_a_3d_translation_of_the_whole_boundary_is_exact(self):
        mesh = meshmorph.read_mesh(str(SPHERE))
        boundary = [{"group": g, "translate": [0.5, 0.25, -2.0]} for g in ("box", "sphere")]
        r = meshmorph.Morpher(mesh, boundary).solve()
        self.assertTrue(r["converged"], r["message"])
        self.assertLess(np.abs(r["points"] - (mesh.points + [0.5, 0.25, -2.0])).max(), 1e-10)

    def test_the_same_mesh_as_the_command_line(self):
        # One thread each: the results are then equal bit for bit.
        with tempfile.TemporaryDirectory() as tmp:
            case = pathlib.Path(tmp) / "case.json"
            case.write_text(json.dumps({"mesh": str(ANNULUS), "boundary": ROTATE, "output": "out.vtu", "report": "r.json"}))
            subprocess.run([os.environ["MESHMORPH_BIN"], "--threads", "1", "--quiet", "morph", str(case)], check=True,
                           stdout=subprocess.DEVNULL)
            cli = meshmorph.read_mesh(str(pathlib.Path(tmp) / "out.vtu"))
            cli_report = json.loads((pathlib.Path(tmp) / "r.json").read_text())
        r = meshmorph.Morpher(self.annulus, ROTATE, threads=1).solve()
        self.assertTrue(np.array_equal(r["points"], cli.points))
        self.assertEqual(r["iterations"], cli_report["iterations"])
        self.assertEqual(r["history"], cli_report["history"])
        for key in ("valid", "inverted_elements", "min_quality", "boundary_error_max", "converged", "message",
                    "guarded_cells", "untangle_passes"):
            self.assertEqual(r[key], cli_report[key], key)

    def test_a_time_series_carries_its_state(self):
        m = meshmorph.Morpher(self.annulus, ROTATE)
        half = m.solve(0.5)
        full = m.solve(1.0)
        self.assertTrue(half["converged"] and full["converged"])
        self.assertEqual({row["step"] for row in half["history"]}, {1})
        self.assertEqual({row["step"] for row in full["history"]}, {2})
        inner = self.annulus.group_nodes("inner")
        x = self.annulus.points
        for r, degrees in ((half, 30.0), (full, 60.0)):
            np.testing.assert_allclose(r["points"][inner], x[inner] @ rotation(degrees).T, atol=1e-8)
            self.assertLess(r["boundary_error_max"], 1e-8)  # against this solve's targets
        self.assertTrue(np.array_equal(m.points, full["points"]))

    def test_explicit_targets_move_the_moving_groups_only(self):
        x = self.annulus.points
        inner = self.annulus.group_nodes("inner")
        # The case decides which nodes move, the targets where they go: the other rows are not read.
        targets = np.full_like(x, 1e6)
        targets[inner] = x[inner] @ rotation(60.0).T
        r = meshmorph.Morpher(self.annulus, ROTATE).solve(targets=targets)
        self.assertTrue(r["converged"], r["message"])
        self.assertLess(r["boundary_error_max"], 1e-8)
        ref = meshmorph.Morpher(self.annulus, ROTATE).solve()
        np.testing.assert_allclose(r["points"], ref["points"], atol=1e-8)
        outer = self.annulus.group_nodes("outer")
        self.assertTrue(np.array_equal(r["points"][outer], x[outer]))

    def test_a_run_that_misses_its_goal_says_so_and_stays_valid(self):
        r = meshmorph.Morpher(self.annulus, ROTATE, options={"max_outer": 1}).solve()
        self.assertFalse(r["converged"])
        self.assertIn("not reached within 1 augmented-Lagrangian iterations", r["message"])
        moved = self.annulus.copy()
        moved.points = r["points"]
        self.assertTrue(meshmorph.quality(moved)["valid"])

    def morph_folder(self, name):
        folder = FOLDED / name
        case = json.loads((folder / "case.json").read_text())
        boundary = [dict(e, displace={"file": str(folder / e["displace"]["file"])}) if "displace" in e else e
                    for e in case["boundary"]]
        mesh = meshmorph.read_mesh(str(folder / case["mesh"]))
        report, moved = meshmorph.morph(mesh, boundary, steps=case.get("steps"), threads=1)
        return mesh, report, moved

    def test_an_untangle_pass_that_leaves_cells_inverted_between_samples_is_not_taken(self):
        # A smooth motion of both boundaries of a P2 square with a square hole: the augmented
        # Lagrangian stalls, and the untangle pass from there ends with cells that pass its
        # samples but not the Bernstein bounds. The stalled, valid iterate is the result.
        _, report, moved = self.morph_folder("untangle_pass")
        self.assertFalse(report["converged"])
        self.assertIn("the untangle pass left", report["message"])
        self.assertTrue(report["valid"])
        self.assertTrue(meshmorph.quality(moved)["valid"])

    def test_a_result_whose_boundary_passes_through_itself_gives_back_the_start(self):
        # Every cell positive at the targets, but the hole's top edge below its bottom edge.
        mesh, report, moved = self.morph_folder("crossing")
        self.assertFalse(report["converged"])
        self.assertIn("boundary passes through itself", report["message"])
        self.assertIn("the mesh returned is the one the last solve started from", report["message"])
        self.assertTrue(report["valid"])
        self.assertTrue(np.array_equal(moved.points, mesh.points))

    def test_a_series_whose_first_step_overlapped_gives_back_the_input(self):
        # Two steps of a smooth motion of both boundaries: the first ends with the boundary
        # through itself, the second stalls and overlaps too; neither is a result.
        mesh, report, moved = self.morph_folder("series_overlap")
        self.assertFalse(report["converged"])
        self.assertIn("the mesh returned is the input", report["message"])
        self.assertTrue(report["valid"])
        self.assertTrue(np.array_equal(moved.points, mesh.points))

    def test_order_elevation_curves_nothing_on_a_rotation_of_everything(self):
        boundary = [{"group": g, "rotate": {"center": [0, 0], "degrees": 90}} for g in ("inner", "outer")]
        m = meshmorph.Morpher(self.annulus, boundary, order=2)
        self.assertEqual(m.mesh.order, 2)
        r = m.solve()
        self.assertTrue(r["converged"], r["message"])
        self.assertLess(np.abs(r["points"] - m.mesh.points @ rotation(90.0).T).max(), 1e-10)


class MorpherThreadTest(unittest.TestCase):
    def test_solves_from_two_threads_take_turns(self):
        annulus = meshmorph.read_mesh(str(ANNULUS))
        m = meshmorph.Morpher(annulus, ROTATE)
        results = {}
        threads = [threading.Thread(target=lambda t=t: results.update({t: m.solve(t)})) for t in (0.5, 1.0)]
        for th in threads:
            th.start()
        for th in threads:
            th.join()
        self.assertEqual(set(results), {0.5, 1.0})
        for r in results.values():
            self.assertTrue(r["converged"], r["message"])
            self.assertTrue(r["valid"])
        self.assertEqual(sorted(r["history"][0]["step"] for r in results.values()), [1, 2])
        last = max(results.values(), key=lambda r: r["history"][0]["step"])
        self.assertTrue(np.array_equal(m.points, last["points"]))

    def test_threads_that_first_touch_numpy_together(self):
        # A fresh interpreter that has not imported NumPy, and solves shorter than its import: the
        # two solves' first arrays deadlocked on NumPy's lookup, and unguarded solves crashed.
        script = f"""
import threading, meshmorph
mesh = meshmorph.read_mesh({str(ROOT / "tests" / "data" / "annulus_coarse.msh")!r})
m = meshmorph.Morpher(mesh, {ROTATE!r}, threads=1)
ts = [threading.Thread(target=m.solve, args=(t,)) for t in (0.5, 1.0)]
for t in ts: t.start()
for t in ts: t.join()
print("both done")
"""
        out = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True, timeout=120)
        self.assertEqual(out.returncode, 0, out.stderr)
        self.assertIn("both done", out.stdout)

    def test_the_mesh_property_is_a_copy(self):
        annulus = meshmorph.read_mesh(str(ANNULUS))
        m = meshmorph.Morpher(annulus, ROTATE, threads=1)
        mesh = m.mesh
        mesh.points = mesh.points * 1.5  # changes the copy only
        self.assertTrue(np.array_equal(m.mesh.points, annulus.points))
        ref = meshmorph.Morpher(annulus, ROTATE, threads=1).solve()
        self.assertTrue(np.array_equal(m.solve()["points"], ref["points"]))


class MorpherErrorTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.annulus = meshmorph.read_mesh(str(ANNULUS))

    def test_bad_cases(self):
        cases = [
            ([{"group": "wall", "fixed": True}], None, r'Morpher: boundary\[0\]\.group: no physical group "wall" in the mesh'),
            ([{"group": "inner", "spin": 3}], None, r"Morpher: boundary\[0\]\.spin: unknown key"),
            ([{"group": "inner", "translate": [1, 2, 3]}], None,
             r"Morpher: boundary\[0\]\.translate: expected 2 numbers for a 2D mesh, found 3"),
            (ROTATE, {"alpha": -1}, r"Morpher: options\.alpha: expected a number in \[0\.0, 100\.0\], found -1"),
            (ROTATE, {"speed": 2}, r"Morpher: options\.speed: unknown option"),
            (ROTATE, {"method": "laplace"}, r'options\.method: the Morpher runs "morph"'),
        ]
        for boundary, options, message in cases:
            with self.subTest(message=message):
                with self.assertRaisesRegex(meshmorph.InputError, message):
                    meshmorph.Morpher(self.annulus, boundary, options=options)

    def test_an_inverted_mesh(self):
        folded = self.annulus.copy()
        p = folded.points.copy()
        interior = np.setdiff1d(np.arange(p.shape[0]), np.union1d(folded.group_nodes("inner"), folded.group_nodes("outer")))
        p[interior[0]] = -p[interior[0]]
        folded.points = p
        with self.assertRaisesRegex(meshmorph.InputError, r"Morpher: the mesh has \d+ inverted elements"):
            meshmorph.Morpher(folded, ROTATE)

    def test_bad_arguments(self):
        with self.assertRaisesRegex(meshmorph.InputError, "Morpher: the boundary, options and level sets must hold finite"):
            meshmorph.Morpher(self.annulus, [{"group": "inner", "translate": [float("nan"), 0]}])
        with self.assertRaisesRegex(meshmorph.InputError, "Morpher: threads: expected 0 .* found -5"):
            meshmorph.Morpher(self.annulus, ROTATE, threads=-5)
        m = meshmorph.Morpher(self.annulus, ROTATE)
        with self.assertRaisesRegex(meshmorph.InputError, "Morpher.solve: give t or targets, not both"):
            m.solve(0.5, targets=self.annulus.points)
        targets = self.annulus.points.copy()
        targets[self.annulus.group_nodes("inner")[0]] = [1e300, 0]
        with self.assertRaisesRegex(meshmorph.InputError, r"targets: row \d+: coordinate 1e\+300 is beyond"):
            m.solve(targets=targets)

    def test_bad_solve_arguments(self):
        m = meshmorph.Morpher(self.annulus, ROTATE)
        with self.assertRaisesRegex(meshmorph.InputError, r"t must be in \[0, 1\]"):
            m.solve(1.5)
        with self.assertRaisesRegex(meshmorph.InputError, r"targets: expected an array of shape \(1265, 2\), found \(4,\)"):
            m.solve(targets=np.zeros(4))
        targets = self.annulus.points.copy()
        targets[3, 0] = np.inf
        with self.assertRaisesRegex(meshmorph.InputError, "targets: row 3 is not finite"):
            m.solve(targets=targets)
        self.assertTrue(np.array_equal(m.points, self.annulus.points))  # nothing ran


if __name__ == "__main__":
    unittest.main()
