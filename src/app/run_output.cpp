// SPDX-License-Identifier: MIT
#include "meshmorph/app/run_output.h"

namespace meshmorph {

nlohmann::ordered_json RunOutput::json() const { return report_json(report, extra); }

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace meshmorph
