// SPDX-License-Identifier: MIT
#pragma once
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "meshmorph/app/case_file.h"
#include "meshmorph/app/report.h"
#include "meshmorph/methods/baselines.h"
#include "meshmorph/methods/morph.h"

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

}  // namespace meshmorph
