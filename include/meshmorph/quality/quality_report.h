// SPDX-License-Identifier: MIT
#pragma once
#include <array>
#include <cstddef>
#include <cstdint>
#include <string_view>
#include <vector>

#include "meshmorph/mesh/mesh.h"

namespace meshmorph {

/// The minima of QualityReport over the cells of one type (all its blocks, any order), e.g. a
/// boundary layer's prisms apart from the tetrahedra around them. NaN where the whole
/// report's value is (min_quality without an input mesh), and min_scaled_jacobian where no
/// cell of the type has a finite value.
struct CellTypeQuality {
  ElementType type = ElementType::Tetrahedron;
  std::size_t n_cells = 0;
  double min_quality = 0.0;
  double min_shape_quality = 0.0;
  double min_scaled_jacobian = 0.0;
};

/// Mesh quality summary and per-cell values (DESIGN §3.3 names). "Not available" values
/// (no input mesh, no cells) are NaN; a JSON writer emits them as null. Per-cell arrays
/// follow the global cell order (blocks of Mesh::cells concatenated, as Topology does) and
/// are meant as .vtu cell data under the names kQualityField, kShapeQualityField and
/// kScaledJacobianField.
struct QualityReport {
  std::size_t n_cells = 0;
  /// Cells with min_jacobian_det ≤ 0 over validity_samples, or non-finite coordinates.
  std::size_t inverted_elements = 0;
  /// Injectivity (DESIGN §2, fem/orientation.h): the cells listed mirrored against the
  /// mesh's orientation (global indices, ascending), whether no orientation fits the cells at
  /// all, and the cells' signed volumes added up against the volume the boundary encloses.
  std::vector<std::int32_t> flipped_cells;
  bool twisted = false;
  double cell_volume = 0.0;
  double enclosed_volume = 0.0;
  /// Pairs of boundary pieces that cross, and the first pair's facets (Topology numbering).
  std::size_t boundary_crossings = 0;
  std::array<std::int32_t, 2> crossing_facets{-1, -1};
  /// The cells overlap: a flipped cell, a twisted mesh, volumes that do not add up, or a
  /// boundary that passes through itself.
  bool overlapping = false;
  /// Every cell positive and no overlap: the map is injective (DESIGN §2).
  bool valid() const { return inverted_elements == 0 && !overlapping; }
  bool has_input = false;  ///< whether `quality` is against an input mesh
  /// q_e = 1/η_e against the input mesh (paper 000 eq. 9; 1 = undistorted, 0 = inverted).
  double min_quality = 0.0;
  double mean_quality = 0.0;
  /// The same measure against the ideal element (regular simplex / square / cube).
  double min_shape_quality = 0.0;
  double mean_shape_quality = 0.0;
  /// Verdict's scaled Jacobian (linear cells) or its sampled minimum (curved cells);
  /// minimum over the cells whose value is a number (non-finite cells count as inverted).
  double min_scaled_jacobian = 0.0;
  /// Counts of q_e in 10 bins [k/10, (k+1)/10) on [0, 1], the last bin closed (quality_bin):
  /// `quality_histogram` of `quality` (all zero without input), `shape_histogram` of
  /// `shape_quality`.
  std::array<std::size_t, 10> quality_histogram{};
  std::array<std::size_t, 10> shape_histogram{};
  /// One entry per cell type of the mesh, in ElementType order.
  std::vector<CellTypeQuality> by_type;
  std::vector<double> quality;          ///< per cell, against the input (empty without input)
  std::vector<double> shape_quality;    ///< per cell, against the ideal element
  std::vector<double> scaled_jacobian;  ///< per cell (NaN for non-finite coordinates)
};

inline constexpr std::string_view kQualityField = "quality";
inline constexpr std::string_view kShapeQualityField = "shape_quality";
inline constexpr std::string_view kScaledJacobianField = "scaled_jacobian";

/// Measures every cell of `current`; against `input` too when it is given, which must have
/// the same dimension, node count and cell blocks (types, orders, connectivity sizes) —
/// otherwise std::invalid_argument. Parallel over cells (OpenMP); the result does not
/// depend on the thread count.
QualityReport quality_report(const Mesh& current, const Mesh* input = nullptr);

/// The histogram bin of a quality value: min(9, ⌊10 q⌋), values below 0 (and NaN) in bin 0.
std::size_t quality_bin(double q);

}  // namespace meshmorph
