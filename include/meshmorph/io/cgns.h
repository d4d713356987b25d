// SPDX-License-Identifier: MIT
#pragma once
#include <filesystem>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "meshmorph/io/mesh_series.h"
#include "meshmorph/mesh/mesh.h"

namespace meshmorph {

/// Reads an unstructured CGNS file (HDF5 or ADF) of one base: its zones' coordinates and
/// element sections (every type of cgns_type_order, MIXED sections too) in the internal node
/// order. Groups: each BC_t (PointList/PointRange of elements at FaceCenter/EdgeCenter, or
/// ElementList/ElementRange; at Vertex, the facets whose nodes it holds all, else its nodes
/// as points) and each ZoneSubRegion_t is a group named by its FamilyName, else by its own
/// name; a family's Ordinal_t is the group's tag. A Vertex sub-region's nodes are points. Without any BC or sub-region, each facet
/// section is a group named by the section. Several zones are merged on nodes of equal
/// coordinates; zones that touch without matching facets are an InputError. Malformed or
/// unsupported content is an InputError "file: node /Base/Zone/…: what".
Mesh read_cgns(const std::filesystem::path& path);

/// Writes `mesh` as an unstructured CGNS (HDF5) file at `file`, a temporary path the
/// caller renames (`shown`, the final path, is the file named in IoError messages): base
/// "Base", zone "Zone", one element section per block (cells, then facets, in their
/// order), a Family_t per group (its name; Ordinal_t = tag; unnamed groups
/// "group_<dim>_<tag>" with a Descriptor "unnamed"), facet groups of dimension dim − 1 as
/// BC_t (PointList of elements at FaceCenter/EdgeCenter, FamilySpecified), point groups as
/// Vertex ZoneSubRegion_t (their nodes; no NODE sections) and the other groups as
/// ZoneSubRegion_t of elements; `point_vectors` (Mesh::dim × n_nodes) as the Vertex
/// FlowSolution_t "FlowSolution" (components <Name>X/Y/Z: GridVelocity for mesh_velocity,
/// Displacement for displacement), `cell_data` (one value per cell of Mesh::cells, the zone's
/// elements 1 … n_cells) as the CellCenter FlowSolution_t "CellData". Throws InputError
/// without the file name for what CGNS cannot hold (names over 32 characters or with '/', two
/// groups of one name), IoError when the library fails.
void write_cgns(const std::filesystem::path& file, const Mesh& mesh, const std::filesystem::path& shown,
                const std::map<std::string, std::vector<double>>& cell_data = {},
                const std::map<std::string, Eigen::MatrixXd>& point_vectors = {});

/// Writes a moving mesh (write_mesh_series) as write_cgns lays out `mesh` (GridCoordinates:
/// the positions the motion starts from), with SimulationType TimeAccurate and per step k
/// (from 1) the GridCoordinates_t GridCoordinates_000k, the Vertex FlowSolution_t
/// FlowSolution_000k and the CellCenter one CellData_000k; BaseIterativeData_t holds the
/// steps' TimeValues and IterationValues (1 … n), ZoneIterativeData_t the pointers
/// GridCoordinatesPointers, FlowSolutionPointers (the Vertex solutions),
/// FlowSolutionCellCenterPointers (the CellCenter ones) and ArbitraryGridMotionPointers (each
/// naming the ArbitraryGridMotion_t "ArbitraryGridMotion" of type DeformingGrid).
void write_cgns_series(const std::filesystem::path& file, const Mesh& mesh, int n_steps,
                       const std::function<MeshStep(int)>& step, const std::filesystem::path& shown);

}  // namespace meshmorph
