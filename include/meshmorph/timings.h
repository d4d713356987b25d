// SPDX-License-Identifier: MIT
#pragma once
#include <array>
#include <chrono>
#include <string_view>

#include <omp.h>

namespace meshmorph {

/// The phases of a run whose seconds a report lists (DESIGN §3.3 "timings"). Each second of a
/// run counts in exactly one: the innermost phase open on the run's thread, else Other.
enum class Phase { Assembly, Validity, LineSearch, SolverSetup, Solve, Io, Other };
inline constexpr int k_phases = 7;

/// The report's key of a phase.
constexpr std::string_view phase_key(Phase p) {
  constexpr std::array<std::string_view, k_phases> keys = {"assembly", "validity",   "line_search", "solver_setup",
                                                           "solve",    "io",         "other"};
  return keys[static_cast<std::size_t>(p)];
}

/// Seconds per phase of one run.
struct Timings {
  std::array<double, k_phases> seconds{};
  double operator[](Phase p) const { return seconds[static_cast<std::size_t>(p)]; }
  bool operator==(const Timings&) const = default;
};

namespace detail {
struct PhaseClock {
  using clock = std::chrono::steady_clock;
  bool running = false;
  Phase current = Phase::Other;
  clock::time_point mark;
  Timings totals;
  // The time since the last mark goes to the current phase.
  void settle(clock::time_point now) {
    totals.seconds[static_cast<std::size_t>(current)] += std::chrono::duration<double>(now - mark).count();
    mark = now;
  }
};
inline PhaseClock& phase_clock() {
  thread_local PhaseClock clock;
  return clock;
}
}  // namespace detail

/// Times the run made on this thread during its lifetime: phases opened by PhaseTimer on this
/// thread count toward it, time in none of them as Other. A run inside another (a method
/// called by a method) adds to the outer one's timings.
class RunTimings {
 public:
  RunTimings() {
    auto& c = detail::phase_clock();
    owner_ = !c.running;
    if (owner_) c = {true, Phase::Other, detail::PhaseClock::clock::now(), {}};
  }
  ~RunTimings() {
    if (owner_) detail::phase_clock().running = false;
  }
  RunTimings(const RunTimings&) = delete;
  RunTimings& operator=(const RunTimings&) = delete;
  /// The seconds so far.
  Timings totals() const {
    auto& c = detail::phase_clock();
    if (c.running) c.settle(detail::PhaseClock::clock::now());
    return c.totals;
  }

 private:
  bool owner_ = false;
};

/// The time from construction to destruction counts as `phase` (less the phases opened inside
/// it), on a thread that runs a RunTimings and outside parallel regions; elsewhere it does
/// nothing, not even read the clock.
class PhaseTimer {
 public:
  explicit PhaseTimer(Phase phase) {
    auto& c = detail::phase_clock();
    active_ = c.running && !omp_in_parallel();
    if (!active_) return;
    c.settle(detail::PhaseClock::clock::now());
    outer_ = c.current;
    c.current = phase;
  }
  ~PhaseTimer() {
    if (!active_) return;
    auto& c = detail::phase_clock();
    c.settle(detail::PhaseClock::clock::now());
    c.current = outer_;
  }
  PhaseTimer(const PhaseTimer&) = delete;
  PhaseTimer& operator=(const PhaseTimer&) = delete;

 private:
  bool active_ = false;
  Phase outer_ = Phase::Other;
};

}  // namespace meshmorph
