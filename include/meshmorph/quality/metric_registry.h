// SPDX-License-Identifier: MIT
#pragma once
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "meshmorph/quality/metric.h"

namespace meshmorph {

/// Named numeric parameters of a metric, e.g. {"gamma": 0.3} for mu80 or {"delta": 1e-3,
/// "n": -1} for edge_quality. Missing parameters take their paper defaults.
using MetricParams = std::map<std::string, double, std::less<>>;

/// Registry keys of the metrics available in dimension d (2 or 3), in a fixed order:
/// "distortion", "distortion2", "mu2" (2D) / "mu303" (3D), "mu77", "mu80", "edge_quality".
std::vector<std::string> metric_names(int d);

/// The TMOP shape metric of dimension d that optimize and fit take by default: "mu2" (2D),
/// "mu303" (3D).
inline const char* default_shape_metric(int d) { return d == 2 ? "mu2" : "mu303"; }

/// Parameter names a metric accepts (empty for most); throws InputError for an unknown name.
std::vector<std::string> metric_parameter_names(std::string_view name);

/// Builds the metric `name` of dimension d. Parameters: mu80 "gamma" (default 0.5);
/// edge_quality "delta" (0) and "n" (−1). Throws InputError naming the metric and the key
/// for an unknown metric, an unknown parameter or an out-of-range value (the caller adds
/// the file and the key path of its case file).
template <int d>
std::unique_ptr<Metric<d>> make_metric(std::string_view name, const MetricParams& params = {});

extern template std::unique_ptr<Metric<2>> make_metric<2>(std::string_view, const MetricParams&);
extern template std::unique_ptr<Metric<3>> make_metric<3>(std::string_view, const MetricParams&);

}  // namespace meshmorph
