// SPDX-License-Identifier: MIT
#include "cli/detail/plot_file.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <memory>
#include <numbers>
#include <ostream>

#include <cairo-svg.h>
#include <cairo.h>

#include "cli/detail/mesh_picture.h"
#include "meshmorph/error.h"
#include "meshmorph/io/atomic_file.h"

namespace meshmorph::detail {
namespace {

constexpr double kSide = 480.0;  // a panel's width and height, in pixels (matplotlib's 6 inches at 80 dpi)
constexpr double kUnit = kSide / 600.0;  // the layout's unit: a panel is 600 units wide
constexpr double kWorst = 0.05;  // the fraction of cells outlined
constexpr int kBins = 40;

// matplotlib's viridis at 33 evenly spaced points; linear between them (within 2.5/255).
constexpr std::array<std::array<double, 3>, 33> kViridis = {{
    {0.2670, 0.0049, 0.3294}, {0.2770, 0.0503, 0.3757}, {0.2823, 0.0950, 0.4173},
    {0.2829, 0.1359, 0.4534}, {0.2788, 0.1755, 0.4834}, {0.2706, 0.2141, 0.5071},
    {0.2590, 0.2515, 0.5247}, {0.2450, 0.2877, 0.5373}, {0.2297, 0.3224, 0.5457},
    {0.2143, 0.3556, 0.5512}, {0.1994, 0.3876, 0.5546}, {0.1856, 0.4186, 0.5568},
    {0.1727, 0.4488, 0.5579}, {0.1607, 0.4785, 0.5581}, {0.1490, 0.5081, 0.5573},
    {0.1378, 0.5375, 0.5549}, {0.1276, 0.5669, 0.5506}, {0.1206, 0.5964, 0.5436},
    {0.1206, 0.6258, 0.5335}, {0.1323, 0.6550, 0.5197}, {0.1579, 0.6838, 0.5017},
    {0.1966, 0.7118, 0.4792}, {0.2461, 0.7389, 0.4520}, {0.3041, 0.7647, 0.4199},
    {0.3692, 0.7889, 0.3829}, {0.4401, 0.8111, 0.3410}, {0.5160, 0.8312, 0.2943},
    {0.5958, 0.8487, 0.2433}, {0.6785, 0.8637, 0.1895}, {0.7624, 0.8764, 0.1371},
    {0.8456, 0.8873, 0.0997}, {0.9261, 0.8973, 0.1041}, {0.9932, 0.9062, 0.1439},
}};

struct Rect {
  double left, top, right, bottom;
  double width() const { return right - left; }
  double height() const { return bottom - top; }
};

// The value range of the colours and the histograms: NumPy's for an empty one.
struct Scale {
  double low, high;
  double at(double v) const { return std::clamp((v - low) / (high - low), 0.0, 1.0); }
};

using Context = std::unique_ptr<cairo_t, decltype(&cairo_destroy)>;

// The colour of `t` in [0, 1] (light grey for NaN), mixed with `dark` of dark grey.
void set_colour(cairo_t* cr, double t, double dark = 0.0) {
  Eigen::Vector3d c = Eigen::Vector3d::Constant(0.8);
  if (std::isfinite(t)) {
    const double at = t * (kViridis.size() - 1);
    const auto k = std::min(static_cast<std::size_t>(at), kViridis.size() - 2);
    const Eigen::Vector3d a(kViridis[k].data()), b(kViridis[k + 1].data());
    c = a + (at - static_cast<double>(k)) * (b - a);
  }
  c = (1.0 - dark) * c + dark * Eigen::Vector3d::Constant(0.25);
  cairo_set_source_rgb(cr, c.x(), c.y(), c.z());
}

// Text with its reference point at (x, y): `align` 0 left, 0.5 centred, 1 right; `turn` a
// quarter turn counterclockwise (the labels of vertical axes).
void text(cairo_t* cr, const std::string& s, double x, double y, double size, double align = 0.5, bool turn = false) {
  cairo_save(cr);
  cairo_set_font_size(cr, size);
  cairo_text_extents_t e;
  cairo_text_extents(cr, s.c_str(), &e);
  cairo_translate(cr, x, y);
  if (turn) cairo_rotate(cr, -std::numbers::pi / 2);
  cairo_move_to(cr, -align * e.x_advance, 0.0);
  cairo_set_source_rgb(cr, 0, 0, 0);
  cairo_show_text(cr, s.c_str());
  cairo_restore(cr);
}

// Round tick values in [low, high]: steps of 1, 2 or 5 times a power of ten, about five.
std::vector<double> ticks(double low, double high) {
  const double raw = (high - low) / 5.0;
  const double power = std::pow(10.0, std::floor(std::log10(raw)));
  const double f = raw / power;
  const double step = (f < 1.5 ? 1.0 : f < 3.0 ? 2.0 : f < 7.0 ? 5.0 : 10.0) * power;
  std::vector<double> t;
  for (double v = std::ceil(low / step - 1e-9) * step; v <= high + 1e-9 * step; v += step) t.push_back(v == 0.0 ? 0.0 : v);
  return t;
}

std::string tick_label(double v, double step) {
  char s[32];
  std::snprintf(s, sizeof s, "%.*f", std::max(0, -static_cast<int>(std::floor(std::log10(step) + 1e-9))), v);
  return s;
}

void stroke_outline(cairo_t* cr, const Face& face, const Eigen::Vector2d& origin, double scale) {
  cairo_new_path(cr);
  for (const Eigen::Vector2d& p : face.outline)
    cairo_line_to(cr, origin.x() + scale * p.x(), origin.y() - scale * p.y());
  cairo_close_path(cr);
}

// The mesh in `box`, at one scale in x and y, centred.
void draw_mesh(cairo_t* cr, const Mesh& mesh, const std::vector<double>& values, const std::vector<bool>& worst,
               const Scale& scale, const Rect& box) {
  const std::vector<Face> faces = mesh_faces(mesh);
  Eigen::Vector2d low = Eigen::Vector2d::Constant(HUGE_VAL), high = -low;
  for (const Face& f : faces)
    for (const Eigen::Vector2d& p : f.outline) {
      low = low.cwiseMin(p);
      high = high.cwiseMax(p);
    }
  const Eigen::Vector2d size = (high - low).cwiseMax(1e-300);
  const double s = std::min(box.width() / size.x(), box.height() / size.y());
  const Eigen::Vector2d middle = 0.5 * (low + high);
  const Eigen::Vector2d origin(0.5 * (box.left + box.right) - s * middle.x(), 0.5 * (box.top + box.bottom) + s * middle.y());
  const bool solid = mesh.dim == 3;  // faces hide those behind: their edges are painted with them
  // Cells and edges without antialiasing, and 64 colours of the map: a PNG of a few thousand
  // cells compresses to less than half. The edges are one pixel of the cell's colour darkened, where
  // matplotlib's are thin grey.
  cairo_save(cr);
  cairo_set_antialias(cr, CAIRO_ANTIALIAS_NONE);
  cairo_set_line_width(cr, 1.0);
  for (const Face& f : faces) {
    const double t = std::round(64 * scale.at(values[static_cast<std::size_t>(f.cell)])) / 64;
    stroke_outline(cr, f, origin, s);
    set_colour(cr, t);
    cairo_fill_preserve(cr);
    const bool red = solid && worst[static_cast<std::size_t>(f.cell)];
    red ? cairo_set_source_rgb(cr, 1, 0, 0) : set_colour(cr, t, 0.4);
    cairo_stroke(cr);
  }
  cairo_set_source_rgb(cr, 1, 0, 0);
  for (const Face& f : faces)
    if (!solid && worst[static_cast<std::size_t>(f.cell)]) {
      stroke_outline(cr, f, origin, s);
      cairo_stroke(cr);
    }
  cairo_restore(cr);
}

void draw_colour_bar(cairo_t* cr, const Scale& scale, const Rect& bar, const std::string& label, double label_x) {
  cairo_pattern_t* gradient = cairo_pattern_create_linear(0, bar.bottom, 0, bar.top);
  for (std::size_t k = 0; k < kViridis.size(); ++k)
    cairo_pattern_add_color_stop_rgb(gradient, static_cast<double>(k) / (kViridis.size() - 1), kViridis[k][0],
                                     kViridis[k][1], kViridis[k][2]);
  cairo_rectangle(cr, bar.left, bar.top, bar.width(), bar.height());
  cairo_set_source(cr, gradient);
  cairo_fill_preserve(cr);
  cairo_pattern_destroy(gradient);
  cairo_set_source_rgb(cr, 0, 0, 0);
  cairo_set_line_width(cr, 0.8);
  cairo_stroke(cr);
  const std::vector<double> t = ticks(scale.low, scale.high);
  for (const double v : t) {
    const double y = bar.bottom - scale.at(v) * bar.height();
    cairo_move_to(cr, bar.right, y);
    cairo_line_to(cr, bar.right + 4, y);
    cairo_stroke(cr);
    text(cr, tick_label(v, t.size() > 1 ? t[1] - t[0] : 1.0), bar.right + 7, y + 4, 11, 0.0);
  }
  text(cr, label, label_x, 0.5 * (bar.top + bar.bottom), 12, 0.5, true);
}

void draw_histogram(cairo_t* cr, const std::vector<double>& values, const Scale& scale, const Rect& box,
                    const std::string& label) {
  std::array<int, kBins> count{};
  for (const double v : values)
    if (std::isfinite(v) && v >= scale.low && v <= scale.high)
      ++count[std::min(static_cast<std::size_t>(scale.at(v) * kBins), std::size_t{kBins - 1})];
  const int most = std::max(1, *std::max_element(count.begin(), count.end()));
  const double width = box.width() / kBins;
  cairo_set_source_rgb(cr, 0.2745, 0.5098, 0.7059);  // matplotlib's steelblue
  for (int k = 0; k < kBins; ++k)
    if (count[static_cast<std::size_t>(k)] > 0) {
      const double h = box.height() * count[static_cast<std::size_t>(k)] / most;
      cairo_rectangle(cr, box.left + k * width, box.bottom - h, width, h);
    }
  cairo_fill(cr);
  cairo_set_source_rgb(cr, 0, 0, 0);
  cairo_set_line_width(cr, 0.8);
  cairo_rectangle(cr, box.left, box.top, box.width(), box.height());
  cairo_stroke(cr);
  const std::vector<double> tx = ticks(scale.low, scale.high);
  for (const double v : tx) {
    const double x = box.left + scale.at(v) * box.width();
    cairo_move_to(cr, x, box.bottom);
    cairo_line_to(cr, x, box.bottom + 4);
    cairo_stroke(cr);
    text(cr, tick_label(v, tx.size() > 1 ? tx[1] - tx[0] : 1.0), x, box.bottom + 15, 10);
  }
  const std::vector<double> ty = ticks(0.0, most);
  for (const double v : ty) {
    if (v != std::round(v)) continue;  // whole cells
    const double y = box.bottom - box.height() * v / most;
    cairo_move_to(cr, box.left - 4, y);
    cairo_line_to(cr, box.left, y);
    cairo_stroke(cr);
    text(cr, tick_label(v, 1.0), box.left - 6, y + 4, 10, 1.0);
  }
  text(cr, label, 0.5 * (box.left + box.right), box.bottom + 32, 11);
  text(cr, "cells", box.left - 45, 0.5 * (box.top + box.bottom), 11, 0.5, true);
}

// Panel `k` from the left. The mesh is drawn in pixels (its edges one pixel wide), the rest in the layout's units.
void draw_panel(cairo_t* cr, const PlotPanel& panel, const Scale& scale, const std::string& label, std::size_t k) {
  const double x = 600.0 * static_cast<double>(k);
  const std::vector<bool> worst = worst_cells(panel.values, kWorst);
  double low = HUGE_VAL;
  for (const double v : panel.values)
    if (std::isfinite(v)) low = std::min(low, v);
  char title[64];
  std::snprintf(title, sizeof title, ": min %.3f, %zu worst outlined", low,
                static_cast<std::size_t>(std::count(worst.begin(), worst.end(), true)));
  draw_mesh(cr, *panel.mesh, panel.values, worst, scale, {kUnit * (x + 15), kUnit * 35, kUnit * (x + 485), kUnit * 420});
  cairo_save(cr);
  cairo_scale(cr, kUnit, kUnit);
  text(cr, panel.title + title, x + 300, 20, 13);
  draw_colour_bar(cr, scale, {x + 500, 90, x + 514, 365}, label, x + 578);
  draw_histogram(cr, panel.values, scale, {x + 70, 450, x + 485, 535}, label);
  cairo_restore(cr);
}

cairo_status_t write_to(void* closure, const unsigned char* data, unsigned int length) {
  auto& out = *static_cast<std::ostream*>(closure);
  out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(length));
  return out ? CAIRO_STATUS_SUCCESS : CAIRO_STATUS_WRITE_ERROR;
}

void check(cairo_status_t status, const std::filesystem::path& path) {
  if (status != CAIRO_STATUS_SUCCESS) throw IoError(path.string() + ": cairo: " + cairo_status_to_string(status));
}

}  // namespace

