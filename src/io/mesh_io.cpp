// SPDX-License-Identifier: MIT
#include "meshmorph/io/mesh_io.h"

#include <cstdint>
#include <cstdio>

#include <algorithm>
#include <cctype>
#include <string>
#include <system_error>

#include "meshmorph/error.h"
#include "meshmorph/io/atomic_file.h"
#include "meshmorph/io/cgns.h"
#include "meshmorph/io/exodus.h"
#include "meshmorph/io/foam.h"
#include "meshmorph/io/medit.h"
#include "meshmorph/io/mesh_series.h"
#include "meshmorph/io/msh.h"
#include "meshmorph/io/su2.h"
#include "meshmorph/io/vtu.h"
#include "meshmorph/timings.h"

namespace meshmorph {
namespace {

std::string extension_of(const std::filesystem::path& path) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext;
}

bool is_exodus(const std::string& ext) { return ext == ".exo" || ext == ".e" || ext == ".ex2"; }

void check_group_names(const std::filesystem::path& path, const Mesh& mesh) {
  for (const PhysicalGroup& g : mesh.groups)
    if (const auto bad = group_name_problem(g.name))
      throw InputError(path.string() + ": the name of physical group " + std::to_string(g.tag) + " (dimension " +
                       std::to_string(g.dim) + ") " + *bad + ", which no mesh format can hold");
}

// Writes through a library that opens a file by name (CGNS, Exodus II) into a temporary that
// is renamed to `path`; what the format cannot hold names the file it was for.
void write_by_library(const std::filesystem::path& path, const std::function<void(const std::filesystem::path&)>& write) {
  write_atomically_at(path, [&](const std::filesystem::path& tmp) {
    try {
      write(tmp);
    } catch (const InputError& e) {
      throw InputError(path.string() + ": " + e.what());
    }
  });
}

}  // namespace

bool known_mesh_format(const std::filesystem::path& path) {
  const std::string ext = extension_of(path);
  return ext == ".msh" || ext == ".vtu" || ext == ".mesh" || ext == ".su2" || ext == ".cgns" || is_exodus(ext);
}

Mesh read_mesh(const std::filesystem::path& path) {
  const PhaseTimer timer(Phase::Io);
  const std::string ext = extension_of(path);
  if (ext == ".msh") return read_msh(path);
  if (ext == ".vtu") return read_vtu(path);
  if (ext == ".mesh") return read_medit(path);
  if (ext == ".su2") return read_su2(path);
  if (ext == ".cgns") return read_cgns(path);
  if (is_exodus(ext)) return read_exodus(path);
  if (std::error_code ec; ext == ".foam" || std::filesystem::is_directory(path, ec)) return read_foam(path);
  throw InputError(path.string() + ": unknown mesh format '" + ext +
                   "' (expected .msh, .vtu, .mesh, .su2, .cgns, .exo or an OpenFOAM case folder)");
}

std::optional<std::string> group_name_problem(std::string_view name) {
  char hex[8];
  for (std::size_t i = 0; i < name.size();) {
    const auto b = static_cast<unsigned char>(name[i]);
    if (b < 0x20 || b == 0x7f) {
      std::snprintf(hex, sizeof hex, "0x%02x", b);
      return "holds the control byte " + std::string(hex) + " at byte " + std::to_string(i);
    }
    if (b == '"') return "holds a double quote at byte " + std::to_string(i) + " (MSH keeps names in quotes)";
    // UTF-8: a lead byte and its continuation bytes 10xxxxxx; no overlong forms, surrogates
    // or code points above U+10FFFF.
    const int len = b < 0x80 ? 1 : (b >> 5) == 0x6 ? 2 : (b >> 4) == 0xe ? 3 : (b >> 3) == 0x1e ? 4 : 0;
    bool ok = len > 0 && i + static_cast<std::size_t>(len) <= name.size();
    std::uint32_t cp = len == 1 ? b : len == 2 ? (b & 0x1fu) : len == 3 ? (b & 0x0fu) : (b & 0x07u);
    for (int k = 1; ok && k < len; ++k) {
      const auto c = static_cast<unsigned char>(name[i + static_cast<std::size_t>(k)]);
      ok = (c >> 6) == 0x2;
      cp = (cp << 6) | (c & 0x3fu);
    }
    static constexpr std::uint32_t least[] = {0, 0, 0x80, 0x800, 0x10000};
    if (ok) ok = cp >= least[len] && cp <= 0x10ffff && (cp < 0xd800 || cp > 0xdfff);
    if (!ok) {
      std::snprintf(hex, sizeof hex, "0x%02x", b);
      return "is not valid UTF-8 (byte " + std::string(hex) + " at byte " + std::to_string(i) + ")";
    }
    i += static_cast<std::size_t>(len);
  }
  return std::nullopt;
}

