// SPDX-License-Identifier: MIT
#pragma once
#include <filesystem>
#include <string>
#include <vector>

#include "meshmorph/mesh/mesh.h"

namespace meshmorph::detail {

/// One mesh of a picture: its cells' values (one per cell, cell_field) and its title.
struct PlotPanel {
  const Mesh* mesh = nullptr;
  std::vector<double> values;
  std::string title;
};

/// Throws InputError unless `path` ends in .png or .svg (`option` names where it came from).
void check_plot_path(const std::filesystem::path& path, const std::string& option);

/// Draws the panels side by side (480 × 480 pixels each; SVG: points) with cairo, as Python's
/// meshmorph.plot draws them: each mesh (mesh_faces) with its cells filled by the viridis
/// colour map on one scale over all panels, the worst 5 % (worst_cells) outlined in red, its
/// minimum and the number outlined in its title, a colour bar labelled `label`, and a
/// histogram of 40 bins beneath. PNG or SVG by the extension; written atomically. Throws
/// InputError where every value is NaN or a panel has no cells, IoError where cairo fails.
void write_plot(const std::filesystem::path& path, const std::vector<PlotPanel>& panels, const std::string& label);

/// `input` and `output` side by side, coloured by their shape quality (meshmorph.plot.compare).
void write_comparison(const std::filesystem::path& path, const Mesh& input, const Mesh& output);

}  // namespace meshmorph::detail
