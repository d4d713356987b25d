# SPDX-License-Identifier: MIT
"""Pictures of meshes with matplotlib: cells coloured by a quality field (2D: every cell, curved
ones through their edge nodes; 3D: the boundary faces of the cells on one side of a cut plane,
so that the inside shows, each face coloured by its cell), the worst cells outlined in red, and
a histogram of the field beside.

    import meshmorph, meshmorph.plot
    before = meshmorph.read_mesh("examples/meshes/annulus.msh")
    report, after = meshmorph.morph(before, boundary)
    meshmorph.plot.compare(before, after, "morph.png")   # input and output side by side
    meshmorph.plot.save(after, "after.png", reference=before)

Needs matplotlib (Debian python3-matplotlib); draws without pyplot, so no display is used.
"""
import numpy as np
from matplotlib.collections import PolyCollection
from matplotlib.figure import Figure
from mpl_toolkits.mplot3d.art3d import Poly3DCollection

from . import _meshmorph as _core
from . import quality

FIELDS = ("quality", "shape_quality", "scaled_jacobian", "displacement")
_LABELS = {"quality": "quality 1/η against the input", "shape_quality": "shape quality",
           "scaled_jacobian": "scaled Jacobian", "displacement": "displacement (cell mean)"}


def cell_field(mesh, field=None, reference=None):
    """(values per cell, label): `field` is one of FIELDS or an array of one value per cell.
    None: "quality" with a reference (a mesh with the same cells), else "shape_quality".
    "quality" and "displacement" need `reference`."""
    if field is None:
        field = "quality" if reference is not None else "shape_quality"
    if not isinstance(field, str):
        values = np.asarray(field, dtype=float)
        if values.shape != (mesh.n_cells,):
            raise _core.InputError(f"plot: field: expected one value per cell ({mesh.n_cells}), found shape "
                                   f"{values.shape}")
        return values, "field"
    if field not in FIELDS:
        raise _core.InputError(f"plot: field: expected one of {', '.join(FIELDS)}, found \"{field}\"")
    if field in ("quality", "displacement") and reference is None:
        raise _core.InputError(f"plot: field \"{field}\" needs the reference mesh (reference=...)")
    if field == "displacement":
        moved = np.linalg.norm(mesh.points - reference.points, axis=1)
        return np.concatenate([moved[b["nodes"]].mean(axis=1) for b in mesh.cell_blocks]), _LABELS[field]
    return np.asarray(quality(mesh, reference)[field], dtype=float), _LABELS[field]


def _worst(values, mark):
    """The cells to outline: the `mark` fraction with the lowest values, and those at 0 or below;
    none at the best value (a uniform field outlines nothing), as `meshmorph plot` draws them."""
    worst = values <= 0.0
    if mark > 0 and len(values):
        top = values.max()
        worst |= (values <= np.quantile(values, mark)) & (values < top - 1e-9 * abs(top))
    return worst


def _cut(mesh):
    """The cells of a 3D mesh whose centres lie below the middle of its y range, as a mesh,
    and their indices in `mesh`."""
    points = mesh.points
    centres = np.concatenate([points[b["nodes"]].mean(axis=1) for b in mesh.cell_blocks])
    keep = centres[:, 1] <= 0.5 * (points[:, 1].min() + points[:, 1].max())
    blocks, start = [], 0
    for b in mesh.cell_blocks:
        rows = keep[start:start + len(b["nodes"])]
        start += len(b["nodes"])
        if rows.any():
            blocks.append({"type": b["type"], "order": b["order"], "nodes": b["nodes"][rows]})
    return _core.Mesh(points, blocks), np.flatnonzero(keep)


