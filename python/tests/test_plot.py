# SPDX-License-Identifier: MIT
"""meshmorph.plot: PNG and SVG files of 2D and 3D meshes, of the right size and not blank."""
import pathlib
import tempfile
import unittest

import numpy as np

import meshmorph

try:
    import matplotlib.image
    import meshmorph.plot
except ImportError:  # scripts/install-deps installs python3-matplotlib
    matplotlib = None

ROOT = pathlib.Path(__file__).resolve().parents[2]
ANNULUS = ROOT / "tests" / "data" / "annulus_coarse.msh"
TETS = ROOT / "tests" / "data" / "io" / "gmsh_tet4_22a.msh"
ROTATE = [{"group": "inner", "rotate": {"center": [0, 0], "degrees": 30}}, {"group": "outer", "fixed": True}]


@unittest.skipIf(matplotlib is None, "matplotlib is not installed")
class PlotTest(unittest.TestCase):
    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory()
        self.dir = pathlib.Path(self.tmp.name)
        self.annulus = meshmorph.read_mesh(ANNULUS)

    def tearDown(self):
        self.tmp.cleanup()

    def assertPicture(self, path, width, height):
        """A PNG of width × height pixels with more than two colours and no colour on 90% of it."""
        image = matplotlib.image.imread(str(path))
        self.assertEqual(image.shape[:2], (height, width))
        colours, counts = np.unique(image.reshape(-1, image.shape[2]).round(2), axis=0, return_counts=True)
        self.assertGreater(len(colours), 20)
        self.assertLess(counts.max(), 0.9 * counts.sum())

    def test_a_morph_side_by_side(self):
        report, turned = meshmorph.morph(self.annulus, ROTATE, threads=1)
        path = self.dir / "morph.png"
        meshmorph.plot.compare(self.annulus, turned, path, dpi=50)
        self.assertPicture(path, 600, 300)

    def test_fields_of_a_curved_2d_and_a_3d_mesh(self):
        report, turned = meshmorph.morph(self.annulus, ROTATE, threads=1)
        values, _ = meshmorph.plot.cell_field(turned, reference=self.annulus)  # quality against the input
        self.assertAlmostEqual(values.min(), report["min_quality"], places=12)
        path = self.dir / "displacement.png"
        meshmorph.plot.save(turned, path, field="displacement", reference=self.annulus, dpi=40)
        self.assertPicture(path, 240, 240)
        path = self.dir / "p3.png"
        meshmorph.plot.save(meshmorph.elevate(self.annulus, 3), path, field="scaled_jacobian", dpi=40)
        self.assertPicture(path, 240, 240)
        tets = meshmorph.read_mesh(TETS)
        path = self.dir / "tets.png"
        meshmorph.plot.save(tets, path, dpi=40)
        self.assertPicture(path, 240, 240)
        svg = self.dir / "tets.svg"
        meshmorph.plot.save(tets, svg, field=np.arange(tets.n_cells))
        self.assertIn("<svg", svg.read_text())

    def test_bad_fields_are_named(self):
        with self.assertRaisesRegex(ValueError, "plot: field \"quality\" needs the reference mesh"):
            meshmorph.plot.figure(self.annulus, "quality")
        with self.assertRaisesRegex(ValueError, "plot: field: expected one of"):
            meshmorph.plot.figure(self.annulus, "beauty")
        with self.assertRaisesRegex(ValueError, r"one value per cell \(332\)"):
            meshmorph.plot.figure(self.annulus, np.zeros(3))


if __name__ == "__main__":
    unittest.main()
