// SPDX-License-Identifier: MIT
#pragma once
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "cli/detail/output_files.h"
#include "meshmorph/app/case_file.h"
#include "meshmorph/app/run_output.h"
#include "meshmorph/mesh/mesh.h"

namespace meshmorph::detail {

/// The meshes a morph, untangle or deform writes, as an ALE solver reads them (docs/cli.md,
/// "Time series"): each carries point data `displacement` (from the input) and, where the case
/// gives `dt`, `mesh_velocity` (from the increment before, the input before the first), and
/// cell data `quality` and `shape_quality`. With `output_each_step` and a .vtu output, OUT.pvd
/// lists the increments and the result at their times (step · dt, or the step number); with a
/// .cgns or .exo output, the increments and the result are the time steps of that one file
/// (write_mesh_series), written where the goal is reached: the increments' positions and
/// cell quality are kept until then (8 · dim bytes a node and 16 a cell, per increment).
class SeriesOutput {
 public:
  SeriesOutput(const Mesh& input, const CaseFile* c, const RunFiles& files);
  /// Increment `step` of the series, not the last: written (or, for one file, kept) with
  /// `output_each_step`, and remembered for the next increment's velocity.
  void step(int step, const Mesh& mesh);
  /// The run's mesh with its fields (where the goal was reached; for one file, with the
  /// increments before it), its report, then the .pvd.
  void finish(RunOutput& run, const RunTimings& timings);
  /// How many increment files were written.
  int step_files() const { return static_cast<int>(written_.size()); }

 private:
  // An increment of a one-file series, until the file is written.
  struct Kept {
    int step;
    Eigen::MatrixXd x;
    std::map<std::string, std::vector<double>> cell_data;
  };

  // displacement = x − input, and with dt, mesh_velocity = (x − previous)/dt.
  std::map<std::string, Eigen::MatrixXd> fields(const Eigen::MatrixXd& x, const Eigen::MatrixXd& previous) const;
  double time_of(int step) const { return dt_ ? step * *dt_ : static_cast<double>(step); }
  void write_one_file(const RunOutput& run) const;

  const Mesh& input_;
  std::optional<double> dt_;
  bool each_step_ = false;
  bool one_file_ = false;  // a .cgns/.exo output with output_each_step
  RunFiles files_;
  Eigen::MatrixXd previous_;  // the last increment's positions
  int last_step_ = 0;
  std::vector<std::pair<int, std::filesystem::path>> written_;  // (step, file)
  std::vector<Kept> kept_;
};

/// OUT.pvd for a .vtu output, else none: the collection file of a VTU series.
std::optional<std::filesystem::path> series_path(const std::filesystem::path& output);

}  // namespace meshmorph::detail
