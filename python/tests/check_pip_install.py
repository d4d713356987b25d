# SPDX-License-Identifier: MIT
"""pip install of the package from this tree, its module taken from an existing CMake build
(MESHMORPH_BUILD_DIR: nothing is rebuilt), into a temporary folder; then the installed package,
imported from outside the tree, reads a mesh and measures it.

    python3 python/tests/check_pip_install.py BUILD_DIR
"""
import os
import pathlib
import subprocess
import sys
import tempfile

ROOT = pathlib.Path(__file__).resolve().parents[2]
USE = """
import pathlib, sys, meshmorph
assert pathlib.Path(meshmorph.__file__).is_relative_to(sys.argv[1]), meshmorph.__file__
mesh = meshmorph.read_mesh(sys.argv[2])
assert (mesh.n_nodes, mesh.n_cells, meshmorph.quality(mesh)["inverted_elements"]) == (196, 332, 0), mesh
print("installed:", meshmorph.__file__, meshmorph.__version__, mesh)
"""

with tempfile.TemporaryDirectory() as tmp:
    target = pathlib.Path(tmp) / "site"
    env = {k: v for k, v in os.environ.items() if k != "PYTHONPATH"}
    subprocess.run([sys.executable, "-m", "pip", "install", "--quiet", "--no-build-isolation", "--no-deps", "--no-index",
                    "--disable-pip-version-check", "--target", str(target), str(ROOT)],
                   env={**env, "MESHMORPH_BUILD_DIR": sys.argv[1], "PIP_ROOT_USER_ACTION": "ignore"}, check=True)
    subprocess.run([sys.executable, "-c", USE, str(target), str(ROOT / "tests" / "data" / "annulus_coarse.msh")],
                   env={**env, "PYTHONPATH": str(target)}, cwd=tmp, check=True)
