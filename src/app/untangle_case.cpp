// SPDX-License-Identifier: MIT
#include "meshmorph/app/untangle_case.h"

#include "app/detail/solver_option.h"
#include "meshmorph/app/option_reader.h"
#include "meshmorph/error.h"

namespace meshmorph {

UntangleOptions read_untangle_options(const nlohmann::json& options, const std::string& file, int threads,
                                      std::optional<UntangleReference>& reference, UntangleBoundary& boundary) {
  UntangleOptions o;
  o.certify = true;
  OptionReader r(options, file);
  r.read("n", o.n, -16.0, -1e-3);
  r.read("h_min", o.h_min, 1e-3, 1.0 - 1e-3);
  r.read("eps_delta", o.eps_delta, 1e-300, 1.0);
  r.read("alpha", o.alpha, 0.0, 1.0);
  r.read("beta", o.beta, 0.0, 1.0 - 1e-12);
  r.read("eps_q", o.eps_q, 0.0, 1.0);
  r.read("gamma_untangle", o.gamma_untangle, 0.0, 1.0);
  r.read("gamma_smooth", o.gamma_smooth, 0.0, 1.0);
  if (r.has("reference")) {
    std::string ref;
    r.read("reference", ref, {"input", "regular"});
    reference = ref == "input" ? UntangleReference::Input : UntangleReference::Regular;
  }
  std::string rule = "continuation";
  r.read("delta_rule", rule, {"continuation", "paper"});
  o.delta_rule = rule == "paper" ? DeltaRule::Paper : DeltaRule::Continuation;
  r.read("predictor", o.predictor);
  r.read("max_newton", o.max_newton, 1, 100000);
  o.solver = detail::read_solver(r);
  if (r.has("boundary")) r.read("boundary", boundary.mode, {"fixed", "slide", "auto"});
  r.read("feature_angle", boundary.feature_angle, 0.0, 180.0);
  r.finish();
  o.threads = threads;
  return o;
}

void resolve_untangle_reference(UntangleOptions& o, const std::optional<UntangleReference>& named,
                                std::size_t input_inverted, const std::string& where) {
  if (named == UntangleReference::Input && input_inverted > 0)
    throw InputError(where + ": options.reference: \"input\" needs a valid input mesh, and " +
                     std::to_string(input_inverted) + " cells of it are inverted (\"regular\" untangles it)");
  o.reference = named.value_or(input_inverted > 0 ? UntangleReference::Regular : UntangleReference::Input);
}

std::vector<HistoryRow> untangle_history(const UntangleResult& r) {
  std::vector<HistoryRow> rows;
  for (const UntangleIteration& h : r.history)
    rows.push_back({{"step", h.step}, {"newton", h.newton}, {"delta", h.delta}, {"alpha", h.alpha},
                    {"min_quality", h.min_quality}, {"inverted", static_cast<double>(h.inverted)}});
  return rows;
}

}  // namespace meshmorph
