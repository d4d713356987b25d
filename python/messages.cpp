// SPDX-License-Identifier: MIT
// The library's log sink for the module: lines on stderr at the level set_log_level chose, and
// the progress lines of a call with a progress callback to that callback.
#include "messages.h"

#include <cstdio>
#include <mutex>

#include "meshmorph/error.h"
#include "meshmorph/log.h"

namespace meshmorph {
namespace {

struct Routing {
  std::mutex mutex;
  std::optional<LogLevel> stderr_level;  // none: quiet
  int callbacks = 0;                     // progress scopes alive on any thread
};

Routing& routing() {
  static Routing r;
  return r;
}

thread_local ProgressScope* current_scope = nullptr;

// The sink for the current settings. Without the GIL: the sink runs under the library's log
// lock and takes the GIL for a callback, so whoever holds the GIL must not wait for that lock.
void install(Routing& r) {
  py::gil_scoped_release release;
  std::lock_guard lock(r.mutex);
  const std::optional<LogLevel> shown = r.stderr_level;
  LogLevel max = shown.value_or(LogLevel::Error);
  if (r.callbacks > 0 && max < LogLevel::Progress) max = LogLevel::Progress;
  if (!shown && r.callbacks == 0) return set_log_sink({});
  set_log_sink([shown](LogLevel level, std::string_view message) {
    if (level == LogLevel::Progress && current_scope != nullptr) current_scope->deliver(message);
    if (shown && level <= *shown) std::fprintf(stderr, "meshmorph: %.*s\n", static_cast<int>(message.size()), message.data());
  }, max);
}

}  // namespace

ProgressScope::ProgressScope(py::object callback) : callback_(std::move(callback)), outer_(current_scope) {
  if (callback_.is_none()) return;
  if (!PyCallable_Check(callback_.ptr())) throw InputError("progress: expected a callable or None");
  current_scope = this;
  {
    std::lock_guard lock(routing().mutex);
    ++routing().callbacks;
  }
  install(routing());
}

ProgressScope::~ProgressScope() {
  if (callback_.is_none()) return;
  current_scope = outer_;
  {
    std::lock_guard lock(routing().mutex);
    --routing().callbacks;
  }
  install(routing());
}

void ProgressScope::rethrow() {
  if (error_) {
    py::error_already_set e = std::move(*error_);
    error_.reset();
    throw e;
  }
}

void ProgressScope::deliver(std::string_view message) {
  if (error_) return;
  py::gil_scoped_acquire gil;
  try {
    callback_(py::str(message.data(), message.size()));
  } catch (py::error_already_set& e) {
    error_ = std::move(e);
  }
}

void add_messages(py::module_& m) {
  m.def("set_log_level", [](const std::string& level) {
    Routing& r = routing();
    std::optional<LogLevel> shown;
    if (level == "detail") shown = LogLevel::Detail;
    else if (level == "progress") shown = LogLevel::Progress;
    else if (level == "info") shown = LogLevel::Info;
    else if (level != "quiet")
      throw InputError("set_log_level: expected \"quiet\", \"info\", \"progress\" or \"detail\", found \"" + level + "\"");
    {
      std::lock_guard lock(r.mutex);
      r.stderr_level = shown;
    }
    install(r);
  }, py::arg("level"), "Where the library's messages go: \"quiet\" (none, the default), \"info\", \"progress\" "
                        "(a line per iteration) or \"detail\" (Newton steps), on stderr.");
}

}  // namespace meshmorph
