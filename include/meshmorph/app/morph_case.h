// SPDX-License-Identifier: MIT
#pragma once
#include <memory>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <nlohmann/json.hpp>

#include "meshmorph/methods/boundary_motion.h"
#include "meshmorph/app/case_file.h"
#include "meshmorph/app/report.h"
#include "meshmorph/app/run_output.h"
#include "meshmorph/methods/baselines.h"
#include "meshmorph/methods/morph.h"
#include "meshmorph/mesh/topology.h"

namespace meshmorph {

/// What the "options" of a morph case choose (docs/morph.md, Options): the method and the
/// settings of each.
struct MorphSettings {
  std::string method = "morph";  ///< "morph", "laplace" or "elastic"
  MorphOptions morph;
  BaselineOptions baseline;
};

/// Reads c.options for `meshmorph morph` and the Python module's Morpher, with `threads`
/// OpenMP threads (0: the OpenMP default). Throws InputError naming the case file and the key
/// for unknown keys, wrong types and values out of range.
MorphSettings read_morph_settings(const CaseFile& c, int threads);

/// The report's "history" rows of one Morpher::solve (docs/morph.md, Report), one per
/// augmented-Lagrangian iteration.
std::vector<HistoryRow> morph_history(const MorphResult& r);

/// The report's "untangle_passes" entry of a solve that finished by an untangle pass
/// (MorphResult::finish) at time step `step`.
nlohmann::ordered_json untangle_pass(const MorphResult::Finish& f, int step);

/// The morph output with the figures the command line prints beside the report.
struct MorphOutput : RunOutput {
  long long krylov = 0;  ///< CG iterations, also those preconditioned by a Cholesky factor
};

/// The case runner of `meshmorph morph` and of the Python module's morph() and Morpher: a
/// case set up on its mesh, then solved as a whole (run) or solve by solve (solve).
class MorphRunner {
 public:
  /// Rejects keys morph does not use, checks the case against `mesh`, reads its options,
  /// elevates the mesh to the case's order and resolves the boundary. Throws InputError
  /// naming the case file (or, for a case read from a file, the mesh) and what is wrong: an
  /// inverted input cell, a bad option or motion.
  MorphRunner(const CaseFile& c, Mesh mesh, int threads);
  ~MorphRunner();
  MorphRunner(const MorphRunner&) = delete;
  MorphRunner& operator=(const MorphRunner&) = delete;

  const Mesh& input() const { return input_; }
  const MorphSettings& settings() const { return settings_; }
  const BoundaryMotion& motion() const { return *motion_; }

  /// The case's run: `steps` solves along the motion, each from where the last ended, and
  /// `on_step` after each but the last (docs/morph.md, Time series; the baselines solve once
  /// per increment on the mesh the last one left and stop at one that inverts a cell). A
  /// morph whose result fails the checks of the report (inverted between the samples, or
  /// overlapping) ends on the mesh its last solve started from where that passes them, else
  /// on the input.
  MorphOutput run(const StepSink& on_step = {});

  /// One solve towards `target` (d × n: positions of the prescribed nodes) from where the
  /// last solve ended, with the multipliers, penalty and weights it left (paper 000 §5.5):
  /// the report of that solve alone, its boundary error measured against `target`. Only for
  /// options.method "morph".
  MorphOutput solve(const Eigen::MatrixXd& target);

 private:
  struct Progress;
  bool advance(const Eigen::MatrixXd& target, int step, bool label, Progress& p, MorphOutput& out);
  MorphOutput finish(MorphOutput out, const Progress& p, const BoundaryTargets& bc) const;
  MorphOutput keep_valid(MorphOutput out, const Eigen::MatrixXd& before, const Progress& p, const BoundaryTargets& bc);

  std::string where_;
  MorphSettings settings_;
  Mesh input_;
  Topology topology_;
  std::unique_ptr<BoundaryMotion> motion_;  // points to input_
  std::unique_ptr<Morpher> morpher_;        // options.method "morph"
  Eigen::MatrixXd x_;
  int steps_ = 1;
  int solves_ = 0;
};

}  // namespace meshmorph
