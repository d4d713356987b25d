// SPDX-License-Identifier: MIT
#include "cli/detail/series_output.h"

#include <charconv>
#include <string_view>

#include "meshmorph/io/atomic_file.h"
#include "meshmorph/io/mesh_io.h"
#include "meshmorph/io/mesh_series.h"
#include "meshmorph/quality/quality_report.h"

namespace meshmorph::detail {
namespace {

// ParaView's collection format: one DataSet per file, at its time, names relative to the
// .pvd's own folder (every file of a series lies beside it).
void write_pvd(const std::filesystem::path& path, const std::vector<std::pair<double, std::filesystem::path>>& files) {
  write_atomically(path, false, [&](std::ostream& out) {
    out << "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
        << "  <Collection>\n";
    char time[32];
    for (const auto& [t, file] : files) {
      const auto end = std::to_chars(time, time + sizeof time, t).ptr;  // shortest exact
      out << "    <DataSet timestep=\"" << std::string_view(time, static_cast<std::size_t>(end - time))
          << "\" part=\"0\" file=\"" << file.filename().string() << "\"/>\n";
    }
    out << "  </Collection>\n</VTKFile>\n";
  });
}

}  // namespace

std::optional<std::filesystem::path> series_path(const std::filesystem::path& output) {
  if (output.extension() != ".vtu") return std::nullopt;
  return std::filesystem::path(output).replace_extension(".pvd");
}

SeriesOutput::SeriesOutput(const Mesh& input, const CaseFile* c, const RunFiles& files)
    : input_(input), dt_(c ? c->dt : std::nullopt), each_step_(c && c->output_each_step),
      one_file_(each_step_ && files.output && is_series_format(*files.output)), files_(files), previous_(input.x) {}

std::map<std::string, Eigen::MatrixXd> SeriesOutput::fields(const Eigen::MatrixXd& x, const Eigen::MatrixXd& previous) const {
  std::map<std::string, Eigen::MatrixXd> v;
  if (x.cols() != input_.x.cols()) return v;  // a method that added nodes: no node's motion
  v["displacement"] = x - input_.x;
  if (dt_) v["mesh_velocity"] = (x - previous) / *dt_;
  return v;
}

void SeriesOutput::step(int step, const Mesh& mesh) {
  if (one_file_) {
    kept_.push_back({step, mesh.x, mesh_options(quality_report(mesh, &input_), {}).cell_data});
  } else if (each_step_ && files_.output) {
    const std::filesystem::path path = step_path(*files_.output, step);
    write_mesh(path, mesh, mesh_options(quality_report(mesh, &input_), fields(mesh.x, previous_)));
    written_.emplace_back(step, path);
  }
  previous_ = mesh.x;
  last_step_ = step;
}

// The input's cells and groups at the start positions; a step each increment and the result.
void SeriesOutput::write_one_file(const RunOutput& run) const {
  const int n = static_cast<int>(kept_.size()) + 1;
  write_mesh_series(*files_.output, input_, n, [&](int k) {
    const bool result = k + 1 == n;
    const auto at = static_cast<std::size_t>(k);
    MeshStep s;
    s.x = result ? run.moved.x : kept_[at].x;
    s.time = time_of(result ? last_step_ + 1 : kept_[at].step);
    s.point_vectors = fields(s.x, k == 0 ? input_.x : kept_[at - 1].x);
    s.cell_data = result ? mesh_options(run.quality, {}).cell_data : kept_[at].cell_data;
    return s;
  });
}

void SeriesOutput::finish(RunOutput& run, const RunTimings& timings) {
  if (one_file_) {
    if (writes_mesh(run)) write_one_file(run);
    RunFiles report_only = files_;
    report_only.output.reset();
    write_run(run, report_only, timings, input_);
    return;
  }
  write_run(run, files_, timings, input_, fields(run.moved.x, previous_));
  if (!each_step_ || !files_.output) return;
  const std::optional<std::filesystem::path> pvd = series_path(*files_.output);
  if (!pvd) return;
  std::vector<std::pair<double, std::filesystem::path>> series;
  for (const auto& [step, path] : written_) series.emplace_back(time_of(step), path);
  if (writes_mesh(run)) series.emplace_back(time_of(last_step_ + 1), *files_.output);
  if (!series.empty()) write_pvd(*pvd, series);
}

}  // namespace meshmorph::detail
