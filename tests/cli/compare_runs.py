#!/usr/bin/python3
# SPDX-License-Identifier: MIT
# compare_runs.py REFERENCE.msh REFERENCE.json OTHER.msh OTHER.json: exit 1 unless the node
# positions of the two MSH 4.1 ASCII meshes agree to 1e-10 of the reference's bounding-box
# diagonal and the reports' figures to 1e-9 relative (1e-12 of the energy's scale near 0).
import json
import math
import sys


def nodes(path):
    lines = open(path).read().split("\n")
    at = lines.index("$Nodes") + 1
    n_blocks, n_nodes = (int(v) for v in lines[at].split()[:2])
    at += 1
    out = {}
    for _ in range(n_blocks):
        count = int(lines[at].split()[3])
        tags = [int(lines[at + 1 + k]) for k in range(count)]
        for k, tag in enumerate(tags):
            out[tag] = [float(v) for v in lines[at + 1 + count + k].split()]
        at += 1 + 2 * count
    assert len(out) == n_nodes, path
    return out


def main():
    ref_mesh, ref_report, mesh, report = sys.argv[1:5]
    a, b = nodes(ref_mesh), nodes(mesh)
    if a.keys() != b.keys():
        sys.exit(f"{mesh}: other node tags than {ref_mesh}")
    lo = [min(p[k] for p in a.values()) for k in range(3)]
    hi = [max(p[k] for p in a.values()) for k in range(3)]
    diagonal = math.dist(lo, hi)
    worst = max(math.dist(a[t], b[t]) for t in a) / diagonal
    if not worst <= 1e-10:
        sys.exit(f"{mesh}: nodes {worst:.3g} of the diagonal away from {ref_mesh}")
    r, s = json.load(open(ref_report)), json.load(open(report))
    scale = abs(r["energy_initial"])
    for key in ("energy_final", "energy_initial", "mu_min", "mu_mean", "mu_max", "min_det_final", "min_quality",
                "mean_quality", "min_shape_quality", "min_scaled_jacobian"):
        x, y = r[key], s[key]
        if not abs(x - y) <= 1e-9 * abs(x) + 1e-12 * scale:
            sys.exit(f"{report}: {key} {y!r} against {x!r} in {ref_report}")
    for key in ("valid", "converged", "inverted_elements", "nodes", "elements"):
        if r[key] != s[key]:
            sys.exit(f"{report}: {key} {s[key]!r} against {r[key]!r}")
    print(f"{mesh}: nodes within {worst:.2g} of the diagonal")


main()
