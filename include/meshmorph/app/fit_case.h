// SPDX-License-Identifier: MIT
#pragma once
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "meshmorph/app/case_file.h"
#include "meshmorph/app/report.h"
#include "meshmorph/app/run_output.h"
#include "meshmorph/methods/fit.h"
#include "meshmorph/methods/fit_features.h"
#include "meshmorph/mesh/mesh.h"
#include "meshmorph/mesh/topology.h"
#include "meshmorph/quality/quality_report.h"

namespace meshmorph {

/// What the "options" of a fit case choose (docs/fit.md, Options).
struct FitSettings {
  FitOptions fit;
  bool split = true;
  /// σ sampled at the nodes of the (elevated) input mesh and interpolated with its basis, as
  /// in paper 003 §4.1 (x_B = x), instead of evaluated exactly.
  bool discrete = false;
  /// A volume group whose cells are material 1 (the others 0): the interface is taken as
  /// given, in place of eq. 10–12.
  std::string materials;
  /// "auto", "true" or "false" (docs/fit.md, Pillowing).
  std::string pillow = "auto";
  /// Sharp features of a CSG surface followed (docs/fit.md, Sharp features).
  bool features = true;
  /// Whether the case sets the target and eps_sigma; fit picks them otherwise (Choices).
  bool target_given = false, eps_sigma_given = false;
};

/// Reads c.options for `meshmorph fit` and the Python module's fit(), with `threads` OpenMP
/// threads. Throws InputError naming the case file and the key.
FitSettings read_fit_settings(const CaseFile& c, int threads);

/// A fit case set up on its mesh (docs/fit.md): the mesh trimmed, split and elevated as the
/// case asks, its topology, the level-set terms with the nodes each fits, and the fixed DOFs.
struct FitSetup {
  Mesh mesh;
  Topology topology;
  /// The case's level sets with the nodes each fits; after them, one term per piece of a
  /// sharp CSG with the feature nodes that follow it (docs/fit.md, Sharp features).
  std::vector<FitTerm> terms;
  std::size_t surface_terms = 0;  ///< terms[0, surface_terms): the case's level sets
  /// The features of each fitted CSG surface, with its pieces.
  struct Features {
    FitFeatures found;
    std::vector<LevelSetFunction> pieces;
  };
  std::vector<Features> features;
  std::vector<std::uint8_t> fixed;  ///< d per node
  std::size_t split_cells = 0, two_facet_cells = 0, pillowed_cells = 0;
  /// The settings' fit options with fit's own picks filled in (target, eps_sigma).
  FitOptions fit;
  /// What fit picked where the case left it open, and why (docs/fit.md, Choices).
  nlohmann::ordered_json choices = nlohmann::ordered_json::object();
};

/// Sets the case up on `mesh` (valid, checked against the case): every level set must cover
/// the mesh, be a number at its nodes and cross it, and leave nodes to fit. Throws InputError
/// whose message starts with `where` (the case file) otherwise.
FitSetup prepare_fit(const CaseFile& c, Mesh mesh, const FitSettings& settings, const std::string& where);

/// The case runner of `meshmorph fit` and of the Python module's fit() (paper 003).
class FitRunner {
 public:
  /// Rejects keys fit does not use, checks the case against `mesh` (which must be valid),
  /// reads its options and sets it up (prepare_fit). Throws InputError naming the case file.
  FitRunner(const CaseFile& c, Mesh mesh, int threads);

  const FitSetup& setup() const { return setup_; }
  const FitSettings& settings() const { return settings_; }
  /// The fit: its report (DESIGN §3.3) and the members that follow it (docs/fit.md,
  /// Report), the fitted mesh and its quality.
  RunOutput run() const;

 private:
  FitSettings settings_;
  FitSetup setup_;
};

}  // namespace meshmorph
