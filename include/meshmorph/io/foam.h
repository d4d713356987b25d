// SPDX-License-Identifier: MIT
#pragma once
#include <filesystem>

#include "meshmorph/mesh/mesh.h"

namespace meshmorph {

/// Reads an OpenFOAM polyMesh. `path` is a case folder (its constant/polyMesh), a polyMesh
/// folder, a time folder of a case (its polyMesh/points with the topology of the case's
/// constant/polyMesh: a mesh moved before) or a `*.foam` file in a case folder (ParaView's
/// way to name a case). Reads points, faces (faceList or faceCompactList), owner, neighbour
/// and boundary, ASCII or binary (`format binary;`, labels of 32 or 64 bits, scalars of 64
/// or 32, as the header's `arch` says). Every cell must be a tetrahedron, prism, pyramid or
/// hexahedron: its faces, oriented out of their owner and into their neighbour, are matched
/// against the cell's and give its nodes in the internal (Gmsh) order. Boundary faces become
/// triangle and quadrilateral facets, one group per patch (tags 1, 2, … in the file's order,
/// named by the patch, whatever its type: empty and wedge patches too). Nodes keep the
/// points file's order (node j is OpenFOAM's point j), so a moved mesh writes back with
/// write_foam_points. Throws InputError naming the file and line (byte offset in binary
/// data) for malformed content, or the polyMesh folder and the cell or face, for a cell of
/// another shape (its index and face count), faces that do not close a cell or are
/// oriented against it, and patches that do not cover the boundary faces; IoError when a
/// file cannot be read.
Mesh read_foam(const std::filesystem::path& path);

/// True where `path` names a time folder of an OpenFOAM case: its name is a number (0.001)
/// and its parent folder holds constant/polyMesh (the folder itself need not exist yet).
bool is_foam_time_folder(const std::filesystem::path& path);

/// Writes the nodes of `mesh` as `<time_folder>/polyMesh/points` (ASCII vectorField, shortest
/// exact doubles, so the coordinates read back bit for bit), creating the folders, atomically
/// (io/atomic_file.h): OpenFOAM takes the topology of the case's constant/polyMesh with these
/// points (`checkMesh -time T`, a solver started at time T). The folder's name must be a
/// number (OpenFOAM's time), and the mesh must be the case's constant/polyMesh (read by
/// read_foam, whose node order it keeps), moved: as many nodes, and its cells on the same
/// nodes. Otherwise InputError, before anything is written.
void write_foam_points(const std::filesystem::path& time_folder, const Mesh& mesh);

}  // namespace meshmorph
