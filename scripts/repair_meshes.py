#!/usr/bin/python3
# SPDX-License-Identifier: MIT
"""Curved meshes as Gmsh makes them, for scripts/bench-repair and tests/cli/check_repair.sh.

    repair_meshes.py OUT_DIR [NAME ...]

Each NAME (default: all of MESHES) is GEOMETRY_KIND_SIZE, e.g. sphere_p2tet_0.4: the geometry
meshed by Gmsh at that size and order, written as OUT_DIR/NAME.msh (MSH 4.1). Gmsh's own check
(Plugin AnalyseMeshQuality) gives its least Jacobian; where it is negative, the mesh is then
optimized by Gmsh (Mesh.HighOrderOptimize = 1, what `gmsh -optimize_ho` does) and written as
OUT_DIR/NAME_gmsh.msh. One JSON line per mesh on stdout: name, gmsh_min_jacobian,
gmsh_optimize_seconds, gmsh_cad_distance (the largest distance of a boundary node of the
optimized mesh from its CAD surface: Gmsh moves boundary nodes on the CAD). The optimizer runs
in a child process stopped after GMSH_TIMEOUT seconds (default 300); the row then has
"gmsh_timeout": true and no optimized mesh. Needs python3-gmsh.
"""
import json
import math
import multiprocessing
import os
import sys
import time

import gmsh

GEOMETRIES = ["sphere", "torus", "cylinder", "fillet", "wing"]
KINDS = {"p2tet": (2, False), "p3tet": (3, False), "p2hex": (2, True)}
SIZES = {"sphere": (0.4, 0.6), "torus": (0.3, 0.5), "cylinder": (0.2, 0.35), "fillet": (0.3, 0.5), "wing": (0.15, 0.25)}
MESHES = [f"{g}_{k}_{s}" for g in GEOMETRIES for k in KINDS for s in SIZES[g]]


def geometry(name):
    occ = gmsh.model.occ
    if name == "sphere":  # a sphere in a box
        occ.cut([(3, occ.addBox(-1.3, -1.3, -1.3, 2.6, 2.6, 2.6))], [(3, occ.addSphere(0, 0, 0, 1))])
    elif name == "torus":  # a torus in a box
        occ.cut([(3, occ.addBox(-2, -2, -1, 4, 4, 2))], [(3, occ.addTorus(0, 0, 0, 1.2, 0.4))])
    elif name == "cylinder":  # a cylinder through a box
        occ.cut([(3, occ.addBox(-1, -1, -1, 2, 2, 2))], [(3, occ.addCylinder(0, 0, -1.5, 0, 0, 3, 0.4))])
    elif name == "fillet":  # a box with filleted edges
        box = occ.addBox(0, 0, 0, 2, 1.5, 1)
        occ.synchronize()
        occ.fillet([box], [e[1] for e in gmsh.model.getEntities(1)], [0.25])
    elif name == "wing":  # a NACA 0012 section, extruded, in a box
        points = []
        for i in range(40):
            x = 0.5 * (1 - math.cos(math.pi * i / 39))
            t = 0.6 * (0.2969 * math.sqrt(x) - 0.126 * x - 0.3516 * x**2 + 0.2843 * x**3 - 0.1036 * x**4)
            points.append((x, t))
        upper = [occ.addPoint(x, y, 0) for x, y in points]
        lower = [occ.addPoint(x, -y, 0) for x, y in points[1:-1]] + [upper[-1]]
        curves = [occ.addBSpline(upper), occ.addBSpline([upper[0]] + lower)]
        section = occ.addPlaneSurface([occ.addCurveLoop(curves)])
        wing = occ.extrude([(2, section)], 0, 0, 1)
        body = [e for e in wing if e[0] == 3]
        occ.cut([(3, occ.addBox(-0.5, -0.6, 0, 2, 1.2, 1))], body)
    occ.synchronize()


def cad_distance():
    """The largest distance of a node on a CAD surface from that surface."""
    worst = 0.0
    for dim, tag in gmsh.model.getEntities(2):
        _, x, _ = gmsh.model.mesh.getNodes(dim, tag, False, False)
        if len(x) == 0:
            continue
        closest, _ = gmsh.model.getClosestPoint(dim, tag, x)
        worst = max(worst, max(math.dist(x[i:i + 3], closest[i:i + 3]) for i in range(0, len(x), 3)))
    return worst


def min_jacobian():
    gmsh.logger.start()
    gmsh.plugin.setNumber("AnalyseMeshQuality", "JacobianDeterminant", 1)
    gmsh.plugin.setNumber("AnalyseMeshQuality", "CreateView", 0)
    gmsh.plugin.run("AnalyseMeshQuality")
    lines = gmsh.logger.get()
    gmsh.logger.stop()
    for line in lines:
        if "minJ/maxJ =" in line and "worst" in line:
            return float(line.split("=")[1].split(",")[0])
    return float("nan")


def optimize(name, out, pipe):
    """Gmsh's high-order optimizer on the current model (a child process): its seconds and CAD distance."""
    start = time.perf_counter()
    gmsh.option.setNumber("Mesh.HighOrderOptimize", 1)
    gmsh.model.mesh.optimize("HighOrder")
    seconds = time.perf_counter() - start
    row = {"gmsh_optimize_seconds": seconds, "gmsh_cad_distance": cad_distance()}
    gmsh.write(f"{out}/{name}_gmsh.msh")
    pipe.send(row)


def make(name, out):
    geo, kind, size = name.split("_")
    order, hexes = KINDS[kind]
    gmsh.initialize()  # a session per mesh: the quality plugin measures a mesh once per session
    gmsh.option.setNumber("General.Terminal", 0)
    gmsh.model.add(name)
    geometry(geo)
    gmsh.option.setNumber("Mesh.MeshSizeMin", float(size))
    gmsh.option.setNumber("Mesh.MeshSizeMax", float(size))
    gmsh.option.setNumber("Mesh.SubdivisionAlgorithm", 2 if hexes else 0)
    gmsh.option.setNumber("Mesh.HighOrderOptimize", 0)
    gmsh.model.mesh.generate(3)
    gmsh.model.mesh.setOrder(order)
    gmsh.option.setNumber("Mesh.MshFileVersion", 4.1)
    gmsh.option.setNumber("Mesh.Binary", 1)
    gmsh.write(f"{out}/{name}.msh")
    row = {"name": name, "gmsh_min_jacobian": min_jacobian()}
    if row["gmsh_min_jacobian"] < 0:
        limit = float(os.environ.get("GMSH_TIMEOUT", "300"))
        # A forked child holds the model: the parent can stop an optimizer that runs too long.
        reader, writer = multiprocessing.get_context("fork").Pipe(False)
        child = multiprocessing.get_context("fork").Process(target=optimize, args=(name, out, writer))
        start = time.perf_counter()
        child.start()
        if reader.poll(limit):
            row.update(reader.recv())
        else:
            row["gmsh_optimize_seconds"] = time.perf_counter() - start
            row["gmsh_timeout"] = True
        child.terminate()
        child.join()
    gmsh.finalize()
    print(json.dumps(row), flush=True)


def main():
    out, names = sys.argv[1], sys.argv[2:] or MESHES
    for name in names:
        make(name, out)


if __name__ == "__main__":
    main()
