// SPDX-License-Identifier: MIT
#pragma once
#include <stdexcept>
#include <string>

namespace meshmorph {

/// Bad input from a user: a malformed file, an unknown key, an impossible value.
/// The message names the file and the line, byte offset or key path. Maps to exit code 2.
class InputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// A file that cannot be opened, read or written for reasons outside its content.
class IoError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace meshmorph

/// Always-on precondition check for callers of the library; throws std::invalid_argument.
#define MESHMORPH_CHECK(cond, msg)                                     \
  do {                                                                 \
    if (!(cond)) throw std::invalid_argument(std::string("meshmorph: ") + (msg)); \
  } while (false)

#ifndef NDEBUG
#include <cassert>
/// Internal invariant, checked in debug builds only.
#define MESHMORPH_ASSERT(cond) assert(cond)
#else
#define MESHMORPH_ASSERT(cond) ((void)0)
#endif
