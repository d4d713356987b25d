# SPDX-License-Identifier: MIT
"""meshmorph in Python: read, convert and measure meshes; morph, untangle, fit, deform and optimize them.

    import meshmorph
    mesh = meshmorph.read_mesh("annulus.msh")
    m = meshmorph.Morpher(mesh, [{"group": "inner", "rotate": {"center": [0, 0], "degrees": 60}},
                                 {"group": "outer", "fixed": True}])
    result = m.solve()          # the report of `meshmorph morph`, and "points"
    mesh.points = result["points"]
    mesh.write("rotated.vtu")

Points are NumPy arrays of shape (n_nodes, dim): Mesh.points a read-only view, the other
arrays of a mesh read-only copies. Each method's options are keyword arguments too. Bad input
raises InputError (a ValueError) with the message the command line prints; a file that
cannot be read or written raises IoError (an OSError), MissingFileError (also a
FileNotFoundError) when it does not exist. docs/python.md has the whole interface.
"""
import json as _json
import os as _os


def _load_core():
    """Imports the C++ core with libgomp's threads sleeping at barriers unless the user chose.

    libgomp's threads spin at a barrier until the slowest arrives; where another process
    shares the cores, the thread they wait for is often paused and their spinning keeps it
    so (a solve 25-45 times slower beside one busy process on 2 cores: bench/python_load.py).
    libgomp reads OMP_WAIT_POLICY once, when it loads with the core: it is set to "passive"
    for that moment, unless the user set it or GOMP_SPINCOUNT, and taken out of the
    environment again, so that programs the user starts see theirs.
    """
    if "OMP_WAIT_POLICY" in _os.environ or "GOMP_SPINCOUNT" in _os.environ:
        return _import_core()
    import ctypes
    try:  # loaded already (by another module): its policy is fixed
        ctypes.CDLL("libgomp.so.1", mode=_os.RTLD_NOLOAD)
    except OSError:
        pass
    else:
        import warnings
        warnings.warn("meshmorph: libgomp was loaded before meshmorph with OMP_WAIT_POLICY unset: its threads "
                      "spin at barriers, and solves may be many times slower beside another busy process; "
                      "set OMP_WAIT_POLICY=passive before Python starts, or import meshmorph first "
                      "(docs/python.md, Threads)", RuntimeWarning, stacklevel=2)
        return _import_core()
    _os.environ["OMP_WAIT_POLICY"] = "passive"
    try:
        return _import_core()
    finally:
        del _os.environ["OMP_WAIT_POLICY"]


def _import_core():
    from . import _meshmorph
    return _meshmorph


_load_core()

import errno as _errno
import pathlib as _pathlib

from ._meshmorph import InputError, IoError, Mesh, __version__, elevate, quality, set_log_level
from ._meshmorph import read_mesh as _read_mesh
from ._meshmorph import _convert, _deform, _fit, _morph, _optimize, _untangle
from ._meshmorph import MorphSession as _MorphSession
from ._meshmorph import UntangleSession as _UntangleSession
from . import _meshio
from ._options import DEFORM as _DEFORM, FIT as _FIT, MORPH as _MORPH, MORPHER as _MORPHER
from ._options import OPTIMIZE as _OPTIMIZE, UNTANGLE as _UNTANGLE, keyword_options as _keyword_options

Mesh.from_meshio = staticmethod(_meshio.from_meshio)
Mesh.to_meshio = _meshio.to_meshio

__all__ = ["InputError", "IoError", "Mesh", "MissingFileError", "Morpher", "Untangler", "convert", "deform", "elevate", "fit", "morph",
           "optimize", "quality", "read_mesh", "set_log_level", "untangle", "write_mesh", "__version__"]


class MissingFileError(IoError, FileNotFoundError):
    """A file to read, or the folder of one to write, does not exist: an IoError and a
    FileNotFoundError (errno ENOENT, filename the missing path), its message the command line's."""

    def __str__(self):
        return self.strerror


def _missing(error, path, output=False):
    """`error` (an IoError about `path`) as a MissingFileError where the path, or an output's
    folder, does not exist."""
    missing = _pathlib.Path(path).parent if output else _pathlib.Path(path)
    if missing.exists():
        return error
    e = MissingFileError(_errno.ENOENT, str(error))
    e.filename = str(missing)
    return e


def read_mesh(path):
    """Reads a mesh; the format comes from the extension: .msh (2.2 or 4.1, ASCII or binary),
    .vtu, .mesh, .su2, .cgns, .exo/.e/.ex2, or an OpenFOAM case, polyMesh or time folder
    (docs/formats.md). Nodes come in Gmsh's order. Raises InputError (a ValueError) naming the
    file and line for bad content, MissingFileError (a FileNotFoundError and an IoError) when
    the file does not exist, IoError when it cannot be read.
    """
    try:
        return _read_mesh(path)
    except IoError as e:
        raise _missing(e, path) from None


