// SPDX-License-Identifier: MIT
#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstring>
#include <string>

#include "io/detail/foam_file.h"
#include "meshmorph/error.h"

namespace meshmorph::detail {
namespace {

bool is_delimiter(char ch) { return Cursor::is_space(ch) || std::strchr("(){};\"", ch) != nullptr; }

std::string_view unquoted(std::string_view v) {
  return v.size() >= 2 && v.front() == '"' && v.back() == '"' ? v.substr(1, v.size() - 2) : v;
}

}  // namespace

FoamFile::FoamFile(const std::filesystem::path& path) : data_(read_file(path)), c_(path, data_) {
  skip();
  if (c_.pos() >= data_.size()) c_.fail_at(0, "empty file");
  const std::size_t at = c_.pos();
  if (word("the FoamFile header") != "FoamFile")
    c_.fail_at(at, "expected the FoamFile header, got '" + Cursor::shorten(data_.substr(at, c_.pos() - at)) + "'");
  expect('{');
  std::string format;
  std::size_t format_at = 0;
  while (peek() != '}') {
    const std::string_view key = word("a header entry or '}'");
    const std::size_t key_at = c_.token_start();
    const std::string_view v = unquoted(value());
    if (key == "format") format = v, format_at = key_at;
    if (key == "class") class_ = v;
    if (key == "arch") {
      if (v.find("MSB") != std::string_view::npos)
        c_.fail_at(key_at, "binary polyMesh with a foreign byte order (MSB)");
      if (v.find("label=64") != std::string_view::npos) label_bytes_ = 8;
      if (v.find("scalar=32") != std::string_view::npos) scalar_bytes_ = 4;
      if (v.find("scalar=128") != std::string_view::npos) c_.fail_at(key_at, "128-bit scalars are not supported");
    }
  }
  c_.seek(c_.pos() + 1);
  if (format == "binary")
    binary_ = true;
  else if (format != "ascii")
    c_.fail_at(format_at, format.empty() ? "the FoamFile header has no format"
                                         : "unknown format '" + Cursor::shorten(format) + "'");
}

void FoamFile::skip() {
  const std::string_view t = data_;
  std::size_t p = c_.pos();
  for (;;) {
    while (p < t.size() && Cursor::is_space(t[p])) ++p;
    if (t.compare(p, 2, "//") == 0) {
      while (p < t.size() && t[p] != '\n') ++p;
    } else if (t.compare(p, 2, "/*") == 0) {
      const std::size_t end = t.find("*/", p + 2);
      if (end == std::string_view::npos) c_.fail_at(p, "unterminated comment");
      p = end + 2;
    } else {
      break;
    }
  }
  c_.seek(p);
}

char FoamFile::peek() {
  skip();
  return c_.pos() < data_.size() ? data_[c_.pos()] : '\0';
}

void FoamFile::expect(char ch) {
  const char got = peek();
  if (got != ch) {
    if (got == '\0') c_.fail(std::string("unexpected end of file, expected '") + ch + "'");
    c_.fail(std::string("expected '") + ch + "', got '" + Cursor::shorten(std::string_view(&data_[c_.pos()], 1)) + "'");
  }
  c_.seek(c_.pos() + 1);
}

std::string_view FoamFile::word(std::string_view what) {
  skip();
  const std::size_t start = c_.pos();
  std::size_t p = start;
  while (p < data_.size() && !is_delimiter(data_[p])) ++p;
  if (p == start) {
    if (p >= data_.size()) c_.fail("unexpected end of file, expected " + std::string(what));
    c_.fail("expected " + std::string(what) + ", got '" + Cursor::shorten(std::string_view(&data_[p], 1)) + "'");
  }
  c_.seek(start);
  c_.token(what);  // records token_start for messages
  c_.seek(p);
  return std::string_view(data_).substr(start, p - start);
}

std::int64_t FoamFile::label(std::string_view what) {
  const std::string_view t = word(what);
  std::int64_t v = 0;
  const auto [end, ec] = std::from_chars(t.data(), t.data() + t.size(), v);
  if (ec != std::errc() || end != t.data() + t.size())
    c_.fail_at(c_.token_start(), "expected " + std::string(what) + " (an integer), got '" + Cursor::shorten(t) + "'");
  if (v < 0) c_.fail_at(c_.token_start(), std::string(what) + " " + std::to_string(v) + " is negative");
  return v;
}

double FoamFile::scalar(std::string_view what) {
  const std::string_view t = word(what);
  double v = 0;
  const char* b = t.data() + (!t.empty() && t[0] == '+' ? 1 : 0);
  const auto [end, ec] = std::from_chars(b, t.data() + t.size(), v);
  if (ec != std::errc() || end != t.data() + t.size() || !std::isfinite(v))
    c_.fail_at(c_.token_start(),
               "expected " + std::string(what) + " (a finite number), got '" + Cursor::shorten(t) + "'");
  return v;
}

std::string_view FoamFile::value() {
  skip();
  const std::size_t start = c_.pos();
  int depth = 0;
  for (std::size_t p = start; p < data_.size(); ++p) {
    const char ch = data_[p];
    if (ch == '"') {
      p = data_.find('"', p + 1);
      if (p == std::string::npos) c_.fail_at(start, "unterminated string");
    } else if (ch == '(') {
      ++depth;
    } else if (ch == ')') {
      if (--depth < 0) c_.fail_at(p, "unbalanced ')'");
    } else if (depth == 0 && (ch == '{' || ch == '}')) {
      c_.fail_at(p, "expected ';' before '" + std::string(1, ch) + "'");
    } else if (depth == 0 && ch == ';') {
      c_.seek(p + 1);
      std::string_view v = std::string_view(data_).substr(start, p - start);
      while (!v.empty() && Cursor::is_space(v.back())) v.remove_suffix(1);
      return v;
    }
  }
  c_.fail_at(start, "unexpected end of file, expected ';'");
}

std::int64_t FoamFile::list_start(std::string_view what, bool& uniform) {
  const std::size_t at = (skip(), c_.pos());
  std::int64_t n = -1;
  if (const char ch = peek(); ch >= '0' && ch <= '9') {
    n = label("the size of the " + std::string(what) + " list");
    if (static_cast<std::uint64_t>(n) > c_.remaining())
      c_.fail_at(c_.token_start(), "list size " + std::to_string(n) + " is larger than the rest of the file can hold");
  }
  uniform = peek() == '{';
  if (uniform) {
    if (n < 0) c_.fail("a uniform list {…} needs a size");
    c_.seek(c_.pos() + 1);
    return n;
  }
  if (peek() != '(')
    c_.fail_at(c_.pos() < data_.size() ? c_.pos() : at, "expected the " + std::string(what) + " list: N ( … )");
  c_.seek(c_.pos() + 1);
  if (binary_ && n < 0) c_.fail("a binary list needs a size");
  return n;
}

std::int64_t FoamFile::plain_list_start(std::string_view what, bool whole) {
  bool uniform = false;
  const std::size_t at = (skip(), c_.pos());
  const std::int64_t n = list_start(what, uniform);
  if (uniform) c_.fail_at(at, "a uniform list of " + std::string(what) + " {…}");
  if (whole) list_at_ = at;
  return n;
}

std::int64_t FoamFile::binary_label() {
  if (label_bytes_ == 8) return c_.raw<std::int64_t>("a label");
  return c_.raw<std::int32_t>("a label");
}

double FoamFile::binary_scalar() {
  if (scalar_bytes_ == 4) return c_.raw<float>("a scalar");
  return c_.raw<double>("a scalar");
}

std::vector<std::int64_t> FoamFile::labels(std::string_view what) {
  bool uniform = false;
  const std::size_t at = (skip(), c_.pos());
  const std::int64_t n = list_start(what, uniform);
  list_at_ = at;
  std::vector<std::int64_t> out;
  if (uniform) {
    out.assign(static_cast<std::size_t>(n), label(what));
    expect('}');
  } else if (binary_) {
    if (static_cast<std::uint64_t>(n) * static_cast<std::uint64_t>(label_bytes_) > c_.remaining())
      c_.fail_at(at, "the binary list of " + std::to_string(n) + " labels is cut short by the end of the file");
    c_.binary = true;
    out.resize(static_cast<std::size_t>(n));
    for (std::int64_t& v : out) {
      v = binary_label();
      if (v < 0) c_.fail_at(c_.token_start(), std::string(what) + " " + std::to_string(v) + " is negative");
    }
    c_.binary = false;
    expect(')');
  } else {
    if (n > 0) out.reserve(std::min(static_cast<std::size_t>(n), c_.remaining() / 2));  // "0 " at least
    while (peek() != ')') {
      if (c_.pos() >= data_.size())
        c_.fail("unexpected end of file, expected ')' closing the " + std::string(what) + " list");
      out.push_back(label(what));
    }
    c_.seek(c_.pos() + 1);
    if (n >= 0 && out.size() != static_cast<std::size_t>(n))
      c_.fail_at(at, "the list announces " + std::to_string(n) + " labels but holds " + std::to_string(out.size()));
  }
  return out;
}

std::vector<double> FoamFile::points() {
  if (class_ != "vectorField") c_.fail_at(0, "expected class vectorField, got '" + Cursor::shorten(class_) + "'");
  const std::int64_t n = plain_list_start("points");
  const std::size_t at = list_at_;
  std::vector<double> xyz;
  if (binary_) {
    if (static_cast<std::uint64_t>(n) * 3 * static_cast<std::uint64_t>(scalar_bytes_) > c_.remaining())
      c_.fail_at(at, "the binary list of " + std::to_string(n) + " points is cut short by the end of the file");
    c_.binary = true;
    xyz.resize(3 * static_cast<std::size_t>(n));
    for (double& v : xyz)
      if (v = binary_scalar(); !std::isfinite(v)) c_.fail_at(c_.token_start(), "coordinate is not finite");
    c_.binary = false;
    expect(')');
    return xyz;
  }
  if (n > 0) xyz.reserve(3 * std::min(static_cast<std::size_t>(n), c_.remaining() / 8));  // "(0 0 0) "
  while (peek() != ')') {
    if (c_.pos() >= data_.size()) c_.fail("unexpected end of file, expected ')' closing the points list");
    expect('(');
    for (int k = 0; k < 3; ++k) xyz.push_back(scalar("coordinate"));
    expect(')');
  }
  c_.seek(c_.pos() + 1);
  if (n >= 0 && xyz.size() != 3 * static_cast<std::size_t>(n))
    c_.fail_at(at, "the list announces " + std::to_string(n) + " points but holds " + std::to_string(xyz.size() / 3));
  return xyz;
}

FoamFaces FoamFile::faces(std::int64_t n_points) {
  FoamFaces f;
  const std::string range = " is outside the points 0.." + std::to_string(n_points - 1);
  if (class_ == "faceCompactList") {
    f.offsets = labels("face offset");
    const std::size_t at = list_at_;
    const std::size_t points_at = (skip(), c_.pos());
    f.points = labels("point label");
    if (f.offsets.empty() || f.offsets.front() != 0 || f.offsets.back() != static_cast<std::int64_t>(f.points.size()))
      c_.fail_at(at, "the face offsets do not span the " + std::to_string(f.points.size()) + " point labels");
    for (std::size_t i = 0; i + 1 < f.offsets.size(); ++i)
      if (f.offsets[i + 1] - f.offsets[i] < 3)
        c_.fail_at(at, "face " + std::to_string(i) + " has " + std::to_string(f.offsets[i + 1] - f.offsets[i]) +
                           " points (at least 3)");
    for (std::size_t i = 0; i < f.points.size(); ++i)
      if (f.points[i] >= n_points) c_.fail_at(points_at, "point label " + std::to_string(f.points[i]) + range);
    list_at_ = at;
    return f;
  }
  if (class_ != "faceList")
    c_.fail_at(0, "expected class faceList or faceCompactList, got '" + Cursor::shorten(class_) + "'");
  if (binary_) c_.fail_at(0, "a binary faceList (OpenFOAM writes binary faces as faceCompactList)");
  const std::int64_t n = plain_list_start("faces");
  const std::size_t at = list_at_;
  while (peek() != ')') {
    if (c_.pos() >= data_.size()) c_.fail("unexpected end of file, expected ')' closing the faces list");
    const std::size_t face_at = c_.pos();
    const std::size_t before = f.points.size();
    const std::int64_t k = plain_list_start("face's point", false);
    while (peek() != ')') {
      if (c_.pos() >= data_.size()) c_.fail("unexpected end of file, expected ')' closing a face");
      const std::int64_t p = label("point label");
      if (p >= n_points) c_.fail_at(c_.token_start(), "point label " + std::to_string(p) + range);
      f.points.push_back(p);
    }
    c_.seek(c_.pos() + 1);
    const auto got = static_cast<std::int64_t>(f.points.size() - before);
    if (k >= 0 && got != k)
      c_.fail_at(face_at, "the face announces " + std::to_string(k) + " points but holds " + std::to_string(got));
    if (got < 3)
      c_.fail_at(face_at, "face " + std::to_string(f.size()) + " has " + std::to_string(got) + " points (at least 3)");
    f.offsets.push_back(static_cast<std::int64_t>(f.points.size()));
  }
  c_.seek(c_.pos() + 1);
  if (n >= 0 && f.size() != static_cast<std::size_t>(n))
    c_.fail_at(at, "the list announces " + std::to_string(n) + " faces but holds " + std::to_string(f.size()));
  return f;
}

std::vector<FoamPatch> FoamFile::patches() {
  if (class_ != "polyBoundaryMesh")
    c_.fail_at(0, "expected class polyBoundaryMesh, got '" + Cursor::shorten(class_) + "'");
  binary_ = false;  // the boundary dictionary is text in binary cases too
  const std::int64_t n = plain_list_start("patches");
  const std::size_t at = list_at_;
  std::vector<FoamPatch> out;
  while (peek() != ')') {
    FoamPatch p;
    p.name = word("a patch name or ')'");
    p.at = c_.token_start();
    expect('{');
    bool have_n = false, have_start = false;
    while (peek() != '}') {
      const std::string_view key = word("a patch entry or '}'");
      const std::size_t key_at = c_.token_start();
      if (peek() == '{') {  // a sub-dictionary: skipped
        for (int depth = 0; c_.pos() < data_.size();) {
          const char ch = data_[c_.pos()];
          c_.seek(c_.pos() + 1);
          if (ch == '{') ++depth;
          if (ch == '}' && --depth == 0) break;
        }
        continue;
      }
      const std::string v(value());
      if (key == "type") p.type = v;
      if (key == "nFaces" || key == "startFace") {
        std::int64_t x = -1;
        const auto [end, ec] = std::from_chars(v.data(), v.data() + v.size(), x);
        if (ec != std::errc() || end != v.data() + v.size() || x < 0)
          c_.fail_at(key_at, std::string(key) + " must be a count, got '" + Cursor::shorten(v) + "'");
        (key == "nFaces" ? p.n_faces : p.start_face) = x;
        (key == "nFaces" ? have_n : have_start) = true;
      }
    }
    c_.seek(c_.pos() + 1);
    if (!have_n || !have_start) c_.fail_at(p.at, "patch '" + Cursor::shorten(p.name) + "' needs nFaces and startFace");
    out.push_back(std::move(p));
  }
  c_.seek(c_.pos() + 1);
  if (n >= 0 && out.size() != static_cast<std::size_t>(n))
    c_.fail_at(at, "the list announces " + std::to_string(n) + " patches but holds " + std::to_string(out.size()));
  return out;
}

void FoamFile::expect_end() {
  if (peek() != '\0')
    c_.fail("unexpected '" + Cursor::shorten(std::string_view(&data_[c_.pos()], 1)) + "' after the list");
}

}  // namespace meshmorph::detail