void write_mesh(const std::filesystem::path& path, const Mesh& mesh, const WriteOptions& options) {
  const PhaseTimer timer(Phase::Io);
  check_group_names(path, mesh);
  MeshFormat format{};
  if (options.format) {
    format = *options.format;
  } else {
    const std::string ext = extension_of(path);
    if (ext == ".msh") format = MeshFormat::Msh41;
    else if (ext == ".vtu") format = MeshFormat::Vtu;
    else if (ext == ".mesh") format = MeshFormat::Medit;
    else if (ext == ".su2") format = MeshFormat::Su2;
    else if (ext == ".cgns") format = MeshFormat::Cgns;
    else if (is_exodus(ext)) format = MeshFormat::Exodus;
    else if (is_foam_time_folder(path)) format = MeshFormat::Foam;
    else
      throw InputError(path.string() + ": unknown mesh format '" + ext +
                       "' (expected .msh, .vtu, .mesh, .su2, .cgns, .exo or the time folder of an OpenFOAM case)");
  }
  if (format == MeshFormat::Cgns || format == MeshFormat::Exodus) {  // libraries that write to a path
    return write_by_library(path, [&](const std::filesystem::path& tmp) {
      format == MeshFormat::Cgns ? write_cgns(tmp, mesh, path, options.cell_data, options.point_vectors)
                                 : write_exodus(tmp, mesh, path, options.cell_data, options.point_vectors);
    });
  }
  if (format == MeshFormat::Foam) return write_foam_points(path, mesh);
  write_atomically(path, true, [&](std::ostream& out) {
    try {
      switch (format) {
        case MeshFormat::Msh41: write_msh(out, mesh, 41, options.binary, options.cell_data, options.point_vectors); break;
        case MeshFormat::Msh22: write_msh(out, mesh, 22, options.binary, options.cell_data, options.point_vectors); break;
        case MeshFormat::Vtu: write_vtu(out, mesh, options.binary, options.cell_data, options.point_vectors); break;
        case MeshFormat::Medit: write_medit(out, mesh); break;
        case MeshFormat::Su2: write_su2(out, mesh); break;
        default: break;  // Foam, Cgns and Exodus: above
      }
    } catch (const InputError& e) {  // what the format cannot hold: name the file it was for
      throw InputError(path.string() + ": " + e.what());
    }
  });
}

bool is_series_format(const std::filesystem::path& path) {
  const std::string ext = extension_of(path);
  return ext == ".cgns" || is_exodus(ext);
}

void write_mesh_series(const std::filesystem::path& path, const Mesh& mesh, int n_steps,
                       const std::function<MeshStep(int)>& step) {
  const PhaseTimer timer(Phase::Io);
  if (!is_series_format(path))
    throw InputError(path.string() + ": a series in one file is written as .cgns or .exo, not '" + extension_of(path) + "'");
  check_group_names(path, mesh);
  write_by_library(path, [&](const std::filesystem::path& tmp) {
    extension_of(path) == ".cgns" ? write_cgns_series(tmp, mesh, n_steps, step, path)
                                  : write_exodus_series(tmp, mesh, n_steps, step, path);
  });
}

}  // namespace meshmorph
