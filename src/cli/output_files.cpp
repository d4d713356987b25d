// SPDX-License-Identifier: MIT
#include "cli/detail/output_files.h"

#include "cli/detail/plot_file.h"
#include "cli/detail/series_output.h"

#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <set>
#include <system_error>

#include <omp.h>

#include "meshmorph/error.h"
#include "meshmorph/io/foam.h"
#include "meshmorph/io/input_files.h"
#include "meshmorph/io/mesh_io.h"
#include "meshmorph/io/mesh_series.h"
#include "meshmorph/log.h"

namespace meshmorph::detail {

std::filesystem::path step_path(const std::filesystem::path& out, int step) {
  char suffix[16];
  std::snprintf(suffix, sizeof suffix, "_%04d", step);
  return out.parent_path() / (out.stem().string() + suffix + out.extension().string());
}

void check_outputs(const std::vector<OutputFile>& outputs) {
  std::set<std::filesystem::path> probed;
  for (std::size_t i = 0; i < outputs.size(); ++i) {
    const OutputFile& o = outputs[i];
    // Where a later output cannot be written, an earlier one must not be either.
    std::error_code ec;
    if (std::filesystem::is_directory(o.path, ec) && !is_foam_time_folder(o.path))  // OpenFOAM's points go in a folder
      throw InputError(o.label + ": " + o.path.string() + " is a folder, not a file");
    const std::filesystem::path folder = o.path.parent_path().empty() ? std::filesystem::path(".") : o.path.parent_path();
    if (!std::filesystem::is_directory(folder, ec))
      throw InputError(o.label + ": " + o.path.string() + ": no folder " + folder.string());
    // A run that cannot write its result should not run first: create and remove a file in
    // each folder once (the step files of a series share one).
    if (probed.insert(std::filesystem::absolute(folder).lexically_normal()).second) {
      std::string probe = (folder / ".meshmorph-probe-XXXXXX").string();
      const int fd = ::mkstemp(probe.data());
      if (fd < 0)
        throw IoError(o.label + ": " + o.path.string() + ": cannot write in " + folder.string() + ": " +
                      std::generic_category().message(errno));
      ::close(fd);
      ::unlink(probe.c_str());
    }
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
                   const std::optional<std::filesystem::path>& report, const std::optional<std::filesystem::path>& plot) {
  const std::string where = c ? c->file.string() + ": " : std::string();
  std::vector<OutputFile> outputs;
  // The command line's -o may name the output that the case leaves out.
  if (c && c->output_each_step && !output)
    throw InputError(where + "output_each_step: needs \"output\" (or -o) to name the step files");
  if (output) {
    outputs.push_back({where + (c ? "output" : "-o"), *output});
    if (c && c->output_each_step && !is_series_format(*output)) {  // (.cgns, .exo: the steps go in the output)
      for (int s = 1; s < c->steps; ++s)
        outputs.push_back({where + "output_each_step (step " + std::to_string(s) + ")", step_path(*output, s), false});
      if (const auto pvd = series_path(*output)) outputs.push_back({where + "output_each_step (series)", *pvd, false});
    }
  }
  if (report) outputs.push_back({where + (c ? "report" : "--report"), *report, false});
  if (plot) outputs.push_back({"--plot", *plot, false});
  check_outputs(outputs);
}

bool writes_mesh(const RunOutput& run) { return run.report.converged || run.extra.value("improved", false); }

void write_result_mesh(const RunOutput& run, const std::optional<std::filesystem::path>& output,
                       const std::map<std::string, Eigen::MatrixXd>& point_vectors) {
  if (!writes_mesh(run) || !output) return;
  write_mesh(*output, run.moved, mesh_options(run.quality, point_vectors));
}

WriteOptions mesh_options(const QualityReport& q, const std::map<std::string, Eigen::MatrixXd>& point_vectors) {
  WriteOptions wo;
  if (!q.quality.empty()) wo.cell_data[std::string(kQualityField)] = q.quality;
  wo.cell_data[std::string(kShapeQualityField)] = q.shape_quality;
  wo.point_vectors = point_vectors;
  return wo;
}

Outcome print_result(std::ostream& out, const Report& report, const std::optional<std::filesystem::path>& output,
                     int step_files, bool kept) {
  if (report.cell_types.size() > 1) {
    std::string types;
    for (const CellTypeMinima& t : report.cell_types) {
      std::string values;
      const auto put = [&](const char* name, const std::optional<double>& v) {
        if (!v) return;
        char value[48];
        std::snprintf(value, sizeof value, "%s%s %.4f", values.empty() ? "" : ", ", name, *v);
        values += value;
      };
      put("min", t.min_quality);
      put("shape", t.min_shape_quality);
      put("SJ", t.min_scaled_jacobian);
      types += (types.empty() ? "" : "; ") + t.type + ": " + values;
    }
    out << "by type  " << types << "\n";
  }
  out << "result   " << report.message << "\n";
  if (report.converged && output) out << "wrote    " << output->string() << "\n";
  else if (kept && output)
    out << "wrote    " << output->string() << " (valid and better than the input, though the goal was not reached)\n";
  else if (output && step_files > 0)
    out << "wrote    no result mesh (the goal was not reached); the " << step_files << " increment"
        << (step_files > 1 ? "s" : "") << " before: " << step_path(*output, 1).string()
        << (step_files > 1 ? " ... " + step_path(*output, step_files).string() : std::string()) << "\n";
  else if (output) out << "wrote    no mesh (the goal was not reached)\n";
  char line[64];
  const int threads = omp_get_max_threads();  // the run's (use_method_threads)
  std::snprintf(line, sizeof line, "time     %.3f s on %d thread%s\n", report.seconds, threads, threads == 1 ? "" : "s");
  out << line;
  if (report.timings && log_enabled(LogLevel::Detail)) out << timings_line(*report.timings) << "\n";
  return report.converged ? Outcome::GoalReached : Outcome::GoalMissed;
}

std::optional<CaseFile> case_or_mesh(const std::string& input) {
  if (std::filesystem::path(input).extension() == ".json") return read_case_file(input);
  return std::nullopt;
}

RunFiles run_files(const std::string& output, const std::string& report, const std::string& plot, const CaseFile* c,
                   const std::string& input, const std::string& suffix) {
  RunFiles f;
  if (!output.empty()) f.output = output;
  else if (c) f.output = c->output;
  else if (!suffix.empty()) {
    const std::filesystem::path in(input);
    f.output = in.parent_path() / (in.stem().string() + suffix + in.extension().string());
  }
  if (!report.empty()) f.report = report;
  else if (c) f.report = c->report;
  if (!plot.empty()) {
    check_plot_path(plot, "--plot");
    f.plot = plot;
  }
  if (c) f.case_file = input;
  check_outputs(c, f.output, f.report, f.plot);
  return f;
}

void write_run(RunOutput& run, const RunFiles& files, const RunTimings& timings, const Mesh& input,
               const std::map<std::string, Eigen::MatrixXd>& point_vectors) {
  run.report.case_file = files.case_file;
  write_result_mesh(run, files.output, point_vectors);
  if (writes_mesh(run) && files.plot) {
    write_comparison(*files.plot, input, run.moved);
    log_info("wrote " + files.plot->string());
  }
  stamp_times(run.report, timings);
  if (files.report) write_report(*files.report, run.report, run.extra);
}

std::string timings_line(const Timings& timings) {
  std::string line = "timings ";
  for (int p = 0; p < k_phases; ++p) {
    std::string name(phase_key(Phase(p)));
    std::replace(name.begin(), name.end(), '_', ' ');
    char part[64];
    std::snprintf(part, sizeof part, "%s %s %.3f s", p == 0 ? "" : ",", name.c_str(), timings[Phase(p)]);
    line += part;
  }
  return line;
}

std::string mesh_line(const Mesh& mesh) {
  return "mesh     " + std::to_string(mesh.dim) + "D, " + std::to_string(mesh.n_nodes()) + " nodes, " +
         std::to_string(mesh.n_cells()) + " cells, order " + std::to_string(mesh.order());
}

}  // namespace meshmorph::detail
