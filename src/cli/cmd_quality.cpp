// SPDX-License-Identifier: MIT
#include <cmath>
#include <cstdio>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "cli/detail/output_files.h"
#include "meshmorph/cli/commands.h"
#include "meshmorph/app/report.h"
#include "meshmorph/error.h"
#include "meshmorph/io/mesh_io.h"
#include "meshmorph/log.h"
#include "meshmorph/app/quality_case.h"

namespace meshmorph {

namespace {

struct QualityArgs {
  std::string mesh;
  std::string json;    // --json FILE
  std::string output;  // -o FILE.vtu
};

std::string fixed(double v, int digits = 4) {
  if (!std::isfinite(v)) return "n/a";
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*f", digits, v);
  return buf;
}

std::string cell_summary(const Mesh& mesh) {
  std::map<std::string, std::size_t> counts;
  for (const auto& b : mesh.cells)
    counts[std::string(name_of(b.type)) + " P" + std::to_string(b.order)] += b.n_cells();
  std::string s;
  for (const auto& [name, n] : counts) s += (s.empty() ? "" : ", ") + std::to_string(n) + " " + name;
  return s;
}

void print_table(std::ostream& out, const std::string& file, const Mesh& mesh, const QualityReport& q) {
  char line[160];
  auto row = [&](const char* name, const std::string& value) {
    std::snprintf(line, sizeof line, "  %-26s %s\n", name, value.c_str());
    out << line;
  };
  out << "meshmorph quality " << file << "\n";
  row("dimension", std::to_string(mesh.dim) + "D");
  row("order", std::to_string(mesh.order()));
  row("nodes", std::to_string(mesh.n_nodes()));
  row("elements", std::to_string(q.n_cells) + " (" + cell_summary(mesh) + ")");
  row("inverted elements", std::to_string(q.inverted_elements));
  const std::size_t flipped = q.flipped_cells.size();
  row("overlap", !q.overlapping ? std::string("none")
                 : flipped == 0 ? std::string(q.twisted                  ? "no orientation fits the cells"
                                              : q.boundary_crossings > 0 ? "the boundary passes through itself"
                                                                         : "the volumes do not add up")
                                : std::to_string(flipped) + (flipped > 1 ? " cells" : " cell") +
                                      " listed mirrored against the neighbours, first cell " +
                                      std::to_string(q.flipped_cells.front()));
  char volumes[64];
  std::snprintf(volumes, sizeof volumes, "%.10g / %.10g", q.cell_volume, q.enclosed_volume);
  row("volume cells / enclosed", volumes);
  row("shape quality min / mean", fixed(q.min_shape_quality) + " / " + fixed(q.mean_shape_quality) +
                                      "   (1/eta against the ideal element; 1 = ideal, 0 = inverted)");
  row("scaled Jacobian min", fixed(q.min_scaled_jacobian) + "   (Verdict; ParaView's \"Scaled Jacobian\")");
  if (q.by_type.size() > 1) {
    for (const CellTypeQuality& t : q.by_type) {
      const std::string name = "  " + std::string(name_of(t.type));
      row(name.c_str(), "shape quality min " + fixed(t.min_shape_quality) + ", scaled Jacobian min " + fixed(t.min_scaled_jacobian));
    }
  }
  out << "  shape quality histogram\n";
  std::size_t most = 1;
  for (std::size_t n : q.shape_histogram) most = std::max(most, n);
  for (std::size_t k = 0; k < q.shape_histogram.size(); ++k) {
    const std::size_t n = q.shape_histogram[k];
    const std::string bar(n == 0 ? 0 : std::max<std::size_t>(1, 40 * n / most), '#');
    std::snprintf(line, sizeof line, "    [%.1f, %.1f%c %9zu%s%s\n", 0.1 * static_cast<double>(k),
                  0.1 * static_cast<double>(k + 1), k + 1 == q.shape_histogram.size() ? ']' : ')', n,
                  bar.empty() ? "" : "  ", bar.c_str());
    out << line;
  }
}

Outcome run_quality(const QualityArgs& a, std::ostream& out) {
  if (!a.output.empty() && std::filesystem::path(a.output).extension() != ".vtu")
    throw InputError(a.output + ": -o writes the per-element quality as VTU cell data; expected a .vtu file");
  const RunTimings timings;
  const Mesh mesh = read_mesh(a.mesh);
  std::vector<detail::OutputFile> outputs;
  if (!a.json.empty()) outputs.push_back({"--json", a.json, false});
  if (!a.output.empty()) outputs.push_back({"-o", a.output});
  detail::check_outputs(outputs);
  QualityOutput run = run_quality(mesh, a.mesh);
  const QualityReport& q = run.quality;
  print_table(out, a.mesh, mesh, q);
  out.flush();  // the table before the log lines that follow on stderr

  if (!a.json.empty()) {
    stamp_times(run.report, timings);
    write_report(a.json, run.report, run.extra);
    log_info("wrote " + a.json);
  }
  if (!a.output.empty()) {
    WriteOptions options;
    options.cell_data[std::string(kShapeQualityField)] = q.shape_quality;
    options.cell_data[std::string(kScaledJacobianField)] = q.scaled_jacobian;
    write_mesh(a.output, mesh, options);
    log_info("wrote " + a.output);
  }
  return run.report.valid ? Outcome::GoalReached : Outcome::GoalMissed;
}

}  // namespace

void add_quality_command(CLI::App& app, Command& run) {
  auto args = std::make_shared<QualityArgs>();
  CLI::App* cmd = app.add_subcommand("quality", "Element quality table of a mesh (exit 1 if an element is inverted or the cells overlap)");
  cmd->add_option("MESH", args->mesh, "Mesh file (.msh, .vtu, .mesh)")->required();
  cmd->add_option("--json", args->json, "Also write the report as JSON")->type_name("FILE");
  cmd->add_option("-o,--output", args->output, "Write the mesh with per-element quality as VTU cell data")
      ->type_name("FILE.vtu");
  cmd->callback([args, &run] { run = [args](std::ostream& out) { return run_quality(*args, out); }; });
}

}  // namespace meshmorph
