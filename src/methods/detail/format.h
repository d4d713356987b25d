// SPDX-License-Identifier: MIT
#pragma once
#include <cstdio>
#include <string>

namespace meshmorph::detail {

/// printf-style formatting of progress and result messages (at most 240 characters).
template <class... Args>
std::string format(const char* fmt, Args... args) {
  char buffer[240];
  std::snprintf(buffer, sizeof buffer, fmt, args...);
  return buffer;
}

}  // namespace meshmorph::detail
