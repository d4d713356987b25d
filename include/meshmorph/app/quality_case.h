// SPDX-License-Identifier: MIT
#pragma once
#include <optional>
#include <string>

#include <nlohmann/json.hpp>

#include "meshmorph/app/report.h"
#include "meshmorph/io/mesh_io.h"
#include "meshmorph/mesh/mesh.h"
#include "meshmorph/quality/quality_report.h"

namespace meshmorph {

/// What `meshmorph quality` measures: every cell, and the report of DESIGN §3.3 with the
/// members that follow it (docs/cli.md, quality --json).
struct QualityOutput {
  Report report;
  nlohmann::ordered_json extra = nlohmann::ordered_json::object();
  QualityReport quality;
};

/// The runner of `meshmorph quality` and of the Python module's quality(): measures `mesh`
/// (`name`: its file, in the report and messages), against `reference` too (quality 1/η of
/// paper 000) when it is given. Throws InputError when `reference` has other cells or nodes.
QualityOutput run_quality(const Mesh& mesh, const std::string& name, const Mesh* reference = nullptr);

/// The write options of `meshmorph convert` and the Python module's convert() for `output`,
/// whose extension picks the format: binary MSH or VTU, MSH 2.2 with `msh22`. Throws
/// InputError naming `output` for an unknown format or an option it cannot take.
WriteOptions convert_options(const std::string& output, bool binary, bool msh22);

/// `mesh` raised to `order` (straight-sided; 0 keeps it). Throws InputError naming `name`
/// for an order below the mesh's or above the highest of one of its cell types.
Mesh converted(Mesh mesh, int order, const std::string& name);

}  // namespace meshmorph