_write = Mesh.write


def write_mesh(mesh, path, binary=False):
    """Writes `mesh` atomically; the format comes from the extension (.msh: MSH 4.1, .vtu,
    .mesh, .su2, .cgns, .exo/.e/.ex2), or a time folder of the OpenFOAM case the mesh was read
    from (case/0.001: its polyMesh/points). `binary`: binary MSH, base64 VTU. Nothing is
    written when it fails: MissingFileError when the folder does not exist, IoError otherwise.
    """
    try:
        _write(mesh, path, binary)
    except IoError as e:
        raise _missing(e, path, output=True) from None


Mesh.write = write_mesh


def _plain(value):
    """NumPy arrays and scalars in a boundary list or options, as JSON takes them."""
    if hasattr(value, "tolist"):
        return value.tolist()
    raise TypeError(f"{type(value).__name__} is not a JSON value")


def _case_text(name, case):
    """The case as JSON text; `name` stands for its file in messages."""
    try:
        return _json.dumps(case, default=_plain, allow_nan=False)
    except ValueError:
        raise InputError(f"{name}: the boundary, options and level sets must hold finite numbers "
                         "(NaN or infinity found)") from None
    except TypeError as e:
        raise InputError(f"{name}: {e}") from None


class _Method:
    """What Morpher and Untangler share: a case on a mesh in memory, solved again and again."""

    def __init__(self, session, name, mesh, boundary, options, order, threads, reorient=False):
        case = {"reorient": True} if reorient else {}
        if boundary is not None:
            case["boundary"] = boundary
        if options is not None:
            case["options"] = options
        if order is not None:
            case["order"] = order
        self._name = name
        self._session = session(mesh, _case_text(name, case), threads)

    @property
    def mesh(self):
        """A copy of the input mesh (elevated to `order`): the reference of the method's quality."""
        return self._session.mesh

    @property
    def points(self):
        """The current node positions, (n_nodes, dim): a read-only copy."""
        return self._session.points

    def solve(self, t=None, targets=None, progress=None):
        """Moves the nodes towards the boundary motion at fraction `t` (default 1) of its path
        or, when `targets` (an (n_nodes, dim) array) is given, towards the positions it holds
        for the nodes of the moving groups (its other rows are not used, but must be finite).
        `progress`: a callable given each progress line of the solve (a str, one per iteration).

        Returns the report of DESIGN §3.3 as a dict, with "points" (n_nodes, dim) added. When
        "converged" is False, "message" says why. Solves of one object from several threads
        take turns.
        """
        if targets is None:
            text, points = self._session.solve_at(1.0 if t is None else t, progress)
        elif t is None:
            text, points = self._session.solve_to(targets, progress)
        else:
            raise InputError(f"{self._name}.solve: give t or targets, not both")
        report = _json.loads(text)
        report["points"] = points
        return report


class Morpher(_Method):
    """Morphs `mesh` by the augmented Lagrangian of paper 000 (`meshmorph morph`).

    `boundary` is the "boundary" list of a case file (docs/case-file.md): each entry a group
    and its motion (fixed, translate, rotate, scale, project, displace, slide). `options`
    are the case file's morph options (docs/morph.md), `order` elevates the mesh first as the
    case file's "order" does. Relative paths (displacement tables, level-set files) are read
    from the current folder. The mesh is copied; it must be valid.

    Each solve() starts from where the last one ended, with the multipliers, penalty and
    weights it left (paper 000 §5.5): a time series is solve(t) for increasing t, and a
    shape-optimization loop is solve(targets=...) with new boundary positions each time. A
    solve that misses its goal still leaves a valid mesh (the last valid iterate).
    """

    @_keyword_options(_MORPHER, "docs/morph.md")
    def __init__(self, mesh, boundary, options=None, order=None, threads=0, reorient=False):
        super().__init__(_MorphSession, "Morpher", mesh, boundary, options, order, threads, reorient)


class Untangler(_Method):
    """Untangles and smooths `mesh` (paper 001, `meshmorph untangle`); the mesh may be tangled.

    `boundary` as for Morpher, or None: every boundary node stays where it is (`meshmorph
    untangle MESH`). `options` are the case file's untangle options (docs/untangle.md). The
    reference is the input mesh where it is valid, the regular cell where it is not.

    Each solve() starts from the last result, moved by the differential predictor (eq. 22–23).
    When "converged" is False the points may still be tangled: the report says how many cells.
    """

    @_keyword_options(_UNTANGLE, "docs/untangle.md")
    def __init__(self, mesh, boundary=None, options=None, order=None, threads=0, reorient=False):
        super().__init__(_UntangleSession, "Untangler", mesh, boundary, options, order, threads, reorient)


