# SPDX-License-Identifier: MIT
# The cases of scripts/bench-soak: random small meshes with a hole (every cell family, P1–P3),
# random rigid and smooth motions of one of their boundaries, and the check of a P1 result
# that does not use meshmorph (signed volumes, corner Jacobians, face orientations, the volume
# the boundary encloses, crossing boundary edges in 2D).
import math, os

import numpy as np

ROOT = os.path.normpath(os.path.join(os.path.dirname(os.path.abspath(__file__)), '..'))
FAMILIES = [(t, p) for t in ('triangle', 'quadrilateral', 'tetrahedron', 'hexahedron') for p in (1, 2, 3)]
DIM = {'triangle': 2, 'quadrilateral': 2, 'tetrahedron': 3, 'hexahedron': 3}
FACET = {'triangle': 'line', 'quadrilateral': 'line', 'tetrahedron': 'triangle', 'hexahedron': 'quadrilateral'}
SHORT = {'triangle': 'tri', 'quadrilateral': 'quad', 'tetrahedron': 'tet', 'hexahedron': 'hex'}
# The faces of a P1 cell, oriented outwards (Gmsh's node order).
FACES = {'triangle': [(0, 1), (1, 2), (2, 0)], 'quadrilateral': [(0, 1), (1, 2), (2, 3), (3, 0)],
         'tetrahedron': [(0, 2, 1), (0, 1, 3), (0, 3, 2), (1, 2, 3)],
         'hexahedron': [(0, 3, 2, 1), (4, 5, 6, 7), (0, 1, 5, 4), (3, 7, 6, 2), (0, 4, 7, 3), (1, 2, 6, 5)]}
# The corners of the reference square and cube in Gmsh's order.
CORNERS = {'quadrilateral': np.array([[0, 0], [1, 0], [1, 1], [0, 1]], float),
           'hexahedron': np.array([[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0],
                                   [0, 0, 1], [1, 0, 1], [1, 1, 1], [0, 1, 1]], float)}
GAUSS = (0.5 - 0.5 / math.sqrt(3), 0.5 + 0.5 / math.sqrt(3))  # 2 points on [0, 1], weights ½
KUHN = [(0, 1, 2, 6), (0, 2, 3, 6), (0, 3, 7, 6), (0, 7, 4, 6), (0, 4, 5, 6), (0, 5, 1, 6)]
WARMUP = 100


# ---------------------------------------------------------------------------------------------
# Random meshes: a box of n cells per side with a hole of k cells per side, the grid lines
# unevenly spaced, the interior nodes jittered, the axes stretched; simplices split from it.

