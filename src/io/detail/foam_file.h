// SPDX-License-Identifier: MIT
#pragma once
#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "io/detail/cursor.h"

namespace meshmorph::detail {

/// The faces of a polyMesh as OpenFOAM's faceCompactList holds them: face f has the points
/// points[offsets[f] .. offsets[f + 1]).
struct FoamFaces {
  std::vector<std::int64_t> offsets{0};
  std::vector<std::int64_t> points;
  std::size_t size() const { return offsets.size() - 1; }
};

/// A patch of the boundary file, with the offset of its name (for messages).
struct FoamPatch {
  std::string name;
  std::string type;
  std::int64_t n_faces = 0;
  std::int64_t start_face = 0;
  std::size_t at = 0;
};

/// One file of a polyMesh, held in memory: its FoamFile header (format, class, arch) is read on
/// construction, then one of the readers reads its content. ASCII content may hold C and C++
/// comments; lists are `N (…)`, `(…)` or `N{value}`. Binary lists are `N (` raw values `)`.
/// Errors name the file and the line, or the byte offset inside binary data.
class FoamFile {
 public:
  explicit FoamFile(const std::filesystem::path& path);
  FoamFile(const FoamFile&) = delete;
  FoamFile& operator=(const FoamFile&) = delete;

  const std::string& class_name() const { return class_; }
  const Cursor& cursor() const { return c_; }
  /// Where the last list read starts (for messages about the list as a whole).
  std::size_t list_at() const { return list_at_; }
  [[noreturn]] void fail_at(std::size_t offset, const std::string& msg) const { c_.fail_at(offset, msg); }

  /// A vectorField: 3 coordinates a point.
  std::vector<double> points();
  /// A labelList; every label must be ≥ 0.
  std::vector<std::int64_t> labels(std::string_view what);
  /// A faceList or faceCompactList; every face has ≥ 3 points, each below `n_points`.
  FoamFaces faces(std::int64_t n_points);
  /// A polyBoundaryMesh's patches (name, type, nFaces, startFace).
  std::vector<FoamPatch> patches();
  /// Only comments may follow.
  void expect_end();

 private:
  void skip();
  char peek();
  void expect(char ch);
  std::int64_t label(std::string_view what);
  double scalar(std::string_view what);
  std::string_view word(std::string_view what);
  /// Reads `N (` (or `(` without a count, ASCII only); returns N or −1, and whether the list
  /// is `N{value}` (uniform: the cursor is then on the value).
  std::int64_t list_start(std::string_view what, bool& uniform);
  /// list_start for a list that cannot be uniform; `whole`: the file's list (its start goes
  /// to list_at), not an item of it.
  std::int64_t plain_list_start(std::string_view what, bool whole = true);
  /// An entry's value up to its ';' (nested parentheses and quotes kept), trimmed.
  std::string_view value();
  std::int64_t binary_label();
  double binary_scalar();

  std::string data_;
  Cursor c_;
  std::string class_;
  bool binary_ = false;
  int label_bytes_ = 4;
  int scalar_bytes_ = 8;
  std::size_t list_at_ = 0;
};

}  // namespace meshmorph::detail
