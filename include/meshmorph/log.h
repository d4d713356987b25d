// SPDX-License-Identifier: MIT
#pragma once
#include <cstdio>
#include <functional>
#include <mutex>
#include <string>
#include <string_view>
#include <utility>

namespace meshmorph {

/// Severity of a log message, most important first. Progress lines (one per iteration or
/// phase) sit between Info and Detail so that a quiet sink can keep Info and drop them.
enum class LogLevel { Error, Warning, Info, Progress, Detail };

/// Receives every message the library emits. The library never prints: without a sink
/// (the default) messages are dropped. Called under a lock, so a sink needs no locking of
/// its own, but it must not log itself.
using LogSink = std::function<void(LogLevel, std::string_view)>;

namespace detail {
struct LogState {
  std::mutex mutex;
  LogSink sink;
  LogLevel max_level = LogLevel::Info;
};
inline LogState& log_state() {
  static LogState state;
  return state;
}
}  // namespace detail

/// Installs `sink` (an empty function silences the library) and the most detailed level it
/// receives; messages above `max_level` are dropped before they are formatted by callers
/// that test log_enabled().
inline void set_log_sink(LogSink sink, LogLevel max_level = LogLevel::Info) {
  auto& s = detail::log_state();
  std::lock_guard lock(s.mutex);
  s.sink = std::move(sink);
  s.max_level = max_level;
}

/// True when a message of `level` would reach a sink (lets callers skip formatting).
inline bool log_enabled(LogLevel level) {
  auto& s = detail::log_state();
  std::lock_guard lock(s.mutex);
  return s.sink && level <= s.max_level;
}

/// Sends one message (no trailing newline) to the installed sink, if any. Thread-safe.
inline void log_message(LogLevel level, std::string_view message) {
  auto& s = detail::log_state();
  std::lock_guard lock(s.mutex);
  if (s.sink && level <= s.max_level) s.sink(level, message);
}

inline void log_warning(std::string_view message) { log_message(LogLevel::Warning, message); }
inline void log_info(std::string_view message) { log_message(LogLevel::Info, message); }
inline void log_progress(std::string_view message) { log_message(LogLevel::Progress, message); }
inline void log_detail(std::string_view message) { log_message(LogLevel::Detail, message); }

/// printf-style formatting of progress and result messages (at most 240 characters).
template <class... Args>
std::string format(const char* pattern, Args... args) {
  char buffer[240];
  std::snprintf(buffer, sizeof buffer, pattern, args...);
  return buffer;
}

}  // namespace meshmorph