def draw(ax, mesh, values, mark=0.05, cmap="viridis", vmin=None, vmax=None, cut=True):
    """Draws `mesh` on `ax` (a 2D Axes, or a 3D one for a 3D mesh), its cells coloured by
    `values` (one per cell) and the worst ones (`mark`: their fraction) outlined in red; a 3D
    mesh by the boundary faces of its cells on the low-y side of the middle (`cut`), or of all
    its cells. Returns the collection (for a colour bar)."""
    worst = _worst(values, mark)
    if mesh.dim == 2:
        points = mesh.points
        polygons = [points[loop] for block in _core._cell_outlines(mesh) for loop in block]
        cells = PolyCollection(polygons, array=values, cmap=cmap, edgecolors="0.25", linewidths=0.2)
        ax.add_collection(cells)
        ax.add_collection(PolyCollection([p for p, w in zip(polygons, worst) if w], facecolors="none",
                                         edgecolors="red", linewidths=0.9))
        ax.autoscale_view()
        ax.set_aspect("equal")
    else:
        shown, index = _cut(mesh) if cut else (mesh, np.arange(mesh.n_cells))
        cell, corners = _core._boundary_faces(shown)
        cell = index[cell]
        points = mesh.points
        polygons = [points[c[c >= 0]] for c in corners]
        cells = Poly3DCollection(polygons, array=values[cell], cmap=cmap, edgecolors="0.25", linewidths=0.1)
        cells.set_edgecolor([(1, 0, 0, 1) if worst[c] else (0.25, 0.25, 0.25, 1) for c in cell])
        ax.add_collection3d(cells)
        low, high = points.min(axis=0), points.max(axis=0)
        ax.set_xlim(low[0], high[0])
        ax.set_ylim(low[1], high[1])
        ax.set_zlim(low[2], high[2])
        ax.set_box_aspect(high - low)
        ax.view_init(elev=20, azim=60 if cut else -60)  # the cut face looks towards +y
    cells.set_clim(values.min() if vmin is None else vmin, values.max() if vmax is None else vmax)
    ax.set_axis_off()
    return cells


def _panel(fig, spec, mesh, values, label, title, mark, limits):
    """A mesh and its histogram in one cell of the figure's grid."""
    inner = spec.subgridspec(2, 1, height_ratios=[4, 1], hspace=0.25)
    ax = fig.add_subplot(inner[0], projection="3d" if mesh.dim == 3 else None)
    cells = draw(ax, mesh, values, mark, vmin=limits[0], vmax=limits[1])
    fig.colorbar(cells, ax=ax, shrink=0.7, label=label)
    n_worst = int(_worst(values, mark).sum())
    ax.set_title(f"{title}: min {values.min():.3f}, {n_worst} worst outlined", fontsize=9)
    hist = fig.add_subplot(inner[1])
    hist.hist(values, bins=40, range=limits, color="steelblue")
    hist.set_xlabel(label, fontsize=8)
    hist.set_ylabel("cells", fontsize=8)
    hist.tick_params(labelsize=7)


def figure(mesh, field=None, reference=None, mark=0.05, title="mesh"):
    """A matplotlib Figure of `mesh` coloured by `field` (cell_field), with its histogram."""
    values, label = cell_field(mesh, field, reference)
    fig = Figure(figsize=(6, 6), layout="constrained")
    _panel(fig, fig.add_gridspec(1, 1)[0], mesh, values, label, title, mark, (values.min(), values.max()))
    return fig


def save(mesh, path, field=None, reference=None, mark=0.05, title="mesh", dpi=120):
    """Writes figure(...) to `path` (.png, .svg, .pdf: the format from the extension)."""
    figure(mesh, field, reference, mark, title).savefig(str(path), dpi=dpi)


def compare(before, after, path=None, field="shape_quality", mark=0.05, dpi=120):
    """Input and output side by side, each coloured by `field` ("shape_quality" or
    "scaled_jacobian": both are measured on each mesh alone) on one colour scale, with
    histograms. Writes `path` when given; returns the Figure."""
    if field not in ("shape_quality", "scaled_jacobian"):
        raise _core.InputError(f"plot.compare: field: expected \"shape_quality\" or \"scaled_jacobian\", found \"{field}\"")
    (a, label), (b, _) = cell_field(before, field), cell_field(after, field)
    limits = (min(a.min(), b.min()), max(a.max(), b.max()))
    fig = Figure(figsize=(12, 6), layout="constrained")
    grid = fig.add_gridspec(1, 2)
    _panel(fig, grid[0], before, a, label, "input", mark, limits)
    _panel(fig, grid[1], after, b, label, "output", mark, limits)
    if path is not None:
        fig.savefig(str(path), dpi=dpi)
    return fig
