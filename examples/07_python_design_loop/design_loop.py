# SPDX-License-Identifier: MIT
"""A shape-optimization loop in Python: the inner circle of the annulus becomes a three-lobed
shape, r(θ) = 0.4 (1 + a cos 3θ), one design after another (a = 0.025 … 0.2), and the volume
mesh follows each design with one Morpher.solve(targets=...). The Morpher is set up once:
every solve starts from the last mesh with the multipliers, penalty and weights it left.

    PYTHONPATH=build/python python3 examples/07_python_design_loop/design_loop.py [OUT_DIR]

Writes OUT_DIR/design.vtu (default: this folder) and prints a row per design.
"""
import pathlib
import sys
import time

import numpy as np

import meshmorph

here = pathlib.Path(__file__).resolve().parent
out_dir = pathlib.Path(sys.argv[1]) if len(sys.argv) > 1 else here
mesh = meshmorph.read_mesh(str(here.parent / "meshes" / "annulus.msh"))
inner = mesh.group_nodes("inner")
x = mesh.points
theta = np.arctan2(x[inner, 1], x[inner, 0])

# The case's motion only says which nodes move (the inner circle) and which stay (the outer);
# the designs give their positions.
morpher = meshmorph.Morpher(mesh, [{"group": "inner", "translate": [0, 0]}, {"group": "outer", "fixed": True}])
print("| a | min quality | Newton steps | linear solves | seconds | boundary error |")
print("|---:|---:|---:|---:|---:|---:|")
for a in np.linspace(0.025, 0.2, 8):
    targets = x.copy()
    r = 0.4 * (1.0 + a * np.cos(3.0 * theta))
    targets[inner] = np.column_stack([r * np.cos(theta), r * np.sin(theta)])
    start = time.perf_counter()
    result = morpher.solve(targets=targets)
    seconds = time.perf_counter() - start
    if not (result["converged"] and result["valid"]):
        sys.exit(f"design a = {a:.3f}: {result['message']}")
    print(f"| {a:.3f} | {result['min_quality']:.3f} | {result['iterations']['newton']} | "
          f"{result['iterations']['linear']} | {seconds:.3f} | {result['boundary_error_max']:.1e} |")

mesh.points = morpher.points
mesh.write(str(out_dir / "design.vtu"))
print(f"wrote {out_dir / 'design.vtu'}")
