// SPDX-License-Identifier: MIT
#include "cli/detail/series_output.h"

#include <charconv>
#include <string_view>

#include "meshmorph/io/atomic_file.h"
#include "meshmorph/io/mesh_io.h"
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
    : input_(input), dt_(c ? c->dt : std::nullopt), each_step_(c && c->output_each_step), files_(files),
      previous_(input.x) {}

std::map<std::string, Eigen::MatrixXd> SeriesOutput::fields(const Mesh& mesh) const {
  std::map<std::string, Eigen::MatrixXd> v;
  if (mesh.x.cols() != input_.x.cols()) return v;  // a method that added nodes: no node's motion
  v["displacement"] = mesh.x - input_.x;
  if (dt_) v["mesh_velocity"] = (mesh.x - previous_) / *dt_;
  return v;
}

void SeriesOutput::step(int step, const Mesh& mesh) {
  if (each_step_ && files_.output) {
    const std::filesystem::path path = step_path(*files_.output, step);
    write_mesh(path, mesh, mesh_options(quality_report(mesh, &input_), fields(mesh)));
    written_.emplace_back(step, path);
  }
  previous_ = mesh.x;
  last_step_ = step;
}

void SeriesOutput::finish(RunOutput& run, const RunTimings& timings) {
  write_run(run, files_, timings, fields(run.moved));
  if (!each_step_ || !files_.output) return;
  const std::optional<std::filesystem::path> pvd = series_path(*files_.output);
  if (!pvd) return;
  std::vector<std::pair<double, std::filesystem::path>> series;
  const auto time_of = [&](int step) { return dt_ ? step * *dt_ : static_cast<double>(step); };
  for (const auto& [step, path] : written_) series.emplace_back(time_of(step), path);
  if (run.report.converged) series.emplace_back(time_of(last_step_ + 1), *files_.output);
  if (!series.empty()) write_pvd(*pvd, series);
}

}  // namespace meshmorph::detail
