# SPDX-License-Identifier: MIT
"""Pictures of a morph in Python, without the command line: the annulus of example 01 with its
inner circle turned by 60 degrees, input and output side by side coloured by shape quality
(the worst 5% of cells outlined, a histogram under each); and the P2 sphere-in-box mesh of
example 03, cut in half, coloured by its scaled Jacobian.

    PYTHONPATH=build/python python3 examples/08_python_pictures/pictures.py [OUT_DIR]

Writes OUT_DIR/morph.png and OUT_DIR/sphere_in_box_p2.png (default: this folder). Needs
matplotlib (Debian python3-matplotlib).
"""
import pathlib
import sys

import meshmorph
import meshmorph.plot

here = pathlib.Path(__file__).resolve().parent
meshes = here.parent / "meshes"
out_dir = pathlib.Path(sys.argv[1]) if len(sys.argv) > 1 else here

annulus = meshmorph.read_mesh(meshes / "annulus.msh")
report, turned = meshmorph.morph(annulus, [{"group": "inner", "rotate": {"center": [0, 0], "degrees": 60}},
                                           {"group": "outer", "fixed": True}])
if not (report["converged"] and report["valid"]):
    sys.exit(f"morph: {report['message']}")
meshmorph.plot.compare(annulus, turned, out_dir / "morph.png", dpi=80)
print(f"wrote {out_dir / 'morph.png'}: min shape quality {report['min_shape_quality']:.3f}, "
      f"min quality against the input {report['min_quality']:.3f}")

sphere = meshmorph.read_mesh(meshes / "sphere_in_box_p2.msh")
meshmorph.plot.save(sphere, out_dir / "sphere_in_box_p2.png", field="scaled_jacobian", title="sphere_in_box_p2",
                    dpi=80)
print(f"wrote {out_dir / 'sphere_in_box_p2.png'}")
