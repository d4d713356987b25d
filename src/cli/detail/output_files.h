// SPDX-License-Identifier: MIT
#pragma once
#include <filesystem>
#include <map>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include "meshmorph/app/case_file.h"
#include "meshmorph/app/report.h"
#include "meshmorph/app/run_output.h"
#include "meshmorph/cli/commands.h"
#include "meshmorph/io/mesh_io.h"

namespace meshmorph::detail {

/// `out` with the step number before the extension: out_0003.vtu (`output_each_step`).
std::filesystem::path step_path(const std::filesystem::path& out, int step);

/// A file a command writes: the key or option that gives it (for messages), its path, and
/// whether it may replace a file the run reads: only a mesh the user names (DESIGN §3.1), not
/// a report (a typo would put JSON over the mesh it describes) nor a file the command names
/// itself (the step files of `output_each_step`).
struct OutputFile {
  std::string label;
  std::filesystem::path path;
  bool may_replace_input = true;
};

/// Throws InputError, before anything is written, where an output is a folder or its folder
/// does not exist, two outputs share a file (the later would replace the earlier) or an
/// output that may not replace an input is a file the run read: DESIGN §3.1 lets an input be
/// replaced only where the user names it as the output.
void check_outputs(const std::vector<OutputFile>& outputs);

/// check_outputs for a method command: its mesh `output` (and, with `output_each_step`, the
/// step meshes), its `report` and its `plot` (--plot), labelled by the case file's keys, or by
/// the command-line options where `c` is null (a bare mesh).
void check_outputs(const CaseFile* c, const std::optional<std::filesystem::path>& output,
                   const std::optional<std::filesystem::path>& report,
                   const std::optional<std::filesystem::path>& plot = std::nullopt);

/// How a method's mesh is written: its per-cell quality as cell data, `point_vectors` as point data.
WriteOptions mesh_options(const QualityReport& q, const std::map<std::string, Eigen::MatrixXd>& point_vectors);

/// Whether a run's mesh is written (DESIGN §3.1): when the run reached its goal, or when its
/// runner marks the result "improved" in run.extra (optimize, untangle: valid and better than
/// the input although the goal was not reached).
bool writes_mesh(const RunOutput& run);

/// Writes run.moved with its per-cell quality to `output` where writes_mesh(run).
void write_result_mesh(const RunOutput& run, const std::optional<std::filesystem::path>& output,
                       const std::map<std::string, Eigen::MatrixXd>& point_vectors = {});

/// The last lines of a method's summary (result, what was written, time) and its outcome.
/// `kept`: a mesh was written although the goal was not reached (writes_mesh).
Outcome print_result(std::ostream& out, const Report& report, const std::optional<std::filesystem::path>& output,
                     int step_files = 0, bool kept = false);

/// The case file `input` names (a .json path), or none for a bare mesh.
std::optional<CaseFile> case_or_mesh(const std::string& input);

/// The files a method command writes: its mesh (-o, else the case's "output"; for a bare
/// mesh, NAME<suffix>.EXT beside it when `suffix` is given), its report (--report, else the
/// case's "report") and its picture (--plot), and the case file (null for a bare mesh) that
/// the report names.
struct RunFiles {
  std::optional<std::filesystem::path> output;
  std::optional<std::filesystem::path> report;
  std::optional<std::filesystem::path> plot;
  std::optional<std::string> case_file;
};

/// The run's files, checked by check_outputs (and the picture's extension, check_plot_path):
/// call it once every input is read.
RunFiles run_files(const std::string& output, const std::string& report, const std::string& plot, const CaseFile* c,
                   const std::string& input, const std::string& suffix = "");

/// Writes a run's mesh (write_result_mesh), its picture beside `input` (write_comparison)
/// where that mesh is written (writes_mesh), and its report (write_report, with `case`, `seconds` and
/// `timings` filled, the writing of the others included) where `files` ask for them.
void write_run(RunOutput& run, const RunFiles& files, const RunTimings& timings, const Mesh& input,
               const std::map<std::string, Eigen::MatrixXd>& point_vectors = {});

/// "timings  assembly 0.41 s, validity 0.05 s, ...": the seconds by phase, for --verbose.
std::string timings_line(const Timings& timings);

/// "mesh     2D, 1265 nodes, 2304 cells, order 1": the line every method's summary starts with.
std::string mesh_line(const Mesh& mesh);

}  // namespace meshmorph::detail
