// SPDX-License-Identifier: MIT
#pragma once
#include <cstddef>
#include <filesystem>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "meshmorph/timings.h"

namespace meshmorph {

/// Iteration counts of a method run (DESIGN §3.3 "iterations").
struct IterationCounts {
  long long outer = 0;      ///< augmented-Lagrangian / continuation steps
  long long nonlinear = 0;  ///< nonlinear solves
  long long newton = 0;     ///< Newton steps
  long long linear = 0;     ///< linear solves (or Krylov iterations)
  bool operator==(const IterationCounts&) const = default;
};

/// The minima over the cells of one type (JSON "cell_types": {"prism": {...}, ...}).
struct CellTypeMinima {
  std::string type;  ///< "tetrahedron", "prism", ... (mesh/element_type.h, name_of)
  std::size_t elements = 0;
  std::optional<double> min_quality;  ///< against the input mesh
  std::optional<double> min_shape_quality;
  std::optional<double> min_scaled_jacobian;
  bool operator==(const CellTypeMinima&) const = default;
};

/// One row of "history": named values in the order given, written as a JSON object.
using HistoryRow = std::vector<std::pair<std::string, double>>;

/// The report every method writes (DESIGN §3.3), field for field. Optional fields are
/// written as null when not applicable.
struct Report {
  std::string meshmorph_version;          ///< filled by write_report when empty
  std::string method;                     ///< "morph", "untangle", "fit", "deform", "quality"
  std::optional<std::string> case_file;   ///< JSON key "case": the case file, as given
  int dim = 0;
  int order = 1;
  std::size_t nodes = 0;
  std::size_t elements = 0;
  bool valid = false;
  std::size_t inverted_elements = 0;
  /// Cells listed mirrored against their neighbours, which fold the mesh over itself, and the
  /// cells' volumes added up against the volume the boundary encloses (DESIGN §2: valid means
  /// injective), and where the boundary passes through itself. Reports written without them
  /// read back as 0 and empty.
  std::size_t flipped_elements = 0;
  std::size_t boundary_crossings = 0;  ///< pairs of boundary pieces that cross
  std::optional<double> cell_volume;
  std::optional<double> enclosed_volume;
  std::optional<double> min_quality;          ///< q_e = 1/η_e against the input mesh
  std::optional<double> mean_quality;
  std::optional<double> min_shape_quality;    ///< the same against the ideal element
  std::optional<double> min_scaled_jacobian;  ///< Verdict's scaled Jacobian
  std::optional<double> boundary_error_max;
  std::optional<double> boundary_error_l2;
  std::optional<double> fit_error_max;        ///< fit only
  std::optional<IterationCounts> iterations;
  double seconds = 0;
  std::optional<double> peak_memory_mb;       ///< filled by write_report when empty
  bool converged = false;
  std::string message;
  std::vector<HistoryRow> history;
  /// Seconds per phase (JSON "timings", after "history"); reports written without them read
  /// back as none.
  std::optional<Timings> timings;
  /// min_quality, min_shape_quality and min_scaled_jacobian per cell type, in the quality
  /// report's order (JSON "cell_types", after "timings"; written when not empty). Reports
  /// written without them read back as empty.
  std::vector<CellTypeMinima> cell_types;

  bool operator==(const Report&) const = default;
};

/// Peak resident memory of this process in MiB (getrusage), 0 where unknown.
double peak_memory_mb();

/// The project version ("0.1.0"), from CMake's PROJECT_VERSION.
const char* meshmorph_version();

/// The report as JSON, keys in the documented order; non-finite numbers become null.
nlohmann::ordered_json report_to_json(const Report& report);
/// Parses report_to_json's output back. Throws InputError naming `file` and the key.
Report report_from_json(const nlohmann::ordered_json& j, const std::string& file = "report");

/// The report and `extra` (an object whose members follow "history") as one JSON object, with
/// meshmorph_version and peak_memory_mb filled where they are empty: what write_report writes.
nlohmann::ordered_json report_json(Report report, const nlohmann::ordered_json& extra);

/// Writes the report atomically (io/atomic_file.h), filling meshmorph_version and
/// peak_memory_mb when they are empty; the members of `extra` (an object, e.g. a
/// subcommand's histogram) follow "history". Throws IoError when it cannot be written.
void write_report(const std::filesystem::path& path, Report report,
                  const nlohmann::ordered_json& extra = nlohmann::ordered_json::object());
/// Reads a report written by write_report.
Report read_report(const std::filesystem::path& path);

}  // namespace meshmorph
