// SPDX-License-Identifier: MIT
#pragma once
#include <cstddef>
#include <string>
#include <vector>

#include "meshmorph/app/case_file.h"
#include "meshmorph/app/run_output.h"
#include "meshmorph/methods/optimize.h"
#include "meshmorph/methods/optimize_boundary.h"
#include "meshmorph/mesh/topology.h"

namespace meshmorph {

/// Settings that the command line's flags give over the case's options (empty: not given).
struct OptimizeFlags {
  std::string metric, target, boundary, solver;
};

/// What the "options" of an optimize case choose (docs/optimize.md, Options).
struct OptimizeSettings {
  OptimizeOptions options;
  std::string boundary = "fixed";  ///< what happens to boundary nodes that no case entry names
  double feature_angle = 30.0;     ///< degrees: sliding patches split where the normals turn more
};

/// Reads c.options, then `flags` over them, for a mesh of dimension `dim`, with `threads`
/// OpenMP threads. Throws InputError naming the case file and the key.
OptimizeSettings read_optimize_settings(const CaseFile& c, const OptimizeFlags& flags, int dim, int threads);

/// The case runner of `meshmorph optimize` and of the Python module's optimize(): TMOP mesh
/// optimization (paper 003 §2.2) with a fixed or sliding boundary; a tangled input is
/// untangled first.
class OptimizeRunner {
 public:
  /// Rejects keys optimize does not use, checks the case against `mesh`, reads its options
  /// (`flags` over them), elevates the mesh to the case's order and builds the constraints
  /// (optimize_constraints). A case without "boundary" treats the boundary as
  /// options.boundary says. Throws InputError naming the case file.
  OptimizeRunner(const CaseFile& c, Mesh mesh, int threads, const OptimizeFlags& flags = {});

  const Mesh& input() const { return input_; }
  /// The case file (or bare mesh) that messages name.
  const std::string& where() const { return where_; }
  const OptimizeSettings& settings() const { return settings_; }
  /// The OpenMP threads of the run: those asked for, or optimize_threads' choice for 0.
  int threads() const { return threads_; }
  std::size_t initial_inverted() const { return initial_inverted_; }
  const OptimizeConstraints& constraints() const { return constraints_; }
  const Topology& topology() const { return topology_; }

  /// The starting coordinates (d × n): the input's, untangled where it was tangled.
  const Eigen::MatrixXd& start() const { return start_; }

  /// The optimization, on threads() threads (restored when it returns).
  RunOutput run() const;
  /// The run's output (report, moved mesh, figures) for the result `r` of an optimization
  /// from start() that ended at `x` (d × n): run()'s, or the distributed run's.
  RunOutput output(const OptimizeResult& r, const Eigen::MatrixXd& x) const;

 private:
  std::string where_;
  OptimizeSettings settings_;
  int threads_ = 0;
  Mesh input_;
  Topology topology_;
  std::size_t initial_inverted_ = 0;
  Eigen::MatrixXd start_;  // d × n: the input, untangled where tangled, with project nodes on their level sets
  long long untangle_newton_ = 0;
  OptimizeConstraints constraints_;
};

}  // namespace meshmorph