@_keyword_options(_FIT, "docs/fit.md")
def fit(mesh, interface=None, trim=None, boundary=None, options=None, order=None, threads=0, reorient=False,
        progress=None):
    """Fits `mesh` to level sets (paper 003, `meshmorph fit`): its material interface to
    `interface`, its boundary to `trim` after the cells outside are removed, or boundary groups
    to `project` entries of `boundary`. Level sets as in a case file (docs/level-sets.md):
    primitives, CSG, expressions, background meshes, distance fields; relative file paths are
    read from the current folder. `options` are the fit options of docs/fit.md, `order`
    elevates the mesh first. The mesh must be valid.

    Returns (report, mesh): the report of DESIGN §3.3 and docs/fit.md as a dict, and the
    fitted mesh, which trimming and splits may have changed cell by cell. When
    report["converged"] is False, report["message"] says why.
    """
    return _run(_fit, "fit", mesh, threads, progress, interface=interface, trim=trim, boundary=boundary,
                options=options, order=order, reorient=reorient or None)


def _run(method, name, mesh, threads, progress, **keys):
    """A whole case of the command line's runner on `mesh`: (report dict, moved mesh).
    Every method takes reorient=True as the case's "reorient" (cells listed mirrored against
    their neighbours are listed back instead of refused: docs/cli.md, --reorient), and
    `progress`, a callable given each progress line of the run (a str, one per iteration),
    on the calling thread; an exception it raises is raised when the run ends."""
    case = {key: value for key, value in keys.items() if value is not None}
    text, moved = method(mesh, _case_text(name, case), threads, progress)
    return _json.loads(text), moved


@_keyword_options(_MORPH, "docs/morph.md")
def morph(mesh, boundary, options=None, order=None, steps=None, threads=0, reorient=False, progress=None):
    """Morphs `mesh` as `meshmorph morph` runs a case (paper 000, or the baselines with
    options["method"] "laplace" or "elastic"): `boundary`, `options`, `order` and `steps` are
    the case file's keys (docs/case-file.md, docs/morph.md). Returns (report, mesh): the report
    of DESIGN §3.3 as a dict and the morphed mesh. When report["converged"] is False,
    report["message"] says why. Morpher solves again and again with its state kept.
    """
    return _run(_morph, "morph", mesh, threads, progress, boundary=boundary, options=options, order=order, steps=steps, reorient=reorient or None)


@_keyword_options(_UNTANGLE, "docs/untangle.md")
def untangle(mesh, boundary=None, options=None, order=None, steps=None, threads=0, reorient=False, progress=None):
    """Untangles and smooths `mesh` as `meshmorph untangle` runs a case (paper 001); without
    `boundary` every boundary node stays where it is (`meshmorph untangle MESH`). Returns
    (report, mesh); the report holds "steps" as the command line's does.
    """
    return _run(_untangle, "untangle", mesh, threads, progress, boundary=boundary, options=options, order=order, steps=steps, reorient=reorient or None)


@_keyword_options(_DEFORM, "docs/deform.md")
def deform(mesh, boundary, options=None, order=None, steps=None, threads=0, reorient=False, progress=None):
    """Deforms `mesh` as `meshmorph deform` runs a case (paper 004): CVT repair of the moved
    design surface, then Eikonal convection into the volume. `boundary` must move a design
    group; `options` are those of docs/deform.md. Returns (report, mesh).
    """
    return _run(_deform, "deform", mesh, threads, progress, boundary=boundary, options=options, order=order, steps=steps, reorient=reorient or None)


@_keyword_options(_OPTIMIZE, "docs/optimize.md")
def optimize(mesh, boundary=None, options=None, order=None, threads=0, reorient=False, progress=None):
    """Optimizes `mesh` by TMOP as `meshmorph optimize` does (docs/optimize.md): `options`
    choose the metric, target and boundary treatment ("boundary": "fixed", "slide",
    "slide-planes"); `boundary` entries fix a group, let it slide or project it onto a level
    set. A tangled mesh is untangled first. threads=0 picks as the command line does (one
    thread below 30 000 unknowns). Returns (report, mesh).
    """
    return _run(_optimize, "optimize", mesh, threads, progress, boundary=boundary, options=options, order=order, reorient=reorient or None)


def convert(input, output, order=None, binary=False, msh22=False):
    """`meshmorph convert`: reads `input`, raises it to `order` (straight-sided) and writes
    `output` atomically in the format of its extension (binary MSH or VTU with `binary`, MSH 2.2
    with `msh22`). Returns the converted mesh.
    """
    try:
        return _convert(input, output, 0 if order is None else order, binary, msh22)
    except IoError as e:
        raise _missing(_missing(e, input), output, output=True) from None
