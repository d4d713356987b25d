// SPDX-License-Identifier: MIT
#include "meshmorph/quality/metric_registry.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "meshmorph/error.h"
#include "meshmorph/quality/distortion.h"
#include "meshmorph/quality/edge_quality.h"
#include "meshmorph/quality/tmop_shape.h"
#include "meshmorph/quality/tmop_shape_size.h"

namespace meshmorph {
namespace {

std::string joined(const std::vector<std::string>& names) {
  std::string s;
  for (const auto& n : names) s += (s.empty() ? "" : ", ") + n;
  return s.empty() ? "none" : s;
}

// The value of parameter `key` (or `fallback`), after checking that every given key is known.
double param(std::string_view metric, const MetricParams& params, const std::string& key, double fallback) {
  const auto known = metric_parameter_names(metric);
  for (const auto& [k, v] : params) {
    if (std::find(known.begin(), known.end(), k) == known.end()) {
      throw InputError("metric '" + std::string(metric) + "': unknown parameter '" + k +
                       "' (parameters: " + joined(known) + ")");
    }
    if (!std::isfinite(v)) {
      throw InputError("metric '" + std::string(metric) + "': parameter '" + k + "' is not finite");
    }
  }
  const auto it = params.find(key);
  return it == params.end() ? fallback : it->second;
}

void require(bool ok, std::string_view metric, const std::string& key, const std::string& what) {
  if (!ok) throw InputError("metric '" + std::string(metric) + "': parameter '" + key + "' " + what);
}

}  // namespace

std::vector<std::string> metric_names(int d) {
  MESHMORPH_CHECK(d == 2 || d == 3, "metric_names: dimension must be 2 or 3");
  return {"distortion", "distortion2", default_shape_metric(d), "mu77", "mu80", "edge_quality"};
}

std::vector<std::string> metric_parameter_names(std::string_view name) {
  if (name == "mu80") return {"gamma"};
  if (name == "edge_quality") return {"delta", "n"};
  if (name == "distortion" || name == "distortion2" || name == "mu2" || name == "mu303" || name == "mu77") return {};
  throw InputError("unknown metric '" + std::string(name) + "' (metrics: distortion, distortion2, mu2, mu303, mu77, mu80, edge_quality)");
}

template <int d>
std::unique_ptr<Metric<d>> make_metric(std::string_view name, const MetricParams& params) {
  const auto names = metric_names(d);
  if (std::find(names.begin(), names.end(), name) == names.end()) {
    throw InputError("unknown metric '" + std::string(name) + "' in " + std::to_string(d) + "D (metrics: " + joined(names) + ")");
  }
  if (name == "mu80") {
    const double gamma = param(name, params, "gamma", 0.5);
    require(gamma >= 0.0 && gamma <= 1.0, name, "gamma", "must lie in [0, 1]");
    return std::make_unique<TmopMu80<d>>(gamma);
  }
  if (name == "edge_quality") {
    EdgeQualityOptions o;
    o.delta = param(name, params, "delta", o.delta);
    o.n = param(name, params, "n", o.n);
    require(o.delta >= 0.0, name, "delta", "must be >= 0");
    require(o.n < 0.0, name, "n", "must be < 0");
    return std::make_unique<EdgeQuality<d>>(o);
  }
  param(name, params, "", 0.0);  // rejects any parameter: these metrics have none
  if (name == "distortion") return std::make_unique<Distortion<d>>();
  if (name == "distortion2") return std::make_unique<DistortionSquared<d>>();
  if (name == "mu77") return std::make_unique<TmopMu77<d>>();
  if constexpr (d == 2) {
    return std::make_unique<TmopMu2>();  // the only name left in 2D
  } else {
    return std::make_unique<TmopMu303>();
  }
}

template std::unique_ptr<Metric<2>> make_metric<2>(std::string_view, const MetricParams&);
template std::unique_ptr<Metric<3>> make_metric<3>(std::string_view, const MetricParams&);

}  // namespace meshmorph
