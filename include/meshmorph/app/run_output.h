// SPDX-License-Identifier: MIT
#pragma once
#include <functional>

#include <nlohmann/json.hpp>

#include "meshmorph/app/report.h"
#include "meshmorph/mesh/mesh.h"
#include "meshmorph/quality/quality_report.h"
#include "meshmorph/timings.h"

namespace meshmorph {

/// What a case runner returns (DESIGN §1, app): the report of DESIGN §3.3, the members that
/// follow its "history" (the method's own figures, docs/<method>.md, Report), the moved mesh
/// and its per-cell quality. The command line writes them, the Python module returns them.
/// report.case_file, report.seconds, report.timings and report.peak_memory_mb are the caller's to fill.
struct RunOutput {
  Report report;
  nlohmann::ordered_json extra = nlohmann::ordered_json::object();
  Mesh moved;
  QualityReport quality;

  /// The report and its extra members as one JSON object, as write_report writes it (with
  /// meshmorph_version and peak_memory_mb filled where empty).
  nlohmann::ordered_json json() const;
};

/// Called after each increment but the last of a time series (`steps`) with its number and
/// mesh; the command line writes the step files of `output_each_step` there.
using StepSink = std::function<void(int step, const Mesh& mesh)>;

/// Fills report.seconds (the run's seconds so far) and report.timings (those seconds by phase)
/// from the run's clock.
void stamp_times(Report& report, const RunTimings& timings);

}  // namespace meshmorph
