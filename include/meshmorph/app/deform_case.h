// SPDX-License-Identifier: MIT
#pragma once
#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

#include "meshmorph/methods/boundary_motion.h"
#include "meshmorph/app/case_file.h"
#include "meshmorph/app/run_output.h"
#include "meshmorph/methods/deform.h"
#include "meshmorph/methods/design_targets.h"
#include "meshmorph/mesh/topology.h"

namespace meshmorph {

/// Reads the "options" of a deform case (docs/deform.md, Options) with `threads` OpenMP
/// threads. Throws InputError naming the case file and the key.
DeformOptions read_deform_options(const CaseFile& c, int threads);

/// The deform output with the figure the command line prints beside the report.
struct DeformOutput : RunOutput {
  std::size_t design_nodes = 0;
};

/// The case runner of `meshmorph deform` and of the Python module's deform() (paper 004).
class DeformRunner {
 public:
  /// Rejects keys deform does not use, checks the case against `mesh` (which must be valid),
  /// reads its options, elevates the mesh to the case's order and resolves the boundary,
  /// which must move a design group. Throws InputError naming the case file.
  DeformRunner(const CaseFile& c, Mesh mesh, int threads);
  ~DeformRunner();
  DeformRunner(const DeformRunner&) = delete;
  DeformRunner& operator=(const DeformRunner&) = delete;

  const Mesh& input() const { return input_; }
  const DeformOptions& options() const { return options_; }

  /// The case's run: `steps` deformation updates along the motion, each from the last, and
  /// `on_step` after each but the last.
  DeformOutput run(const StepSink& on_step = {}) const;

 private:
  std::string where_;
  DeformOptions options_;
  Mesh input_;
  Topology topology_;
  std::unique_ptr<BoundaryMotion> motion_;  // points to input_ and topology_
  ExactDesignTargets exact_;
  std::vector<std::uint8_t> on_design_;
  DesignSurface surface_;
  int steps_ = 1;
};

}  // namespace meshmorph
