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

/// What untangle does with the boundary nodes that no case entry names, and with `project`
/// groups (options "boundary" and "feature_angle", docs/untangle.md, Boundary).
struct UntangleBoundary {
  /// "fixed", "slide" (along the input's own boundary facets; `project` groups along their
  /// level sets) or "auto" (fixed unless the boundary must move); empty: "auto" for a case
  /// without boundary entries (a bare mesh), "fixed" otherwise.
  std::string mode;
  double feature_angle = 30.0;  ///< degrees: sliding patches split where the normals turn more
};

/// Reads the "options" of an untangle case (docs/untangle.md, Options) for `meshmorph
/// untangle` and the Python module's Untangler, with `threads` OpenMP threads. `file` names the
/// case in messages. UntangleOptions::reference is chosen by resolve_untangle_reference.
/// Throws InputError naming the file and the key.
UntangleOptions read_untangle_options(const nlohmann::json& options, const std::string& file, int threads,
                                      std::optional<UntangleReference>& reference, UntangleBoundary& boundary);

/// Sets o.reference: the one the case names, else input for a valid input mesh and regular
/// for one with `input_inverted` inverted cells. Throws InputError (prefixed `where`) when the
/// case names input for an inverted mesh.
void resolve_untangle_reference(UntangleOptions& o, const std::optional<UntangleReference>& named,
                                std::size_t input_inverted, const std::string& where);

/// The report's "history" rows of one Untangler::solve (docs/untangle.md, Report).
std::vector<HistoryRow> untangle_history(const UntangleResult& r);

/// The case runner of `meshmorph untangle` and of the Python module's untangle() and
/// Untangler (paper 001): a case set up on its mesh, which may be tangled, then solved as a
/// whole (run) or solve by solve (solve). The boundary nodes no entry names stay where they
/// are or slide along the input's own boundary (UntangleBoundary): in "auto" (the default of
/// a case without "boundary", `meshmorph untangle MESH`) they slide from the start where an
/// inverted cell has all its corners on the boundary (boundary_bound_inverted), and run()
/// starts over with them sliding where the fixed boundary leaves the mesh tangled. Where the
/// case moves no boundary node and has one step, sliding starts in patches around the
/// inverted cells (untangle_locally), the rest of the mesh untouched, and takes the whole
/// mesh only where they stay tangled.
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
  /// Whether boundary nodes slide (now: "auto" may turn it on in run()).
  bool sliding() const { return sliding_; }

 private:
  RunOutput finish(RunOutput out, const BoundaryTargets& bc) const;
  // The Untangler, with the boundary sliding or not; x_ back at the input.
  void start(bool slide);
  RunOutput run_steps(const StepSink& on_step);
  // untangle_locally in patches of growing size; the first that ends valid, or the last.
  RunOutput run_local();

  std::string where_;
  UntangleOptions options_;
  UntangleBoundary boundary_;
  std::vector<std::uint8_t> may_slide_;  // per node: a boundary node no entry names
  std::vector<FitTerm> surfaces_;     // where the boundary slides: facets of the input, case level sets
  bool facet_surfaces_ = false;       // surfaces_ holds the input's facets (built when first needed)
  BoundaryTargets bc_;                // the motion's, with the nodes of surfaces_ free
  bool sliding_ = false;
  bool local_ = false;                // "auto" on a bare repair: a patch around the inverted cells first
  std::string boundary_why_;          // why the boundary slides or not (the report's "boundary_choice")
  Mesh input_;
  std::size_t input_inverted_ = 0;
  std::vector<std::uint8_t> input_invalid_;  ///< invalid_cells(input_): the patches start from them
  Topology topology_;
  std::unique_ptr<BoundaryMotion> motion_;  // points to input_ and topology_
  std::unique_ptr<Untangler> untangler_;
  Eigen::MatrixXd x_;
  int steps_ = 1;
  int solves_ = 0;
};

}  // namespace meshmorph
