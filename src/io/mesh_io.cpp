// SPDX-License-Identifier: MIT
#include "meshmorph/io/mesh_io.h"

#include <algorithm>
#include <cctype>
#include <string>

#include "meshmorph/error.h"
#include "meshmorph/io/atomic_file.h"
#include "meshmorph/io/medit.h"
#include "meshmorph/io/msh.h"
#include "meshmorph/io/vtu.h"

namespace meshmorph {
namespace {

std::string extension_of(const std::filesystem::path& path) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext;
}

}  // namespace

Mesh read_mesh(const std::filesystem::path& path) {
  const std::string ext = extension_of(path);
  if (ext == ".msh") return read_msh(path);
  if (ext == ".vtu") return read_vtu(path);
  if (ext == ".mesh") return read_medit(path);
  throw InputError(path.string() + ": unknown mesh format '" + ext + "' (expected .msh, .vtu or .mesh)");
}

void write_mesh(const std::filesystem::path& path, const Mesh& mesh, const WriteOptions& options) {
  MeshFormat format{};
  if (options.format) {
    format = *options.format;
  } else {
    const std::string ext = extension_of(path);
    if (ext == ".msh") format = MeshFormat::Msh41;
    else if (ext == ".vtu") format = MeshFormat::Vtu;
    else if (ext == ".mesh") format = MeshFormat::Medit;
    else throw InputError(path.string() + ": unknown mesh format '" + ext + "' (expected .msh, .vtu or .mesh)");
  }
  write_atomically(path, true, [&](std::ostream& out) {
    try {
      switch (format) {
        case MeshFormat::Msh41: write_msh(out, mesh, 41, options.binary); break;
        case MeshFormat::Msh22: write_msh(out, mesh, 22, options.binary); break;
        case MeshFormat::Vtu: write_vtu(out, mesh, options.binary, options.cell_data); break;
        case MeshFormat::Medit: write_medit(out, mesh); break;
      }
    } catch (const InputError& e) {  // what the format cannot hold: name the file it was for
      throw InputError(path.string() + ": " + e.what());
    }
  });
}

}  // namespace meshmorph