def random_mesh(meshmorph, rng, ctype, order):
    """A valid random mesh with the groups outer (1), inner (2) and domain (3), and its hole's
    centre and the width (a length) of the narrowest layer of cells around the hole."""
    d = DIM[ctype]
    hole = int(rng.integers(1, 3)) if d == 2 or order == 1 else 1
    if d == 2:
        margin = [int(rng.integers(2, {1: 5, 2: 4, 3: 3}[order])) for _ in range(2 * d)]
    else:
        margin = [int(rng.integers(1, 3)) if order == 1 else 1 for _ in range(2 * d)]
    n = [margin[2 * a] + hole + margin[2 * a + 1] for a in range(d)]
    lines = []
    for a in range(d):
        h = rng.uniform(0.7, 1.3, n[a])
        lines.append(np.concatenate([[0.0], np.cumsum(h)]) / n[a] * rng.uniform(0.6, 1.6))
    shape = [m + 1 for m in n]
    index = np.indices(shape).reshape(d, -1).T  # grid index of each node, x fastest last
    x = np.stack([lines[a][index[:, a]] for a in range(d)], axis=1)
    lo = np.array([margin[2 * a] for a in range(d)])
    hi = lo + hole
    # Cells: every grid cell outside the hole, as Gmsh orders a quad / hex.
    cells = []
    for c in np.ndindex(*n):
        c = np.array(c)
        if np.all(c >= lo) and np.all(c < hi):
            continue
        offs = CORNERS['quadrilateral' if d == 2 else 'hexahedron'].astype(int)
        cells.append([np.ravel_multi_index(tuple(c + o), shape) for o in offs])
    cells = np.array(cells)
    interior = np.all((index > 0) & (index < np.array(n)), axis=1) & \
        ~np.all((index >= lo) & (index <= hi), axis=1)
    spacing = min(np.min(np.diff(l)) for l in lines)
    x[interior] += rng.uniform(-0.12, 0.12, (int(interior.sum()), d)) * spacing
    if ctype == 'triangle':
        flip = rng.random(len(cells)) < 0.5  # each square's diagonal at random
        a = np.where(flip[:, None], cells[:, [0, 1, 2]], cells[:, [0, 1, 3]])
        b = np.where(flip[:, None], cells[:, [0, 2, 3]], cells[:, [1, 2, 3]])
        cells = np.concatenate([a, b])
    elif ctype == 'tetrahedron':
        cells = np.concatenate([cells[:, list(t)] for t in KUHN])
    if ctype in ('triangle', 'tetrahedron'):
        neg = signed_volumes(ctype, x, cells) < 0
        cells[neg, 0], cells[neg, 1] = cells[neg, 1].copy(), cells[neg, 0].copy()
    used = np.unique(cells)
    renumber = -np.ones(len(x), dtype=np.int64)
    renumber[used] = np.arange(len(used))
    x, cells, index = x[used], renumber[cells], index[used]
    faces, _ = boundary_faces(ctype, cells)
    on_hole = np.all(np.all((index[faces] >= lo) & (index[faces] <= hi), axis=2), axis=1)
    points = x
    mesh = meshmorph.Mesh(points, [{'type': ctype, 'nodes': cells, 'physical': np.full(len(cells), 3)}],
                          [{'type': FACET[ctype], 'nodes': faces, 'physical': np.where(on_hole, 2, 1)}],
                          [{'name': 'outer', 'dim': d - 1, 'tag': 1}, {'name': 'inner', 'dim': d - 1, 'tag': 2},
                           {'name': 'domain', 'dim': d, 'tag': 3}])
    if order > 1:
        mesh = meshmorph.elevate(mesh, order)
    lo_x = np.array([lines[a][lo[a]] for a in range(d)])
    hi_x = np.array([lines[a][hi[a]] for a in range(d)])
    gap = min(min(lines[a][lo[a]] - lines[a][0], lines[a][-1] - lines[a][hi[a]]) for a in range(d))
    return mesh, (lo_x + hi_x) / 2, gap, float(np.min(hi_x - lo_x))


# ---------------------------------------------------------------------------------------------
# The independent check of a P1 mesh.

def jacobians(ctype, x, cells, at):
    """det of the cell map at reference points `at` (cells × points)."""
    if ctype in ('triangle', 'tetrahedron'):
        e = x[cells[:, 1:]] - x[cells[:, :1]]
        return np.linalg.det(e)[:, None]
    ref = CORNERS[ctype]
    d = ref.shape[1]
    out = []
    for p in at:
        # Gradients of the multilinear shape functions at p.
        grads = np.empty((len(ref), d))
        for i, r in enumerate(ref):
            f = np.where(r == 1, p, 1 - p)
            df = np.where(r == 1, 1.0, -1.0)
            for a in range(d):
                grads[i, a] = df[a] * np.prod(np.delete(f, a))
        out.append(np.linalg.det(np.einsum('cnk,na->cka', x[cells], grads)))
    return np.stack(out, axis=1)


def signed_volumes(ctype, x, cells):
    d = x.shape[1]
    if ctype in ('triangle', 'tetrahedron'):
        return jacobians(ctype, x, cells, None)[:, 0] / math.factorial(d)
    pts = np.array(np.meshgrid(*[GAUSS] * d, indexing='ij')).reshape(d, -1).T
    return jacobians(ctype, x, cells, pts).sum(axis=1) / len(pts)


def boundary_faces(ctype, cells):
    """The faces used by one cell (oriented as that cell induces), and the number of interior
    faces whose two cells do not induce opposite orientations (or that more cells share)."""
    local = FACES[ctype]
    faces = np.concatenate([cells[:, list(f)] for f in local])
    key = np.sort(faces, axis=1)
    _, inverse, counts = np.unique(key, axis=0, return_inverse=True, return_counts=True)
    inverse = inverse.reshape(-1)
    once = counts[inverse] == 1
    bad = int(np.sum(counts > 2))
    two = np.flatnonzero(counts[inverse] == 2)
    order = two[np.argsort(inverse[two], kind='stable')]
    for a, b in zip(order[0::2], order[1::2]):
        if canonical(faces[a]) != canonical(faces[b][::-1]):
            bad += 1
    return faces[once], bad


