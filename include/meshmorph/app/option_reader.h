// SPDX-License-Identifier: MIT
#pragma once
#include <initializer_list>
#include <limits>
#include <set>
#include <string>
#include <string_view>

#include <nlohmann/json.hpp>

namespace meshmorph {

/// Validates the "options" object of a case file against the options a method declares.
///
/// A method driver reads each option it knows straight into its Options struct, whose
/// defaults are the paper's values; an option absent from the case keeps its default:
/// ```
/// OptionReader r(c.options, c.file.string());
/// r.read("max_newton", opts.max_newton, 1, 10000);
/// r.read("tolerance", opts.tolerance, 0.0, 1.0);
/// r.finish();  // any option that was not read is an error
/// ```
/// Every error is an InputError "case.json: options.<name>: <what>".
class OptionReader {
 public:
  /// `options` must be a JSON object; `file` names the case file in messages.
  OptionReader(const nlohmann::json& options, std::string file, std::string path = "options");
  /// The reader keeps a reference to `options`: a temporary would dangle.
  OptionReader(nlohmann::json&& options, std::string file, std::string path = "options") = delete;

  /// A finite number in [lo, hi].
  void read(std::string_view name, double& value, double lo = -std::numeric_limits<double>::max(),
            double hi = std::numeric_limits<double>::max());
  /// An integer in [lo, hi] (2.0 counts as 2; 2.5 does not).
  void read(std::string_view name, int& value, int lo = std::numeric_limits<int>::min(),
            int hi = std::numeric_limits<int>::max());
  void read(std::string_view name, bool& value);
  /// A string; when `choices` is not empty, one of them.
  void read(std::string_view name, std::string& value, std::initializer_list<std::string_view> choices = {});
  /// True when the case sets `name` (which also becomes a declared option).
  bool has(std::string_view name);

  /// Throws for the first option of the case (in file order) that no read() declared,
  /// listing the declared ones.
  void finish() const;

 private:
  const nlohmann::json* find(std::string_view name);
  std::string where(std::string_view name) const;

  const nlohmann::json& options_;
  std::string file_;
  std::string path_;
  std::set<std::string, std::less<>> declared_;
};

}  // namespace meshmorph