void check_plot_path(const std::filesystem::path& path, const std::string& option) {
  const std::filesystem::path ext = path.extension();
  if (ext != ".png" && ext != ".svg")
    throw InputError(option + ": " + path.string() + ": a picture is written as .png or .svg, by its extension");
}

void write_plot(const std::filesystem::path& path, const std::vector<PlotPanel>& panels, const std::string& label) {
  Scale scale{HUGE_VAL, -HUGE_VAL};
  for (const PlotPanel& p : panels) {
    if (p.mesh->n_cells() == 0) throw InputError(p.title + ": no cells to draw");
    for (const double v : p.values)
      if (std::isfinite(v)) scale = {std::min(scale.low, v), std::max(scale.high, v)};
  }
  if (scale.low > scale.high) throw InputError(path.string() + ": no cell has a finite " + label);
  if (scale.high - scale.low <= 1e-12 * std::max(1.0, std::abs(scale.low))) scale = {scale.low - 0.5, scale.high + 0.5};

  const double width = kSide * static_cast<double>(panels.size());
  const bool svg = path.extension() == ".svg";
  write_atomically(path, true, [&](std::ostream& out) {
    std::unique_ptr<cairo_surface_t, decltype(&cairo_surface_destroy)> surface(
        svg ? cairo_svg_surface_create_for_stream(write_to, &out, width, kSide)
            : cairo_image_surface_create(CAIRO_FORMAT_RGB24, static_cast<int>(width), static_cast<int>(kSide)),
        cairo_surface_destroy);
    check(cairo_surface_status(surface.get()), path);
    {
      const Context cr(cairo_create(surface.get()), cairo_destroy);
      cairo_set_source_rgb(cr.get(), 1, 1, 1);
      cairo_paint(cr.get());
      cairo_select_font_face(cr.get(), "sans-serif", CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_NORMAL);
      for (std::size_t k = 0; k < panels.size(); ++k)
        draw_panel(cr.get(), panels[k], scale, label, k);
      check(cairo_status(cr.get()), path);
    }
    if (svg) cairo_surface_finish(surface.get());
    else check(cairo_surface_write_to_png_stream(surface.get(), write_to, &out), path);
    check(cairo_surface_status(surface.get()), path);
  });
}

void write_comparison(const std::filesystem::path& path, const Mesh& input, const Mesh& output) {
  CellField before = cell_field(input, "shape_quality", nullptr);
  CellField after = cell_field(output, "shape_quality", nullptr);
  write_plot(path, {{&input, std::move(before.values), "input"}, {&output, std::move(after.values), "output"}}, before.label);
}

}  // namespace meshmorph::detail
