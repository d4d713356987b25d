// SPDX-License-Identifier: MIT
#include "meshmorph/app/fit_case.h"

#include <algorithm>
#include <cstdio>
#include <cmath>
#include <optional>
#include <stdexcept>
#include <utility>

#include "app/detail/fit_features.h"
#include "app/detail/fit_pillowing.h"
#include "app/detail/method_output.h"
#include "app/detail/solver_option.h"
#include "meshmorph/app/option_reader.h"
#include "meshmorph/error.h"
#include "meshmorph/fem/elevate.h"
#include "meshmorph/fem/trace.h"
#include "meshmorph/fem/validity.h"
#include "meshmorph/io/mesh_io.h"
#include "meshmorph/mesh/pillow.h"

namespace meshmorph {
namespace {

// The level set must be a number at every node and cross the mesh: σ takes both signs over
// its nodes.
void check_crossing(const LevelSetFunction& sigma, const Mesh& mesh, const std::string& where) {
  double lo = 0.0, hi = 0.0;
  for (Eigen::Index i = 0; i < mesh.x.cols(); ++i) {
    const double v = sigma.value(mesh.x.col(i));
    if (!std::isfinite(v))
      throw InputError(where + ": the level set is " + (std::isnan(v) ? "not a number" : "infinite") + " at node " +
                       std::to_string(mesh.node_tags.empty() ? i + 1 : mesh.node_tags[static_cast<std::size_t>(i)]));
    lo = std::min(lo, v);
    hi = std::max(hi, v);
  }
  if (!(lo < 0.0 && hi > 0.0))
    throw InputError(where + ": the level set has no zero crossing in the mesh (sigma is " +
                     (hi <= 0.0 ? "negative" : "positive") + " at every node)");
}

// A `mesh` or `distance` level set must cover the mesh: every node inside its background's
// bounding box (the background interpolates, it does not extrapolate meaningfully).
void check_coverage(const LevelSet& ls, const Mesh& mesh, const std::string& where) {
  if (const auto* m = std::get_if<MeshLevelSet>(&ls.shape)) {
    const Mesh background = read_mesh(m->file);
    const Eigen::VectorXd lo = background.x.rowwise().minCoeff(), hi = background.x.rowwise().maxCoeff();
    const double slack = 1e-9 * (hi - lo).norm();
    for (Eigen::Index i = 0; i < mesh.x.cols(); ++i)
      if (((mesh.x.col(i) - lo).array() < -slack).any() || ((mesh.x.col(i) - hi).array() > slack).any())
        throw InputError(where + ".mesh.file: " + m->file.string() + " does not cover the mesh (node " +
                         std::to_string(mesh.node_tags.empty() ? i + 1 : mesh.node_tags[static_cast<std::size_t>(i)]) +
                         " lies outside its bounding box)");
    return;
  }
  if (const auto* d = std::get_if<DistanceLevelSet>(&ls.shape)) {
    const double slack = 1e-9 * (d->upper - d->lower).norm();
    for (Eigen::Index i = 0; i < mesh.x.cols(); ++i)
      if (((mesh.x.col(i) - d->lower).array() < -slack).any() || ((mesh.x.col(i) - d->upper).array() > slack).any())
        throw InputError(where + ".distance: the box [lower, upper] does not cover the mesh (node " +
                         std::to_string(mesh.node_tags.empty() ? i + 1 : mesh.node_tags[static_cast<std::size_t>(i)]) +
                         " lies outside it)");
    return;
  }
  std::visit([&](const auto& shape) {
    if constexpr (requires { shape.operands; })
      for (const LevelSet& operand : shape.operands) check_coverage(operand, mesh, where);
  }, ls.shape);
}

// The mean shape distortion of the input against the ideal target above which fit takes
// the input target: regular cells (squares, cubes: 0) and right triangles (0.15) keep the
// ideal target; cubes cut into 24 tetrahedra around their centre (0.5) take the input.
constexpr double kInputTargetDistortion = 0.2;

std::string format_distortion(double distortion) {
  char buffer[128];
  std::snprintf(buffer, sizeof buffer, "mean shape distortion of the input against the ideal target %.3g %s %.3g", distortion,
                distortion > kInputTargetDistortion ? ">" : "<=", kInputTargetDistortion);
  return buffer;
}

// A level set of the case, compiled after the checks above.
LevelSetFunction checked_level_set(const LevelSet& ls, const Mesh& mesh, const LevelSetOptions& options,
                                   const std::string& where) {
  check_coverage(ls, mesh, where);
  LevelSetFunction sigma(ls, mesh.dim, options);
  check_crossing(sigma, mesh, where);
  return sigma;
}

}  // namespace

FitSettings read_fit_settings(const CaseFile& c, int threads) {
  FitSettings s;
  FitOptions& o = s.fit;
  OptionReader r(c.options, c.file.string());
  r.read("metric", o.metric, {"mu2", "mu303", "mu77", "mu80"});
  std::string target = "ideal", weights = "adaptive";
  s.target_given = r.has("target");
  s.eps_sigma_given = r.has("eps_sigma");
  r.read("target", target, {"ideal", "input", "ideal_unit"});
  o.target = target_kind(target);
  r.read("weight0", o.weight0, 0.0, 1e30);
  r.read("penalty0", o.penalty0, 1e-12, 1e12);
  r.read("weights", weights, {"adaptive", "constant"});
  o.adaptive = weights == "adaptive";
  r.read("alpha_sigma", o.alpha_sigma, 1.0 + 1e-12, 1e6);
  r.read("eps_dsigma", o.eps_dsigma, 0.0, 1.0);
  r.read("eps_sigma", o.eps_sigma, 1e-300, 1e300);
  r.read("n_sigma", o.n_sigma, 1, 100000);
  r.read("max_newton", o.max_newton, 1, 100000);
  r.read("growth", o.growth, 1.0, 1e6);
  r.read("det_floor", o.det_floor, 0.0, 1.0);
  r.read("flat_edges", o.flat_edges);
  r.read("split", s.split);
  std::string level_set = "analytic";
  r.read("level_set", level_set, {"analytic", "discrete"});
  s.discrete = level_set == "discrete";
  r.read("materials", s.materials);
  if (const auto it = c.options.find("pillow"); it != c.options.end() && it->is_boolean()) {
    bool on = false;
    r.read("pillow", on);
    s.pillow = on ? "true" : "false";
  } else {
    r.read("pillow", s.pillow, {"auto"});
  }
  r.read("features", s.features);
  o.solver = detail::read_solver(r);
  r.finish();
  o.threads = threads;
  return s;
}


FitSetup prepare_fit(const CaseFile& c, Mesh mesh, const FitSettings& settings, const std::string& where) {
  if ((settings.fit.metric == "mu2" && mesh.dim != 2) || (settings.fit.metric == "mu303" && mesh.dim != 3))
    throw InputError(where + ": options.metric: " + settings.fit.metric + " is a " + (mesh.dim == 2 ? "3D" : "2D") +
                     " metric (mu2 in 2D, mu303 in 3D)");
  if (!c.interface && !c.trim && std::none_of(c.boundary.begin(), c.boundary.end(), [](const BoundaryCondition& b) {
        return std::holds_alternative<ProjectMotion>(b.motion);
      }))
    throw InputError(where + ": nothing to fit: give \"interface\", \"trim\" or a boundary entry with \"project\"");
  LevelSetOptions lso;
  lso.source = where;
  lso.length_scale = (mesh.x.rowwise().maxCoeff() - mesh.x.rowwise().minCoeff()).norm();
  FitSetup s;
  s.fit = settings.fit;
  nlohmann::ordered_json& choices = s.choices;
  if (!settings.eps_sigma_given) {
    s.fit.eps_sigma = 1e-9 * lso.length_scale;
    choices["eps_sigma"] = {{"value", s.fit.eps_sigma}, {"why", "1e-9 of the diagonal of the mesh's bounding box"}};
  }
  // Pillowing (docs/fit.md): a layer of cells on each side of the fitted surface that has a
  // cell with two or more facets on it; "auto" pillows hexahedra only.
  const bool tensor = std::ranges::any_of(mesh.cells, [&](const CellBlock& b) {
    return b.type == ElementType::Hexahedron || (settings.pillow == "true" && b.type == ElementType::Quadrilateral);
  });
  if (settings.pillow == "true" && mesh.order() != 1)
    throw InputError(where + ": options.pillow: pillowing needs a linear mesh (raise it with \"order\")");
  const bool may_pillow = settings.pillow == "true" ||
                          (settings.pillow == "auto" && tensor && mesh.order() == 1 && mesh.dim == 3 && !settings.fit.flat_edges);
  const bool reduce_crowding = !settings.fit.flat_edges && !may_pillow;
  const bool split = settings.split && !may_pillow;
  // Vertex-star flips on tetrahedra (no split follows in 3D; hexahedra are pillowed instead).
  const bool stars = std::ranges::any_of(mesh.cells, [](const CellBlock& b) { return b.type == ElementType::Tetrahedron; });
  std::vector<std::string> pillowed_sides;
  std::size_t filled = 0;
  // Pillows the side of `marked` when one of its cells has two or more flagged facets;
  // returns where the new mesh's cells come from (nothing when it did not pillow).
  const auto pillow_side = [&](const std::vector<std::vector<std::uint8_t>>& marked, const std::string& name) {
    if (!may_pillow || !detail::crowded(marked)) return std::optional<Pillowed>();
    Pillowed p;
    try {
      p = pillow(mesh, build_topology(mesh), marked);
    } catch (const std::invalid_argument& e) {
      throw InputError(where + ": options.pillow: " + e.what());
    }
    if (count_invalid_cells(p.mesh) > 0) throw InputError(where + ": pillowing the " + name + " left an invalid cell");
    mesh = std::move(p.mesh);
    s.pillowed_cells += p.added;
    pillowed_sides.push_back(name);
    return std::optional<Pillowed>(std::move(p));
  };

  // Trim (§4.2): the cells outside the level set go (eq. 10, corrected like an interface),
  // and the new boundary is fitted.
  std::size_t split_count = 0, two_facet_cells = 0;
  std::optional<LevelSetFunction> trim;
  std::vector<std::vector<std::uint8_t>> cut;
  if (c.trim) {
    trim.emplace(checked_level_set(*c.trim, mesh, lso, where + ": trim"));
    Topology topo = build_topology(mesh);
    std::vector<std::int32_t> to_split;
    std::vector<std::uint8_t> keep = correct_indicators(topo, material_indicators(mesh, *trim), to_split, reduce_crowding, stars);
    if (may_pillow && detail::crowded(detail::facets_of_side(topo, keep, 1))) filled += detail::fill_saddles(mesh, topo, keep, 1);
    if (split && !to_split.empty() && mesh.order() == 1 && mesh.dim == 2) {
      mesh = split_cells(mesh, topo, to_split, keep);
      split_count += to_split.size();
      topo = build_topology(mesh);
    }
    mesh = trim_cells(mesh, topo, keep, cut);
    if (mesh.n_cells() == 0) throw InputError(where + ": trim: every cell lies outside the level set");
    if (const std::optional<Pillowed> p = pillow_side(cut, "kept side of the trim")) {
      std::vector<std::vector<std::uint8_t>> moved(p->source.size());
      for (std::size_t k = 0; k < moved.size(); ++k) {
        moved[k].assign(cut[static_cast<std::size_t>(p->source[k])].size(), 0);
        if (p->surface_facet[k] >= 0) moved[k][static_cast<std::size_t>(p->surface_facet[k])] = 1;
      }
      cut = std::move(moved);
    }
  }

  // Interface: material indicators (eq. 10), corrected (eq. 12), cells split where two of
  // their facets are still on the interface (linear triangles and quadrilaterals).
  std::vector<std::uint8_t> eta;
  std::optional<LevelSetFunction> interface;
  if (c.interface) {
    interface.emplace(checked_level_set(*c.interface, mesh, lso, where + ": interface"));
    Topology topo = build_topology(mesh);
    std::vector<std::int32_t> to_split;
    if (!settings.materials.empty()) {
      const std::optional<PhysicalGroup> group = mesh.find_group(settings.materials);
      if (!group || group->dim != mesh.dim)
        throw InputError(where + ": options.materials: no volume group \"" + settings.materials + "\" in " +
                         (c.mesh.empty() ? std::string("the mesh") : c.mesh.string()));
      for (const CellBlock& block : mesh.cells)
        for (std::size_t k = 0; k < block.n_cells(); ++k)
          eta.push_back(!block.physical.empty() && block.physical[k] == group->tag ? 1 : 0);
      choices["materials"] = {{"value", settings.materials}, {"why", "given"}};
    } else {
      eta = correct_indicators(topo, material_indicators(mesh, *interface), to_split, reduce_crowding, stars);
      choices["materials"] = {{"value", "eq. 10-12"},
                              {"why", reduce_crowding ? "the level set's sign over each cell, corrected so that few cells keep two or more "
                                                        "interface facets (cells and vertex stars flipped)"
                                                      : "the level set's sign over each cell, corrected by eq. 12 only"}};
    }
    if (split && !to_split.empty() && mesh.order() == 1 && mesh.dim == 2) {
      if (trim) throw InputError(where + ": trim with an interface: give the interface's materials, or fit one at a time");
      mesh = split_cells(mesh, topo, to_split, eta);
      split_count += to_split.size();
    }
    for (bool again = may_pillow; again;) {
      again = false;
      for (const std::uint8_t side : {std::uint8_t{1}, std::uint8_t{0}})
        if (detail::crowded(detail::facets_of_side(topo, eta, side))) {
          const std::size_t n = detail::fill_saddles(mesh, topo, eta, side);
          filled += n;
          again = again || n > 0;
        }
    }
    for (const std::uint8_t side : {std::uint8_t{1}, std::uint8_t{0}}) {
      topo = build_topology(mesh);
      const std::vector<std::vector<std::uint8_t>> marked = detail::facets_of_side(topo, eta, side);
      if (const std::optional<Pillowed> p = pillow_side(marked, side ? "inside of the interface" : "outside of the interface")) {
        std::vector<std::uint8_t> moved(p->source.size());
        for (std::size_t k = 0; k < moved.size(); ++k) moved[k] = eta[static_cast<std::size_t>(p->source[k])];
        eta = std::move(moved);
      }
    }
  }
  if (settings.pillow != "false" || s.pillowed_cells > 0) {
    std::string why = "no cell with two or more fitted facets";
    if (s.pillowed_cells > 0) {
      why = "cells with two or more fitted facets on the ";
      for (std::size_t k = 0; k < pillowed_sides.size(); ++k) why += (k ? " and the " : "") + pillowed_sides[k];
    } else if (!may_pillow) {
      why = mesh.order() != 1            ? "the input mesh is not linear"
            : settings.fit.flat_edges      ? "flat_edges lets cells keep two fitted facets"
            : !tensor || mesh.dim == 2     ? "no hexahedra"
                                           : "no cell with two or more fitted facets";
    }
    choices["pillow"] = {{"value", s.pillowed_cells > 0}, {"cells_added", s.pillowed_cells}, {"saddle_cells_filled", filled}, {"why", why}};
  }
  if (!settings.target_given) {
    // A trim's layer moves by up to half a cell, which its thin input shape resists.
    const bool layers = s.pillowed_cells > 0, interface_layers = layers && c.interface;
    const double distortion = layers ? 0.0 : mean_shape_distortion(mesh);
    s.fit.target = interface_layers || distortion > kInputTargetDistortion ? TargetKind::Input : TargetKind::Ideal;
    choices["target"] = {{"value", target_name(s.fit.target)},
                         {"why", interface_layers ? std::string("the pillowed layers are thin by design")
                                 : layers         ? std::string("a pillowed trim: its layer moves by up to half a cell")
                                                  : format_distortion(distortion)}};
  }
  if (c.order && below_order(mesh, *c.order)) mesh = elevate_order(mesh, *c.order);
  Topology topology = build_topology(mesh);
  // "level_set": "discrete": the nodal interpolant on the mesh as it is now.
  const auto compile = [&](const LevelSetFunction& exact) {
    if (!settings.discrete) return exact;
    Eigen::VectorXd values(static_cast<Eigen::Index>(mesh.n_nodes()));
    for (Eigen::Index i = 0; i < values.size(); ++i) values[i] = exact.value(mesh.x.col(i));
    return LevelSetFunction(mesh, values);
  };
  if (c.interface)
    for (int n : interface_facet_counts(topology, eta)) two_facet_cells += n >= 2 ? 1 : 0;
  for (const std::vector<std::uint8_t>& flags : cut) two_facet_cells += std::count(flags.begin(), flags.end(), 1) >= 2 ? 1 : 0;

  // Fitted nodes and unknowns: every boundary node is fixed unless a `project` entry fits
  // it or a `slide` entry lets it move on its (axis-aligned) plane.
  const int d = mesh.dim;
  std::vector<FitTerm> terms;
  std::vector<std::string> term_keys;  // the case key of each term, for messages
  if (c.interface) {
    terms.push_back({compile(*interface), facets_nodes(interface_facets(mesh, topology, eta))});
    term_keys.push_back("interface");
  }
  std::vector<std::uint8_t> fixed(static_cast<std::size_t>(d) * mesh.n_nodes(), 0);
  for (std::int32_t node : boundary_nodes(mesh, topology)) std::fill_n(fixed.begin() + d * node, d, 1);
  if (trim) {
    FitTerm t{compile(*trim), facets_nodes(cut_facets(mesh, cut))};
    for (std::int32_t node : t.nodes) std::fill_n(fixed.begin() + d * node, d, 0);
    terms.push_back(std::move(t));
    term_keys.push_back("trim");
  }
  for (const BoundaryCondition& b : c.boundary) {
    const std::vector<std::int32_t> nodes = mesh.group_nodes(*mesh.find_group(b.group));
    const std::string at = where + ": " + b.key_path;
    if (const auto* project = std::get_if<ProjectMotion>(&b.motion)) {
      FitTerm t{compile(checked_level_set(project->target, mesh, lso, at + ".project")), nodes};
      for (std::int32_t node : nodes) std::fill_n(fixed.begin() + d * node, d, 0);
      terms.push_back(std::move(t));
      term_keys.push_back(b.key_path + ".project");
    } else if (std::holds_alternative<SlideMotion>(b.motion)) {
      int axis = -1;
      for (int k = 0; k < d && axis < 0; ++k) {
        const Eigen::ArrayXd values = mesh.x.row(k)(nodes).array();
        if (values.maxCoeff() - values.minCoeff() <= 1e-12 * lso.length_scale) axis = k;
      }
      if (axis < 0) throw InputError(at + ".slide: fit slides only on planes x, y or z = const");
      for (std::int32_t node : nodes)
        for (int k = 0; k < d; ++k) fixed[static_cast<std::size_t>(d * node + k)] = k == axis;
    } else if (!std::holds_alternative<FixedMotion>(b.motion)) {
      throw InputError(at + ": fit takes \"fixed\", \"slide\" and \"project\" entries (move the mesh with morph)");
    }
  }
  for (std::size_t k = 0; k < terms.size(); ++k) {  // a node stays where a fixed flag holds it: not fitted
    std::vector<std::int32_t>& nodes = terms[k].nodes;
    std::erase_if(nodes, [&](std::int32_t node) { return fixed[static_cast<std::size_t>(d * node)] && fixed[static_cast<std::size_t>(d * node + d - 1)]; });
    // The level set crosses the mesh (check_crossing), but no facet lies on it at this
    // resolution, or only fixed nodes do: a fit of nothing is not a fit.
    if (nodes.empty())
      throw InputError(where + ": " + term_keys[k] + ": no node to fit: " +
                       (term_keys[k] == "interface" && std::all_of(eta.begin(), eta.end(), [&](std::uint8_t e) { return e == eta.front(); })
                            ? "the material indicators (eq. 10, corrected by eq. 12) put every cell on one side of the level set; "
                              "refine the mesh near it"
                            : "the nodes on it are all fixed (boundary nodes are, unless a project or slide entry frees them)"));
  }

  s.mesh = std::move(mesh);
  s.terms = std::move(terms);
  s.surface_terms = s.terms.size();
  if (settings.features) {  // docs/fit.md, Sharp features
    if (c.interface) detail::follow_features(s, 0, *c.interface, interface_facets(s.mesh, topology, eta), lso);
    if (trim) detail::follow_features(s, c.interface ? 1 : 0, *c.trim, cut_facets(s.mesh, cut), lso);
  }
  if (settings.fit.solver == LinearSolverKind::Auto) {
    const auto n_free = static_cast<std::size_t>(std::ranges::count(fixed, 0));
    const LinearSolverKind kind = resolve_linear_solver(LinearSolverKind::Auto, d, n_free, s.mesh.max_cell_nodes());
    choices["solver"] = {{"value", kind == LinearSolverKind::Cholesky ? "cholesky" : "iterative"},
                         {"why", std::to_string(n_free) + " unknowns (CG-AMG past 300k on P3 tetrahedra and P2/P3 hexahedra)"}};
  }
  s.topology = std::move(topology);
  s.fixed = std::move(fixed);
  s.split_cells = split_count;
  s.two_facet_cells = two_facet_cells;
  return s;
}

FitRunner::FitRunner(const CaseFile& c, Mesh mesh, int threads) {
  reject_unused_keys(c, "fit", {"steps", "output_each_step", "dt"});
  check_case_against_mesh(c, mesh);
  settings_ = read_fit_settings(c, threads);
  orient_cells(c, mesh);
  if (const std::size_t bad = count_invalid_cells(mesh); bad > 0)
    throw InputError(detail::inverted_input(c, bad) + ": fit needs a valid input mesh");
  setup_ = prepare_fit(c, std::move(mesh), settings_, c.file.string());
}

RunOutput FitRunner::run() const {
  const FitSetup& setup = setup_;
  const FitSettings& settings = settings_;
  Eigen::MatrixXd x = setup.mesh.x;
  const FitResult r = fit_to_level_sets(setup.mesh, setup.topology, setup.terms, setup.fixed, setup.fit, x);
  RunOutput o;
  Report& report = o.report;
  report.method = "fit";
  report.converged = r.converged;
  report.message = r.message;
  report.iterations = IterationCounts{r.weight_updates, 1, r.newton, r.linear};
  for (const FitIteration& h : r.history)
    report.history.push_back({{"newton", h.newton}, {"weight", h.weight}, {"alpha", h.alpha}, {"fit_error", h.fit_error},
                              {"min_det", h.min_det}});
  o.moved = setup.mesh;
  o.moved.x = x;
  BoundaryTargets none;
  none.role.assign(setup.mesh.n_nodes(), NodeRole::Free);
  o.quality = detail::fill_result(report, o.moved, &setup.mesh, none);
  if (settings.fit.flat_edges) {  // a cell flat only on its flat edges is not inverted (docs/fit.md)
    report.inverted_elements = r.inverted;
    report.valid = r.inverted == 0;
    report.converged = r.converged && report.valid;
    report.message = report.valid ? r.message : std::to_string(r.inverted) + " inverted elements; " + r.message;
  }
  report.boundary_error_max.reset();
  report.boundary_error_l2.reset();
  report.fit_error_max = r.fit_error;
  o.extra = nlohmann::ordered_json::object();
  o.extra["fit_error_initial"] = r.fit_error0;
  o.extra["min_det_initial"] = r.min_det0;
  o.extra["min_det_final"] = r.min_det;
  std::vector<std::uint8_t> fitted(setup.mesh.n_nodes(), 0);  // a feature node is in two or three terms
  for (const FitTerm& t : setup.terms)
    for (std::int32_t node : t.nodes) fitted[static_cast<std::size_t>(node)] = 1;
  o.extra["fitted_nodes"] = std::ranges::count(fitted, 1);
  o.extra["split_cells"] = setup.split_cells;
  o.extra["cells_with_two_interface_facets"] = setup.two_facet_cells;
  if (settings.fit.flat_edges) o.extra["flat_edge_cells"] = r.flat;
  o.extra["pillowed_cells"] = setup.pillowed_cells;
  if (!setup.features.empty()) o.extra["features"] = detail::feature_report(setup, x);
  o.extra["choices"] = setup.choices;
  return o;
}

}  // namespace meshmorph
