// SPDX-License-Identifier: MIT
#pragma once
#include <optional>
#include <string>
#include <string_view>

#include <pybind11/pybind11.h>

namespace meshmorph {

namespace py = pybind11;

/// set_log_level: the library's messages on stderr up to the level it names.
void add_messages(py::module_& m);

/// While alive (created and destroyed with the GIL held), the progress lines the library
/// emits on this thread go to `callback` (None: nowhere), which runs on this thread with the
/// GIL. An exception the callback raises stops its calls and is raised by rethrow() after the
/// solve, which it does not interrupt.
class ProgressScope {
 public:
  explicit ProgressScope(py::object callback);
  ~ProgressScope();
  ProgressScope(const ProgressScope&) = delete;
  ProgressScope& operator=(const ProgressScope&) = delete;
  /// Raises the callback's exception, if it raised one. With the GIL.
  void rethrow();
  /// One progress line to the callback (from the library's log sink, without the GIL).
  void deliver(std::string_view message);

 private:
  py::object callback_;
  std::optional<py::error_already_set> error_;
  ProgressScope* outer_;
};

}  // namespace meshmorph
