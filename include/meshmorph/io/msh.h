// SPDX-License-Identifier: MIT
#pragma once
#include <filesystem>
#include <map>
#include <ostream>
#include <string>
#include <string_view>
#include <vector>

#include "meshmorph/mesh/mesh.h"

namespace meshmorph {

/// Reads a Gmsh MSH file, version 4.1 or 2.2, ASCII or binary (detected from $MeshFormat).
///
/// Sections read: $MeshFormat, $PhysicalNames, $Entities (4.1: physical tags live on the
/// entities; an entity with several physical tags gives its cells the first one), $Nodes,
/// $Elements, $NodeData; other `$X … $EndX` sections are skipped. Scalar $NodeData (one
/// component) becomes Mesh::node_fields under its first string tag: records are matched to
/// nodes by tag (binary: int32 tag + double, as Gmsh writes them), the last time step of a
/// name wins, sections of the same step (partitions) are merged, and every node must get a
/// value; vector and tensor $NodeData are skipped. Values may be NaN or infinite. Node tags may be sparse and
/// unordered; they are kept in Mesh::node_tags. Element types: the complete Lagrange
/// points, lines, triangles, quadrilaterals, tetrahedra and hexahedra of orders 1–4.
/// Elements of the highest dimension (3 if any 3D element, else 2) become cells, the others
/// facets; one CellBlock per (type, order) in order of first appearance. MSH 2.2: tag 1 is
/// the physical group, tag 2 the elementary entity. Throws InputError ("file: line N: …",
/// or "file: byte offset N: …" inside binary data) for malformed content, MSH 4.0, and
/// unsupported element types, $NodeData before $Nodes, a record of an undefined node tag, or
/// a node without a value; IoError when the file cannot be read.
Mesh read_msh(const std::filesystem::path& path);

/// read_msh on the bytes of a file held in memory; `file` names it in messages.
Mesh parse_msh(std::string_view data, const std::filesystem::path& file);

/// Writes a mesh as MSH `version` 41 (4.1) or 22 (2.2), ASCII or binary (little-endian,
/// size_t = 8). Facets are written before cells; consecutive cells with the same
/// (entity, physical) tags form one element block, so reading the file back gives the same
/// blocks, cells, tags and groups. Named groups go to $PhysicalNames; in 4.1 one entity per
/// (dimension, entity tag, physical tag) carries the physical tag (entity tags are kept when
/// they determine the physical tag, else renumbered). Node tags are written as stored
/// (1..n when Mesh::node_tags is empty). Each node field follows as one $NodeData section
/// (time step 0, one component, Gmsh's layout). Doubles are printed with the shortest exact
/// representation, so ASCII files round-trip bit for bit. Throws InputError for a mesh MSH
/// cannot hold (MSH 2.2 node tags above 2^31 − 1, binary $NodeData with a node tag above
/// 2^31 − 1, a field name with a quote or line break), std::invalid_argument for a node
/// field without one value per node; both before writing anything. Each array of
/// `cell_data` (one value per cell of Mesh::cells) follows as an $ElementData section, each
/// of `point_vectors` (Mesh::dim × n_nodes) as a $NodeData section of 3 components.
void write_msh(std::ostream& out, const Mesh& mesh, int version, bool binary,
               const std::map<std::string, std::vector<double>>& cell_data = {},
               const std::map<std::string, Eigen::MatrixXd>& point_vectors = {});

}  // namespace meshmorph
