# SPDX-License-Identifier: MIT
"""One case runner per method: the Python functions and the command line give the same report
and the same mesh for the same case (one thread each, so bit for bit)."""
import json
import os
import pathlib
import subprocess
import tempfile
import unittest

import numpy as np

import meshmorph

ROOT = pathlib.Path(__file__).resolve().parents[2]
EXAMPLES = ROOT / "examples"
# Members that differ between two runs of one case: when and where, not what.
RUN_MEMBERS = ("seconds", "timings", "peak_memory_mb", "case")


def example_case(name, **changes):
    """An example's case with absolute paths, its output and report left out."""
    folder = EXAMPLES / name
    case = json.loads((folder / "case.json").read_text())
    case["mesh"] = str((folder / case["mesh"]).resolve())
    for entry in case.get("boundary", []):
        if "displace" in entry:
            entry["displace"]["file"] = str(folder / entry["displace"]["file"])
    for key in ("output", "report"):
        case.pop(key, None)
    case.update(changes)
    return case


def command_line(command, case, extra=()):
    """`meshmorph COMMAND case.json` on one thread: its report and output mesh."""
    with tempfile.TemporaryDirectory() as tmp:
        path = pathlib.Path(tmp) / "case.json"
        path.write_text(json.dumps(dict(case, output="out.vtu", report="r.json")))
        subprocess.run([os.environ["MESHMORPH_BIN"], "--threads", "1", "--quiet", command, str(path), *extra], check=True,
                       stdout=subprocess.DEVNULL)
        return json.loads((pathlib.Path(tmp) / "r.json").read_text()), meshmorph.read_mesh(str(pathlib.Path(tmp) / "out.vtu"))


class RunnerTest(unittest.TestCase):
    def check_same(self, command, function, case):
        cli_report, cli_mesh = command_line(command, case)
        mesh = meshmorph.read_mesh(case["mesh"])
        keys = {k: v for k, v in case.items() if k != "mesh"}
        report, moved = function(mesh, threads=1, **keys)
        self.assertTrue(report["converged"], report["message"])
        for r in (report, cli_report):
            for key in RUN_MEMBERS:
                r.pop(key)
        self.assertEqual(report, cli_report)
        self.assertEqual(list(report), list(cli_report))  # the same members in the same order
        self.assertTrue(np.array_equal(moved.points, cli_mesh.points))

    def test_morph(self):
        self.check_same("morph", meshmorph.morph, example_case("01_rotate_annulus"))

    def test_morph_baseline_in_steps(self):
        case = example_case("01_rotate_annulus", steps=2, options={"method": "laplace"})
        case["boundary"][0]["rotate"]["degrees"] = 10
        self.check_same("morph", meshmorph.morph, case)

    def test_untangle(self):
        self.check_same("untangle", meshmorph.untangle, example_case("05_untangle_squeezed_channel"))

    def test_fit(self):
        self.check_same("fit", meshmorph.fit, example_case("04_fit_channel_interface"))

    def test_deform(self):
        self.check_same("deform", meshmorph.deform, example_case("06_deform_obstacle", steps=2))

    def test_optimize(self):
        case = {"mesh": str(EXAMPLES / "meshes" / "annulus.msh"), "options": {"boundary": "slide"}}
        self.check_same("optimize", meshmorph.optimize, case)


class QualityTest(unittest.TestCase):
    def test_the_measures_of_the_command_line(self):
        source = EXAMPLES / "meshes" / "sphere_in_box_p2.msh"
        with tempfile.TemporaryDirectory() as tmp:
            path = pathlib.Path(tmp) / "q.json"
            subprocess.run([os.environ["MESHMORPH_BIN"], "--threads", "1", "quality", str(source), "--json", str(path)],
                           check=True, stdout=subprocess.DEVNULL)
            cli = json.loads(path.read_text())
        q = meshmorph.quality(meshmorph.read_mesh(str(source)))
        for key in ("inverted_elements", "valid", "min_shape_quality", "mean_shape_quality", "min_scaled_jacobian"):
            self.assertEqual(q[key], cli[key], key)
        self.assertEqual(q["cells"], cli["elements"])

    def test_the_minima_per_cell_type_of_the_command_line(self):
        source = ROOT / "tests" / "data" / "hybrid_layer.msh"
        with tempfile.TemporaryDirectory() as tmp:
            path = pathlib.Path(tmp) / "q.json"
            subprocess.run([os.environ["MESHMORPH_BIN"], "--threads", "1", "quality", str(source), "--json", str(path)],
                           check=True, stdout=subprocess.DEVNULL)
            cli = json.loads(path.read_text())["cell_types"]
        mesh = meshmorph.read_mesh(str(source))
        q = meshmorph.quality(mesh)["cell_types"]
        self.assertEqual(list(q), ["tetrahedron", "hexahedron", "prism", "pyramid"])
        self.assertEqual(list(q), list(cli))
        for name, minima in q.items():
            self.assertIsNone(cli[name].pop("min_quality"))
            self.assertEqual(minima, cli[name], name)
        self.assertAlmostEqual(meshmorph.quality(mesh, mesh)["cell_types"]["prism"]["min_quality"], 1.0, places=12)


class ConvertTest(unittest.TestCase):
    def test_the_same_file_as_the_command_line(self):
        source = EXAMPLES / "meshes" / "annulus.msh"
        with tempfile.TemporaryDirectory() as tmp:
            ours, theirs = pathlib.Path(tmp) / "py.msh", pathlib.Path(tmp) / "cli.msh"
            mesh = meshmorph.convert(source, ours, order=2, binary=True)
            subprocess.run([os.environ["MESHMORPH_BIN"], "convert", str(source), str(theirs), "--order", "2", "--binary"],
                           check=True, stdout=subprocess.DEVNULL)
            self.assertEqual(ours.read_bytes(), theirs.read_bytes())
            self.assertEqual(mesh.order, 2)
            with self.assertRaisesRegex(meshmorph.InputError, r"--order 1 is below the mesh's order 2"):
                meshmorph.convert(ours, pathlib.Path(tmp) / "low.vtu", order=1)
            with self.assertRaisesRegex(meshmorph.InputError, r'unknown output format "\.txt"'):
                meshmorph.convert(source, pathlib.Path(tmp) / "out.txt")
            self.assertFalse((pathlib.Path(tmp) / "low.vtu").exists())


if __name__ == "__main__":
    unittest.main()
