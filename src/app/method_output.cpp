// SPDX-License-Identifier: MIT
#include "app/detail/method_output.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <system_error>

#include <omp.h>

#include "meshmorph/error.h"
#include "meshmorph/fem/trace.h"
#include "meshmorph/io/input_files.h"
#include "meshmorph/io/mesh_io.h"

namespace meshmorph::detail {

std::pair<double, double> boundary_errors(const BoundaryTargets& bc, const Eigen::MatrixXd& x) {
  double max = 0.0, sum = 0.0;
  std::size_t count = 0;
  for (std::size_t i = 0; i < bc.n_nodes(); ++i) {
    const auto col = static_cast<Eigen::Index>(i);
    double e = 0.0;
    if (bc.role[i] == NodeRole::Prescribed) e = (x.col(col) - bc.target.col(col)).norm();
    else if (bc.role[i] == NodeRole::Slide) e = std::abs(bc.normal.col(col).dot(x.col(col) - bc.target.col(col)));
    else continue;
    max = std::max(max, e);
    sum += e * e;
    ++count;
  }
  return {max, count ? std::sqrt(sum / static_cast<double>(count)) : 0.0};
}

BoundaryTargets fixed_boundary(const Mesh& mesh, const Topology& topology) {
  BoundaryTargets bc;
  bc.role.assign(mesh.n_nodes(), NodeRole::Free);
  bc.target = mesh.x;
  bc.normal = Eigen::MatrixXd::Zero(mesh.dim, static_cast<Eigen::Index>(mesh.n_nodes()));
  for (std::int32_t node : boundary_nodes(mesh, topology)) bc.role[static_cast<std::size_t>(node)] = NodeRole::Fixed;
  return bc;
}

std::filesystem::path step_path(const std::filesystem::path& out, int step) {
  char suffix[16];
  std::snprintf(suffix, sizeof suffix, "_%04d", step);
  return out.parent_path() / (out.stem().string() + suffix + out.extension().string());
}

void check_outputs(const std::vector<OutputFile>& outputs) {
  for (std::size_t i = 0; i < outputs.size(); ++i) {
    const OutputFile& o = outputs[i];
    // Where a later output cannot be written, an earlier one must not be either.
    std::error_code ec;
    if (std::filesystem::is_directory(o.path, ec))
      throw InputError(o.label + ": " + o.path.string() + " is a folder, not a file");
    const std::filesystem::path folder = o.path.parent_path().empty() ? std::filesystem::path(".") : o.path.parent_path();
    if (!std::filesystem::is_directory(folder, ec))
      throw InputError(o.label + ": " + o.path.string() + ": no folder " + folder.string());
    if (const auto input = o.may_replace_input ? std::nullopt : input_file_at(o.path))
      throw InputError(o.label + ": " + o.path.string() + " is a file this run reads (" + input->string() +
                       "), which only an output mesh you name yourself may replace");
    for (std::size_t j = 0; j < i; ++j)
      if (same_file(outputs[j].path, o.path))
        throw InputError(o.label + ": " + o.path.string() + " is also the file of " + outputs[j].label +
                         ": each output needs a path of its own");
  }
}

void check_outputs(const CaseFile* c, const std::optional<std::filesystem::path>& output,
                   const std::optional<std::filesystem::path>& report) {
  const std::string where = c ? c->file.string() + ": " : std::string();
  std::vector<OutputFile> outputs;
  // The command line's -o may name the output that the case leaves out.
  if (c && c->output_each_step && !output)
    throw InputError(where + "output_each_step: needs \"output\" (or -o) to name the step files");
  if (output) {
    outputs.push_back({where + (c ? "output" : "-o"), *output});
    if (c && c->output_each_step)
      for (int s = 1; s < c->steps; ++s)
        outputs.push_back({where + "output_each_step (step " + std::to_string(s) + ")", step_path(*output, s), false});
  }
  if (report) outputs.push_back({where + (c ? "report" : "--report"), *report, false});
  check_outputs(outputs);
}

QualityReport fill_result(Report& report, const Mesh& moved, const Mesh* input, const BoundaryTargets& bc) {
  QualityReport q = quality_report(moved, input);
  const auto [err_max, err_l2] = boundary_errors(bc, moved.x);
  report.dim = moved.dim;
  report.order = moved.order();
  report.nodes = moved.n_nodes();
  report.elements = moved.n_cells();
  report.inverted_elements = q.inverted_elements;
  report.valid = q.inverted_elements == 0;
  if (input) {
    report.min_quality = q.min_quality;
    report.mean_quality = q.mean_quality;
  }
  report.min_shape_quality = q.min_shape_quality;
  report.min_scaled_jacobian = q.min_scaled_jacobian;
  report.boundary_error_max = err_max;
  report.boundary_error_l2 = err_l2;
  if (!report.valid) {
    report.converged = false;
    report.message = std::to_string(q.inverted_elements) + " inverted elements" +
                     (report.message.empty() ? std::string() : "; " + report.message);
  }
  return q;
}

void write_result_mesh(const Report& report, const Mesh& moved, const QualityReport& q,
                       const std::optional<std::filesystem::path>& output) {
  if (!report.converged || !output) return;
  WriteOptions wo;
  if (!q.quality.empty()) wo.cell_data[std::string(kQualityField)] = q.quality;
  wo.cell_data[std::string(kShapeQualityField)] = q.shape_quality;
  write_mesh(*output, moved, wo);
}

void write_step_mesh(const std::filesystem::path& output, int step, const Mesh& mesh, int& written) {
  write_mesh(step_path(output, step), mesh);
  ++written;
}

Outcome print_result(std::ostream& out, const Report& report, const std::optional<std::filesystem::path>& output,
                     int step_files) {
  out << "result   " << report.message << "\n";
  if (report.converged && output) out << "wrote    " << output->string() << "\n";
  else if (output && step_files > 0)
    out << "wrote    no result mesh (the goal was not reached); the " << step_files << " increment"
        << (step_files > 1 ? "s" : "") << " before: " << step_path(*output, 1).string()
        << (step_files > 1 ? " ... " + step_path(*output, step_files).string() : std::string()) << "\n";
  else if (output) out << "wrote    no mesh (the goal was not reached)\n";
  char line[64];
  const int threads = omp_get_max_threads();  // the run's (use_method_threads)
  std::snprintf(line, sizeof line, "time     %.3f s on %d thread%s\n", report.seconds, threads, threads == 1 ? "" : "s");
  out << line;
  return report.converged ? Outcome::GoalReached : Outcome::GoalMissed;
}

}  // namespace meshmorph::detail
