// SPDX-License-Identifier: MIT
#include "meshmorph/app/morph_case.h"

#include "app/detail/solver_option.h"
#include "meshmorph/app/option_reader.h"

namespace meshmorph {

MorphSettings read_morph_settings(const CaseFile& c, int threads) {
  MorphSettings s;
  OptionReader r(c.options, c.file.string());
  r.read("method", s.method, {"morph", "laplace", "elastic"});
  std::string weights = "adaptive";
  const LinearSolverKind kind = detail::read_solver(r);
  MorphOptions& m = s.morph;
  r.read("tolerance", m.tolerance, 1e-16, 1.0);
  r.read("gradient_tolerance", m.gradient_tolerance, 1e-20, 1.0);
  r.read("eps0", m.eps0, 1e-12, 1.0);
  r.read("delta0", m.delta0, 1e-16, 1.0);
  r.read("penalty0", m.penalty0, 1e-12, 1e12);
  r.read("m0", m.m0, 1.0 + 1e-12, 1e12);
  r.read("m_factor", m.m_factor, 1.0 + 1e-12, 1e12);
  r.read("min_decrease", m.min_decrease, 0.0, 1.0);
  r.read("weights", weights, {"adaptive", "constant"});
  m.adaptive_weights = weights == "adaptive";
  r.read("alpha", m.alpha, 0.0, 100.0);
  r.read("beta", m.beta, 1.0, 100.0);
  std::string growth = "adaptive";
  r.read("weight_growth", growth, {"adaptive", "fixed"});
  m.adaptive_growth = growth == "adaptive";
  r.read("max_weight", m.max_weight, 1.0, 1e300);
  r.read("max_outer", m.max_outer, 1, 10000);
  r.read("max_weight_updates", m.max_weight_updates, 0, 10000);
  r.read("weight_steps", m.weight_steps, 0, 10000);
  r.read("max_newton", m.max_newton, 1, 100000);
  r.read("exact_first", m.exact_first);
  std::string guard = "auto";
  r.read("guard", guard, {"auto", "cells", "ring"});
  m.guard = guard == "ring" ? MorphOptions::Guard::Ring : guard == "cells" ? MorphOptions::Guard::Cells : MorphOptions::Guard::Auto;
  std::string finish = "untangle";
  r.read("finish", finish, {"untangle", "none"});
  m.finish_by_untangle = finish == "untangle";
  r.read("stiffening", s.baseline.stiffening, 0.0, 10.0);
  r.read("poisson_ratio", s.baseline.poisson_ratio, -0.999, 0.499);
  r.finish();
  m.solver = s.baseline.solver = kind;
  m.threads = s.baseline.threads = threads;
  return s;
}

nlohmann::ordered_json untangle_pass(const MorphResult::Finish& f, int step) {
  return {{"step", step},       {"stall", f.stall}, {"boundary_error_max", f.boundary_error_max},
          {"initial_inverted", f.initial_inverted}, {"newton", f.newton}, {"linear", f.linear},
          {"valid", f.valid},   {"message", f.message}};
}

std::vector<HistoryRow> morph_history(const MorphResult& r) {
  std::vector<HistoryRow> rows;
  for (const MorphIteration& h : r.history)
    rows.push_back({{"step", h.step}, {"outer", h.outer}, {"constraint_norm", h.constraint_norm},
                    {"boundary_error_max", h.boundary_error_max}, {"min_quality", h.min_quality}, {"mu", h.mu},
                    {"nonlinear", static_cast<double>(h.nonlinear)}, {"newton", static_cast<double>(h.newton)},
                    {"linear", static_cast<double>(h.linear)}});
  return rows;
}

}  // namespace meshmorph
