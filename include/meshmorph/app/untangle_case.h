// SPDX-License-Identifier: MIT
#pragma once
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "meshmorph/app/report.h"
#include "meshmorph/methods/untangle.h"

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

}  // namespace meshmorph
