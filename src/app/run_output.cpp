// SPDX-License-Identifier: MIT
#include "meshmorph/app/run_output.h"

namespace meshmorph {

nlohmann::ordered_json RunOutput::json() const { return report_json(report, extra); }

void stamp_times(Report& report, const RunTimings& timings) {
  report.timings = timings.totals();
  report.seconds = 0.0;
  for (const double s : report.timings->seconds) report.seconds += s;
}

}  // namespace meshmorph
