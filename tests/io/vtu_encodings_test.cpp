// SPDX-License-Identifier: MIT
// VTU arrays as VTK and ParaView write them: inline base64, appended raw and appended base64,
// with and without zlib compression, UInt32 and UInt64 headers, several pieces.
#include <unistd.h>

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <pugixml.hpp>
#include <zlib.h>

#include "io/detail/base64.h"
#include "io/mesh_compare.h"
#include "meshmorph/error.h"
#include "meshmorph/fem/structured.h"
#include "meshmorph/io/vtu.h"

namespace meshmorph {
namespace {

namespace fs = std::filesystem;

struct Array {
  std::string name, type;
  int components;
  std::string bytes;  // little-endian values
};

template <class T>
std::string bytes_of(const std::string& ascii) {
  std::istringstream in(ascii);
  std::string out;
  double v;
  while (in >> v) {
    const T t = static_cast<T>(v);
    out.append(reinterpret_cast<const char*>(&t), sizeof t);
  }
  return out;
}

// One value per node: j/4 − 3 (exact in Float32) or j (`fraction` = 0), as text.
std::string point_values(const Mesh& m, int fraction) {
  std::string s;
  for (std::size_t j = 0; j < m.n_nodes(); ++j)
    s += std::to_string(fraction ? static_cast<double>(j) / 4 - 3 : static_cast<double>(j)) + ' ';
  return s;
}

Eigen::VectorXd values_of(const std::string& ascii) {
  std::istringstream in(ascii);
  std::vector<double> v;
  double t;
  while (in >> t) v.push_back(t);
  return Eigen::Map<const Eigen::VectorXd>(v.data(), static_cast<Eigen::Index>(v.size()));
}

enum class Mode { Inline, AppendedRaw, AppendedBase64 };

std::string header(std::uint64_t v, bool header64) {
  std::string s(header64 ? 8 : 4, '\0');
  if (header64) {
    std::memcpy(s.data(), &v, 8);
  } else {
    const auto w = static_cast<std::uint32_t>(v);
    std::memcpy(s.data(), &w, 4);
  }
  return s;
}

// Header and data of one array, stored as VTK stores them; `split` marks where the header ends.
std::pair<std::string, std::string> encode(const std::string& data, bool header64, bool compressed) {
  if (!compressed) return {header(data.size(), header64), data};
  const std::size_t block = 1000;  // small, so that arrays span several blocks
  const std::size_t n = (data.size() + block - 1) / block;
  std::string head = header(n, header64) + header(block, header64) + header(data.size() % block, header64);
  std::string body;
  for (std::size_t b = 0; b < n; ++b) {
    const std::size_t len = std::min(block, data.size() - b * block);
    uLongf size = compressBound(len);
    std::string c(size, '\0');
    EXPECT_EQ(compress(reinterpret_cast<Bytef*>(c.data()), &size, reinterpret_cast<const Bytef*>(data.data() + b * block), len), Z_OK);
    c.resize(size);
    head += header(size, header64);
    body += c;
  }
  return {head, body};
}

std::string make_vtu(const std::vector<std::vector<Array>>& pieces, const std::vector<std::pair<long, long>>& sizes,
                     Mode mode, bool header64, bool compressed) {
  std::string xml = "<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\"";
  xml += std::string(" header_type=\"") + (header64 ? "UInt64" : "UInt32") + "\"";
  if (compressed) xml += " compressor=\"vtkZLibDataCompressor\"";
  xml += ">\n<UnstructuredGrid>\n";
  std::string appended;
  for (std::size_t p = 0; p < pieces.size(); ++p) {
    xml += "<Piece NumberOfPoints=\"" + std::to_string(sizes[p].first) + "\" NumberOfCells=\"" + std::to_string(sizes[p].second) + "\">\n";
    for (const char* section : {"Points", "Cells", "CellData", "PointData"}) {
      xml += std::string("<") + section + ">\n";
      for (const Array& a : pieces[p]) {
        const bool in_section = a.name == "Points"          ? std::string(section) == "Points"
                                : a.name == "group"         ? std::string(section) == "CellData"
                                : a.name.starts_with("pd_") ? std::string(section) == "PointData"
                                                            : std::string(section) == "Cells";
        if (!in_section) continue;
        const auto [head, body] = encode(a.bytes, header64, compressed);
        xml += "<DataArray type=\"" + a.type + "\" Name=\"" + a.name + "\" NumberOfComponents=\"" + std::to_string(a.components) + "\"";
        if (mode == Mode::Inline) {
          std::string text;
          detail::base64_encode(head, text);  // encoded separately, as VTK does
          detail::base64_encode(body, text);
          xml += " format=\"binary\">\n" + text + "\n</DataArray>\n";
        } else {
          xml += " format=\"appended\" offset=\"" + std::to_string(appended.size()) + "\"/>\n";
          if (mode == Mode::AppendedRaw) {
            appended += head + body;
          } else {
            detail::base64_encode(head + body, appended);
          }
        }
      }
      xml += std::string("</") + section + ">\n";
    }
    xml += "</Piece>\n";
  }
  xml += "</UnstructuredGrid>\n";
  if (mode != Mode::Inline)
    xml += std::string("<AppendedData encoding=\"") + (mode == Mode::AppendedRaw ? "raw" : "base64") + "\">\n   _" + appended + "\n</AppendedData>\n";
  return xml + "</VTKFile>\n";
}

TEST(VtuEncodings, AppendedRawBase64AndZlibAllReadTheSameMesh) {
  const Mesh m = structured_mesh(ElementType::Tetrahedron, 2, 2);
  Mesh unnamed = m;  // these files carry no FieldData, so the groups come back by number
  for (PhysicalGroup& g : unnamed.groups) g.name.clear();
  std::ostringstream ascii;
  write_vtu(ascii, m, false);
  pugi::xml_document doc;
  ASSERT_TRUE(doc.load_string(ascii.str().c_str()));
  const pugi::xml_node piece = doc.child("VTKFile").child("UnstructuredGrid").child("Piece");
  const auto text = [&](const char* section, const char* name) {
    return std::string(piece.child(section).find_child_by_attribute("Name", name).text().get());
  };
  // Narrower integer types than we write, as other writers use.
  const std::vector<Array> arrays{{"Points", "Float64", 3, bytes_of<double>(text("Points", "Points"))},
                                  {"connectivity", "Int32", 1, bytes_of<std::int32_t>(text("Cells", "connectivity"))},
                                  {"offsets", "Int64", 1, bytes_of<std::int64_t>(text("Cells", "offsets"))},
                                  {"types", "UInt8", 1, bytes_of<std::uint8_t>(text("Cells", "types"))},
                                  {"group", "Int16", 1, bytes_of<std::int16_t>(text("CellData", "group"))},
                                  // Point data: scalars of several types become node fields, vectors do not.
                                  {"pd_phi", "Float32", 1, bytes_of<float>(point_values(m, 1))},
                                  {"pd_label", "UInt16", 1, bytes_of<std::uint16_t>(point_values(m, 0))},
                                  {"pd_vector", "Float64", 3, bytes_of<double>(text("Points", "Points"))}};
  unnamed.node_fields["pd_phi"] = values_of(point_values(m, 1));
  unnamed.node_fields["pd_label"] = values_of(point_values(m, 0));
  const long n_points = piece.attribute("NumberOfPoints").as_llong();
  const long n_cells = piece.attribute("NumberOfCells").as_llong();
  const fs::path dir = fs::temp_directory_path() / ("meshmorph_vtu_enc_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  int variant = 0;
  for (const Mode mode : {Mode::Inline, Mode::AppendedRaw, Mode::AppendedBase64})
    for (const bool header64 : {false, true})
      for (const bool compressed : {false, true}) {
        SCOPED_TRACE("mode " + std::to_string(static_cast<int>(mode)) + (header64 ? " UInt64" : " UInt32") +
                     (compressed ? " zlib" : ""));
        const fs::path p = dir / (std::to_string(variant++) + ".vtu");
        std::ofstream(p, std::ios::binary) << make_vtu({arrays}, {{n_points, n_cells}}, mode, header64, compressed);
        const Mesh r = read_vtu(p);
        test::expect_meshes_equal(unnamed, r, {.node_tags = true, .entities = false});
      }
  // Two pieces: the second piece's point indices are local to it.
  const fs::path p = dir / "pieces.vtu";
  std::ofstream(p, std::ios::binary) << make_vtu({arrays, arrays}, {{n_points, n_cells}, {n_points, n_cells}},
                                                 Mode::AppendedRaw, true, true);
  const Mesh two = read_vtu(p);
  EXPECT_EQ(two.n_nodes(), 2 * m.n_nodes());
  ASSERT_EQ(two.cells.size(), 1u);
  EXPECT_EQ(two.cells[0].n_cells(), 2 * m.cells[0].n_cells());
  EXPECT_EQ(two.cells[0].nodes[m.cells[0].nodes.size()], m.cells[0].nodes[0] + static_cast<std::int32_t>(m.n_nodes()));
  ASSERT_EQ(two.node_fields.count("pd_phi"), 1u);
  EXPECT_EQ(two.node_fields.at("pd_phi").tail(static_cast<Eigen::Index>(m.n_nodes())), unnamed.node_fields.at("pd_phi"));
  fs::remove_all(dir);
}

// One triangle whose Points (3 × 3 Float64) are `stored` (header and data) inline or appended;
// the other arrays are ascii.
std::string triangle_vtu(const std::string& stored, Mode mode, bool header64, bool compressed) {
  std::string xml = "<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\"";
  xml += std::string(" header_type=\"") + (header64 ? "UInt64" : "UInt32") + "\"";
  if (compressed) xml += " compressor=\"vtkZLibDataCompressor\"";
  xml += ">\n<UnstructuredGrid>\n<Piece NumberOfPoints=\"3\" NumberOfCells=\"1\">\n<Points>\n";
  xml += "<DataArray type=\"Float64\" Name=\"Points\" NumberOfComponents=\"3\"";
  std::string text;
  detail::base64_encode(stored, text);
  xml += mode == Mode::Inline ? " format=\"binary\">" + text + "</DataArray>\n" : " format=\"appended\" offset=\"0\"/>\n";
  xml += "</Points>\n<Cells>\n<DataArray type=\"Int64\" Name=\"connectivity\">0 1 2</DataArray>\n"
         "<DataArray type=\"Int64\" Name=\"offsets\">3</DataArray>\n<DataArray type=\"UInt8\" Name=\"types\">5</DataArray>\n"
         "</Cells>\n</Piece>\n</UnstructuredGrid>\n";
  if (mode == Mode::AppendedRaw) xml += "<AppendedData encoding=\"raw\">\n   _" + stored + "\n</AppendedData>\n";
  if (mode == Mode::AppendedBase64) xml += "<AppendedData encoding=\"base64\">\n   _" + text + "\n</AppendedData>\n";
  return xml + "</VTKFile>\n";
}

// The sizes a header announces are checked before anything is allocated: against the bytes the
// array needs, and against what its zlib blocks can inflate to (1032:1 at most). A 4 GB block
// in a 1 kB file is refused before it is allocated, and so is a 2^40-byte one.
TEST(VtuEncodings, HeaderSizesAreCheckedBeforeAllocating) {
  const std::string points = bytes_of<double>("0 0 0 1 0 0 0 1 0");  // 72 bytes
  uLongf size = compressBound(points.size());
  std::string z(size, '\0');
  ASSERT_EQ(compress(reinterpret_cast<Bytef*>(z.data()), &size, reinterpret_cast<const Bytef*>(points.data()), points.size()),
            Z_OK);
  z.resize(size);
  const std::string zsize = std::to_string(z.size());
  struct Case {
    std::string stored;
    bool header64, compressed;
    std::string error;  // empty: the file is valid
  };
  const auto h32 = [](std::uint64_t v) { return header(v, false); };
  const auto h64 = [](std::uint64_t v) { return header(v, true); };
  const std::vector<Case> cases{
      {h32(1) + h32(72) + h32(0) + h32(z.size()) + z, false, true, ""},
      {h64(72) + points, true, false, ""},
      {h32(1) + h32(0xFFFFFFF0) + h32(0xFFFFFFF0) + h32(z.size()) + z, false, true,
       "block 0 announces 4294967280 bytes, more than its " + zsize + " compressed bytes can inflate to"},
      {h64(1) + h64(72) + h64(std::uint64_t{1} << 40) + h64(z.size()) + z, true, true,
       "block 0 announces 1099511627776 bytes, more than its " + zsize + " compressed bytes can inflate to"},
      {h64(2) + h64(72) + h64(0) + h64(z.size()) + h64(z.size()) + z + z, true, true,
       "header announces 144 bytes, expected at most 72"},
      {h64(std::uint64_t{1} << 62) + points, true, false, "header announces 4611686018427387904 bytes, expected at most 72"},
      {h32(0xFFFFFFFF) + points, false, false, "header announces 4294967295 bytes, expected at most 72"},
  };
  const fs::path dir = fs::temp_directory_path() / ("meshmorph_vtu_header_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const fs::path p = dir / "t.vtu";
  for (std::size_t i = 0; i < cases.size(); ++i)
    for (const Mode mode : {Mode::Inline, Mode::AppendedRaw, Mode::AppendedBase64}) {
      SCOPED_TRACE("case " + std::to_string(i) + ", mode " + std::to_string(static_cast<int>(mode)));
      const Case& c = cases[i];
      std::ofstream(p, std::ios::binary | std::ios::trunc) << triangle_vtu(c.stored, mode, c.header64, c.compressed);
      if (c.error.empty()) {
        EXPECT_EQ(read_vtu(p).n_nodes(), 3u);
        continue;
      }
      try {
        read_vtu(p);
        ADD_FAILURE() << "no exception";
      } catch (const InputError& e) {
        EXPECT_EQ(std::string(e.what()), p.string() + ": line 6: DataArray 'Points' " + c.error);
      } catch (const std::exception& e) {
        ADD_FAILURE() << "not an InputError: " << e.what();
      }
    }
  fs::remove_all(dir);
}

// An appended array's offset is a byte count: "-5" or "8x" is an error naming its line, not
// a number that some other array's bytes happen to fit.
TEST(VtuEncodings, AnAppendedOffsetMustBeANonNegativeInteger) {
  const std::string stored = header(72, false) + bytes_of<double>("0 0 0 1 0 0 0 1 0");
  const fs::path dir = fs::temp_directory_path() / ("meshmorph_vtu_offset_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const fs::path p = dir / "t.vtu";
  for (const char* offset : {"-5", "8x", "", "+0"}) {
    SCOPED_TRACE(offset);
    std::string xml = triangle_vtu(stored, Mode::AppendedRaw, false, false);
    xml.replace(xml.find("offset=\"0\""), 10, std::string("offset=\"") + offset + "\"");
    std::ofstream(p, std::ios::binary | std::ios::trunc) << xml;
    try {
      read_vtu(p);
      ADD_FAILURE() << "no exception";
    } catch (const InputError& e) {
      EXPECT_EQ(std::string(e.what()), p.string() + ": line 6: DataArray offset '" + offset +
                                           "' is not a byte offset (a non-negative integer)");
    }
  }
  std::ofstream(p, std::ios::binary | std::ios::trunc) << triangle_vtu(stored, Mode::AppendedRaw, false, false);
  EXPECT_EQ(read_vtu(p).n_nodes(), 3u);
  fs::remove_all(dir);
}

TEST(VtuEncodings, Base64RoundTripsEveryLength) {
  for (std::size_t n = 0; n < 10; ++n) {
    std::string bytes;
    for (std::size_t i = 0; i < n; ++i) bytes.push_back(static_cast<char>(i * 37 + 200));
    std::string text;
    detail::base64_encode(bytes, text);
    EXPECT_EQ(text.size(), (n + 2) / 3 * 4);
    std::size_t bad = 0;
    const auto decoded = detail::base64_decode(text, bad);
    ASSERT_TRUE(decoded.has_value());
    EXPECT_EQ(*decoded, bytes);
  }
  std::size_t bad = 0;
  EXPECT_FALSE(detail::base64_decode("QUJD!A==", bad).has_value());
  EXPECT_EQ(bad, 4u);
  EXPECT_FALSE(detail::base64_decode("QUJ", bad).has_value());
}

}  // namespace
}  // namespace meshmorph
