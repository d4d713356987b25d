// SPDX-License-Identifier: MIT
#pragma once
#include <cstddef>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "meshmorph/methods/boundary_motion.h"
#include "meshmorph/app/case_file.h"
#include "meshmorph/app/report.h"
#include "meshmorph/app/run_output.h"
#include "meshmorph/methods/untangle.h"
#include "meshmorph/mesh/topology.h"

namespace meshmorph {

/// Reads the "options" of an untangle case (docs/untangle.md, Options) for `meshmorph
/// untangle` and the Python module's Untangler, with `threads` OpenMP threads. `file` names the
/// case in messages. UntangleOptions::reference is chosen by resolve_untangle_reference.
/// Throws InputError naming the file and the key.
UntangleOptions read_untangle_options(const nlohmann::json& options, const std::string& file, int threads,
                                      std::optional<UntangleReference>& reference);

/// Sets o.reference: the one the case names, else input for a valid input mesh and regular
/// for one with `input_inverted` inverted cells. Throws InputError (prefixed `where`) when the
/// case names input for an inverted mesh.
void resolve_untangle_reference(UntangleOptions& o, const std::optional<UntangleReference>& named,
                                std::size_t input_inverted, const std::string& where);

/// The report's "history" rows of one Untangler::solve (docs/untangle.md, Report).
std::vector<HistoryRow> untangle_history(const UntangleResult& r);

/// The case runner of `meshmorph untangle` and of the Python module's untangle() and
/// Untangler (paper 001): a case set up on its mesh, which may be tangled, then solved as a
/// whole (run) or solve by solve (solve). A case without "boundary" keeps every boundary node
/// where it is (`meshmorph untangle MESH`).
class UntangleRunner {
 public:
  /// Rejects keys untangle does not use, checks the case against `mesh`, reads its options,
  /// elevates the mesh to the case's order, chooses the reference and resolves the boundary.
  /// Throws InputError naming the case file and what is wrong.
  UntangleRunner(const CaseFile& c, Mesh mesh, int threads);
  ~UntangleRunner();
  UntangleRunner(const UntangleRunner&) = delete;
  UntangleRunner& operator=(const UntangleRunner&) = delete;

  const Mesh& input() const { return input_; }
  const UntangleOptions& options() const { return options_; }
  const BoundaryMotion& motion() const { return *motion_; }

  /// The case's run: `steps` solves along the motion, each from the last result moved by the
  /// differential predictor, and `on_step` after each but the last.
  RunOutput run(const StepSink& on_step = {});
  /// One solve towards `target` (d × n) from the last result: the report of that solve
  /// alone, its boundary error measured against `target`.
  RunOutput solve(const Eigen::MatrixXd& target);

 private:
  RunOutput finish(RunOutput out, const BoundaryTargets& bc) const;

  std::string where_;
  UntangleOptions options_;
  Mesh input_;
  std::size_t input_inverted_ = 0;
  Topology topology_;
  std::unique_ptr<BoundaryMotion> motion_;  // points to input_ and topology_
  std::unique_ptr<Untangler> untangler_;
  Eigen::MatrixXd x_;
  int steps_ = 1;
  int solves_ = 0;
};

}  // namespace meshmorph
