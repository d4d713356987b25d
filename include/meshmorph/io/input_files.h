// SPDX-License-Identifier: MIT
#pragma once
#include <filesystem>
#include <optional>

namespace meshmorph {

/// The files a run has read, so that an output the run names itself (a step file of
/// `output_each_step`) never replaces one (DESIGN §3.1: an input is never overwritten
/// unless the user names it as the output). Off by default; the
/// CLI turns it on, and then every reader notes the file it opens (meshes, case files,
/// displacement tables).
void record_input_files(bool on);

/// Notes `path` as read, when recording is on.
void note_input_file(const std::filesystem::path& path);

/// Whether two paths name the same file, existing or not.
bool same_file(const std::filesystem::path& a, const std::filesystem::path& b);

/// The noted input that `path` names (the same file by whatever path: a relative or
/// absolute name, a link), if any.
std::optional<std::filesystem::path> input_file_at(const std::filesystem::path& path);

}  // namespace meshmorph