def canonical(face):
    """A cyclic face as the rotation that starts at its smallest node."""
    face = [int(v) for v in face]
    i = face.index(min(face))
    return tuple(face[i:] + face[:i])


def enclosed_volume(ctype, x, faces):
    """(1/d) ∮ x·n over the oriented boundary faces (exact for flat and bilinear faces)."""
    p = x[faces]
    if p.shape[1] == 2:
        return 0.5 * float(np.sum(p[:, 0, 0] * p[:, 1, 1] - p[:, 1, 0] * p[:, 0, 1]))
    if p.shape[1] == 3:
        return float(np.sum(np.einsum('fi,fi->f', p[:, 0], np.cross(p[:, 1], p[:, 2])))) / 6
    total = 0.0
    for u in GAUSS:
        for v in GAUSS:
            pt = (1 - u) * (1 - v) * p[:, 0] + u * (1 - v) * p[:, 1] + u * v * p[:, 2] + (1 - u) * v * p[:, 3]
            du = (1 - v) * (p[:, 1] - p[:, 0]) + v * (p[:, 2] - p[:, 3])
            dv = (1 - u) * (p[:, 3] - p[:, 0]) + u * (p[:, 2] - p[:, 1])
            total += float(np.sum(np.einsum('fi,fi->f', pt, np.cross(du, dv)))) / 4
    return total / 3


def crossing_edges(x, edges):
    """The number of pairs of boundary edges (2D) that cross or touch away from a shared node."""
    p, q = x[edges[:, 0]], x[edges[:, 1]]
    r = q - p

    def cross(a, b):
        return a[..., 0] * b[..., 1] - a[..., 1] * b[..., 0]
    dpq = p[None, :, :] - p[:, None, :]
    den = cross(r[:, None, :], r[None, :, :])
    with np.errstate(divide='ignore', invalid='ignore'):
        t = cross(dpq, r[None, :, :]) / den
        s = cross(dpq, r[:, None, :]) / den
    share = (edges[:, None, 0] == edges[None, :, 0]) | (edges[:, None, 0] == edges[None, :, 1]) | \
        (edges[:, None, 1] == edges[None, :, 0]) | (edges[:, None, 1] == edges[None, :, 1])
    # Parallel to rounding (edges along one straight side): t and s are noise there, and such
    # edges meet only where they lie on one line and overlap.
    length = np.linalg.norm(r, axis=1)
    parallel = np.abs(den) <= 1e-12 * length[:, None] * length[None, :]
    hit = ~parallel & (t >= 0) & (t <= 1) & (s >= 0) & (s <= 1) & ~share
    with np.errstate(divide='ignore', invalid='ignore'):
        off_line = np.abs(cross(dpq, r[:, None, :])) / length[:, None]  # p_j's distance from the line of edge i
        a = np.einsum('ijk,ik->ij', dpq, r) / length[:, None] ** 2     # p_j and q_j along edge i (0 … 1)
        b = a + np.einsum('jk,ik->ij', r, r) / length[:, None] ** 2
    overlap = parallel & (off_line <= 1e-12 * length[:, None]) & (np.maximum(a, b) > 0) & (np.minimum(a, b) < 1) & ~share
    return int(np.sum(np.triu(hit | overlap, 1)))


def p1_problems(mesh):
    """What the independent check finds wrong with a P1 mesh ('' if nothing)."""
    blocks = mesh.cell_blocks
    if len(blocks) != 1:
        return 'expected one cell block, found %d' % len(blocks)
    ctype, cells, x = blocks[0]['type'], blocks[0]['nodes'], mesh.points
    d = x.shape[1]
    vol = signed_volumes(ctype, x, cells)
    problems = []
    if np.any(vol <= 0):
        problems.append('%d cells of signed volume <= 0' % int(np.sum(vol <= 0)))
    if ctype in CORNERS:
        bad = int(np.sum(np.any(jacobians(ctype, x, cells, CORNERS[ctype]) <= 0, axis=1)))
        if bad:
            problems.append('%d cells with a corner Jacobian <= 0' % bad)
    faces, misoriented = boundary_faces(ctype, cells)
    if misoriented:
        problems.append('%d interior faces not oriented oppositely by their two cells' % misoriented)
    enclosed, total = enclosed_volume(ctype, x, faces), float(np.sum(vol))
    if abs(total - enclosed) > 1e-9 * float(np.sum(np.abs(vol))):
        problems.append('cell volumes sum to %.17g, the boundary encloses %.17g' % (total, enclosed))
    if d == 2:
        crossings = crossing_edges(x, faces)
        if crossings:
            problems.append('%d pairs of boundary edges cross' % crossings)
    return '; '.join(problems)


