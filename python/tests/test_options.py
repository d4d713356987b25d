# SPDX-License-Identifier: MIT
"""The methods' keyword options: their defaults are the library's (passing every default gives
the run that passing none gives), they join `options`, and bad values get the command line's
message."""
import inspect
import pathlib
import unittest

import meshmorph

ROOT = pathlib.Path(__file__).resolve().parents[2]
ANNULUS = ROOT / "tests" / "data" / "annulus_coarse.msh"
TANGLED = ROOT / "tests" / "data" / "tangled_quads.msh"
ROTATE = [{"group": "inner", "rotate": {"center": [0, 0], "degrees": 10}}, {"group": "outer", "fixed": True}]
# Report members that differ from run to run.
CLOCKS = ("seconds", "timings", "peak_memory_mb")


def defaults(function):
    """The keyword options of `function` with their defaults, None (the method's choice) left out."""
    return {p.name: p.default for p in inspect.signature(function).parameters.values()
            if p.kind == p.KEYWORD_ONLY and p.default is not None}


def same_run(report):
    return {k: v for k, v in report.items() if k not in CLOCKS}


class OptionsTest(unittest.TestCase):
    def setUp(self):
        self.annulus = meshmorph.read_mesh(ANNULUS)

    def test_every_default_is_the_librarys(self):
        runs = [(meshmorph.morph, (self.annulus, ROTATE)),
                (meshmorph.untangle, (meshmorph.read_mesh(TANGLED),)),
                (meshmorph.fit, (self.annulus, {"sphere": {"center": [0, 0], "radius": 0.6}})),
                (meshmorph.deform, (self.annulus, [{"group": "inner", "translate": [0.02, 0]},
                                                   {"group": "outer", "fixed": True}])),
                (meshmorph.optimize, (self.annulus,))]
        for function, args in runs:
            with self.subTest(method=function.__name__):
                given = defaults(function)
                self.assertGreater(len(given), 8)
                plain, _ = function(*args, threads=1)
                explicit, _ = function(*args, threads=1, **given)
                self.assertEqual(same_run(explicit), same_run(plain))

    def test_the_morpher_takes_them_too(self):
        given = defaults(meshmorph.Morpher)
        self.assertNotIn("method", given)
        plain = meshmorph.Morpher(self.annulus, ROTATE, threads=1).solve()
        explicit = meshmorph.Morpher(self.annulus, ROTATE, threads=1, **given).solve()
        self.assertEqual(same_run({k: v for k, v in explicit.items() if k != "points"}),
                         same_run({k: v for k, v in plain.items() if k != "points"}))
        self.assertTrue((explicit["points"] == plain["points"]).all())

    def test_keywords_join_the_options(self):
        a, _ = meshmorph.morph(self.annulus, ROTATE, threads=1, max_outer=1)
        b, _ = meshmorph.morph(self.annulus, ROTATE, options={"max_outer": 1}, threads=1)
        self.assertEqual(same_run(a), same_run(b))
        self.assertEqual(a["iterations"]["outer"], 1)
        report, _ = meshmorph.optimize(self.annulus, boundary_mode="slide", max_newton=2)
        self.assertLessEqual(report["iterations"]["newton"], 2)

    def test_bad_values_get_the_command_lines_message(self):
        with self.assertRaisesRegex(ValueError, r"morph: options\.alpha: .*100"):
            meshmorph.morph(self.annulus, ROTATE, alpha=1000.0)
        with self.assertRaisesRegex(TypeError, "both in options and as a keyword"):
            meshmorph.morph(self.annulus, ROTATE, options={"alpha": 2.0}, alpha=2.0)
        with self.assertRaises(TypeError):
            meshmorph.morph(self.annulus, ROTATE, alpah=2.0)


if __name__ == "__main__":
    unittest.main()
