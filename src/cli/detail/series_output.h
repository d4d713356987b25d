// SPDX-License-Identifier: MIT
#pragma once
#include <filesystem>
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
/// lists the increments and the result at their times (step · dt, or the step number).
class SeriesOutput {
 public:
  SeriesOutput(const Mesh& input, const CaseFile* c, const RunFiles& files);
  /// Increment `step` of the series, not the last: written with `output_each_step`, and
  /// remembered for the next increment's velocity.
  void step(int step, const Mesh& mesh);
  /// The run's mesh with its fields (where the goal was reached), its report, then the .pvd.
  void finish(RunOutput& run, const RunTimings& timings);
  /// How many increments were written.
  int step_files() const { return static_cast<int>(written_.size()); }

 private:
  std::map<std::string, Eigen::MatrixXd> fields(const Mesh& mesh) const;

  const Mesh& input_;
  std::optional<double> dt_;
  bool each_step_ = false;
  RunFiles files_;
  Eigen::MatrixXd previous_;  // the last increment's positions
  int last_step_ = 0;
  std::vector<std::pair<int, std::filesystem::path>> written_;  // (step, file)
};

/// OUT.pvd for a .vtu output, else none: the collection file of a VTU series.
std::optional<std::filesystem::path> series_path(const std::filesystem::path& output);

}  // namespace meshmorph::detail