# ---------------------------------------------------------------------------------------------
# Random motions.

def rotation(rng, d, degrees):
    a = math.radians(degrees)
    if d == 2:
        return np.array([[math.cos(a), -math.sin(a)], [math.sin(a), math.cos(a)]]), None
    axis = rng.normal(size=3)
    axis /= np.linalg.norm(axis)
    k = np.array([[0, -axis[2], axis[1]], [axis[2], 0, -axis[0]], [-axis[1], axis[0], 0]])
    return np.eye(3) + math.sin(a) * k + (1 - math.cos(a)) * k @ k, axis


def random_motion(rng, mesh, center, gap, hole):
    """A boundary list for the case, the smooth displacements {group: (nodes, d)} it names
    through files, and a short name of the motion."""
    d = mesh.dim
    moving, still = ('inner', 'outer') if rng.random() < 0.75 else ('outer', 'inner')
    kind = rng.choice(['rotate', 'translate', 'scale', 'smooth'], p=[0.4, 0.15, 0.1, 0.35])
    if kind == 'rotate':
        degrees = float(rng.uniform(10, 60) if d == 2 else rng.uniform(5, 25)) * rng.choice([-1, 1])
        c = center + rng.uniform(-0.15, 0.15, d) * hole
        _, axis = rotation(rng, d, degrees)
        r = {'center': c.tolist(), 'degrees': degrees}
        if axis is not None:
            r['axis'] = axis.tolist()
        return [{'group': moving, 'rotate': r}, {'group': still, 'fixed': True}], {}, 'rotate %.0f°' % degrees
    if kind == 'translate':
        v = rng.normal(size=d)
        v *= rng.uniform(0.1, 0.5 if d == 2 else 0.35) * gap / np.linalg.norm(v)
        return [{'group': moving, 'translate': v.tolist()}, {'group': still, 'fixed': True}], {}, 'translate'
    if kind == 'scale':
        f = float(rng.uniform(0.75, 1.3) if d == 2 else rng.uniform(0.85, 1.15))
        return [{'group': 'inner', 'scale': {'center': center.tolist(), 'factor': f}},
                {'group': 'outer', 'fixed': True}], {}, 'scale %.2f' % f
    # A smooth displacement of one or both groups: an affine part and a sine wave.
    x = mesh.points
    span = x.max(axis=0) - x.min(axis=0)
    boundary, fields = [], {}
    # Both groups in 2D only: in 3D one layer of cells may lie between them.
    groups = ['inner', 'outer'] if rng.random() < 0.3 and d == 2 else [moving]
    for g in groups:
        nodes = np.asarray(mesh.group_nodes(g))
        amp = rng.uniform(0.1, 0.4 if d == 2 else 0.25) * gap
        k = rng.integers(1, 3, d) * 2 * math.pi / span
        phase = rng.uniform(0, 2 * math.pi, d)
        direction = rng.normal(size=(d, d))
        y = (x[nodes] - center) / span
        disp = amp * np.sin(y @ direction * (k * span) + phase) / math.sqrt(d)
        disp += amp * 0.5 * (rng.normal(size=d) + (y @ rng.normal(size=(d, d))) * 0.5)
        fields[g] = (nodes, disp)
        boundary.append({'group': g, 'displace': {'file': '%s.csv' % g}})
    if len(groups) == 1:
        boundary.append({'group': still, 'fixed': True})
    return boundary, fields, 'smooth'


def write_csv(path, tags, disp):
    with open(path, 'w') as f:
        f.write('node,' + ','.join('d' + c for c in 'xyz'[:disp.shape[1]]) + '\n')
        for t, row in zip(tags, disp):
            f.write('%d,%s\n' % (t, ','.join(repr(float(v)) for v in row)))


def random_case(meshmorph, seed, path, i):
    """Run i of a path: its family, mesh, boundary list, displacement fields, motion name and
    the random generator (for the rest of the run's choices)."""
    rng = np.random.default_rng([seed, path, i])
    ctype, order = FAMILIES[int(rng.integers(len(FAMILIES)))]
    mesh, center, gap, hole = random_mesh(meshmorph, rng, ctype, order)
    boundary, fields, what = random_motion(rng, mesh, center, gap, hole)
    return (ctype, order), mesh, boundary, fields, what, rng
