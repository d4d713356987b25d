// SPDX-License-Identifier: MIT
#include <algorithm>
#include <array>
#include <cstdint>
#include <string>
#include <system_error>
#include <vector>

#include "io/detail/foam_file.h"
#include "io/detail/mesh_builder.h"
#include "meshmorph/error.h"
#include "meshmorph/io/foam.h"
#include "meshmorph/io/mesh_io.h"

namespace meshmorph {
namespace {

namespace fs = std::filesystem;

// The faces of Gmsh's linear cells, oriented out of the cell (right-hand rule).
struct Shape {
  ElementType type;
  int n_faces;
  std::array<std::array<int, 4>, 6> faces;  // -1 ends a triangle
};
constexpr Shape k_tet{ElementType::Tetrahedron, 4, {{{0, 2, 1, -1}, {0, 1, 3, -1}, {0, 3, 2, -1}, {1, 2, 3, -1}}}};
constexpr Shape k_pyramid{
    ElementType::Pyramid, 5, {{{0, 3, 2, 1}, {0, 1, 4, -1}, {1, 2, 4, -1}, {2, 3, 4, -1}, {3, 0, 4, -1}}}};
constexpr Shape k_prism{
    ElementType::Prism, 5, {{{0, 2, 1, -1}, {3, 4, 5, -1}, {0, 1, 4, 3}, {1, 2, 5, 4}, {2, 0, 3, 5}}}};
constexpr Shape k_hex{
    ElementType::Hexahedron, 6, {{{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4}, {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}}}};

// A cell's faces (the first 6 of them) with their points in the order that faces out of the
// cell, and how many it has of each size.
struct CellFaces {
  int n = 0, tri = 0, quad = 0, polygons = 0;
  std::array<std::int64_t, 6> id{};
  std::array<int, 6> size{};
  std::array<std::array<std::int32_t, 4>, 6> v{};
};

// Whether `face` (n points) is `want` up to rotation.
bool same_cycle(const std::int32_t* face, const std::int32_t* want, int n) {
  for (int s = 0; s < n; ++s) {
    bool all = true;
    for (int k = 0; k < n && all; ++k) all = face[(s + k) % n] == want[k];
    if (all) return true;
  }
  return false;
}

class CellBuilder {
 public:
  explicit CellBuilder(fs::path dir) : dir_(std::move(dir)) {}

  // The Gmsh-ordered nodes of cell `c` (its faces in `f`); throws InputError naming it.
  const Shape& build(std::int64_t c, const CellFaces& f, std::array<std::int32_t, 8>& nodes) const {
    const Shape* shape = f.n == 4 && f.tri == 4                  ? &k_tet
                         : f.n == 5 && f.tri == 4 && f.quad == 1 ? &k_pyramid
                         : f.n == 5 && f.tri == 2 && f.quad == 3 ? &k_prism
                         : f.n == 6 && f.quad == 6               ? &k_hex
                                                                 : nullptr;
    if (shape == nullptr) fail_shape(c, f);
    // The base: a quadrilateral for a pyramid, else a face of the base's kind, turned to face into the cell.
    int b = 0;
    while (b < f.n && f.size[b] != (shape == &k_pyramid || shape == &k_hex ? 4 : 3)) ++b;
    const int nb = f.size[b];
    for (int k = 0; k < nb; ++k) nodes[static_cast<std::size_t>(k)] = f.v[b][static_cast<std::size_t>((nb - k) % nb)];
    const auto in_base = [&](std::int32_t p) {
      return std::find(f.v[b].begin(), f.v[b].begin() + nb, p) != f.v[b].begin() + nb;
    };
    if (shape == &k_tet || shape == &k_pyramid) {
      std::int32_t apex = -1;
      for (int k = 0; k < f.n; ++k)
        for (int j = 0; j < f.size[k]; ++j)
          if (const std::int32_t p = f.v[k][j]; !in_base(p)) {
            if (apex >= 0 && apex != p) fail_closed(c, *shape);
            apex = p;
          }
      if (apex < 0) fail_closed(c, *shape);
      nodes[static_cast<std::size_t>(nb)] = apex;
    } else {
      // Each base corner's edge that leaves the base ends at the corner above it.
      for (int i = 0; i < nb; ++i) {
        const std::int32_t p = nodes[static_cast<std::size_t>(i)];
        std::int32_t top = -1;
        for (int k = 0; k < f.n; ++k)
          for (int j = 0; j < f.size[k]; ++j) {
            const std::int32_t u = f.v[k][j], w = f.v[k][(j + 1) % f.size[k]];
            const std::int32_t other = u == p ? w : w == p ? u : -1;
            if (other < 0 || in_base(other)) continue;
            if (top >= 0 && top != other) fail_closed(c, *shape);
            top = other;
          }
        if (top < 0) fail_closed(c, *shape);
        nodes[static_cast<std::size_t>(nb + i)] = top;
      }
    }
    const int n_nodes = n_corners_of(shape->type);
    if (detail::repeated_node(nodes.data(), n_nodes) >= 0) fail_closed(c, *shape);
    // Every face of the shape must be one of the cell's, facing out of it. Where all the faces
    // but the base are turned over, the base is the face that is.
    std::array<bool, 6> used{};
    int flipped = 0, first_flipped = -1;
    for (int r = 0; r < shape->n_faces; ++r) {
      const auto& ref = shape->faces[static_cast<std::size_t>(r)];
      const int n = ref[3] < 0 ? 3 : 4;
      std::array<std::int32_t, 4> want{}, reversed{};
      for (int k = 0; k < n; ++k) want[k] = nodes[static_cast<std::size_t>(ref[k])], reversed[n - 1 - k] = want[k];
      int match = -1;
      bool turned = false;
      for (int k = 0; k < f.n && match < 0; ++k) {
        if (used[k] || f.size[k] != n) continue;
        if (same_cycle(f.v[k].data(), want.data(), n))
          match = k;
        else if (same_cycle(f.v[k].data(), reversed.data(), n))
          match = k, turned = true;
      }
      if (match < 0) fail_closed(c, *shape);
      used[match] = true;
      if (turned && flipped++ == 0) first_flipped = match;
    }
    if (flipped > 0) {
      const std::int64_t face = f.id[flipped == f.n - 1 ? b : first_flipped];
      throw InputError(dir_.string() + ": face " + std::to_string(face) +
                       " is oriented against the other faces of cell " + std::to_string(c) +
                       " (a face points out of its owner and into its neighbour)");
    }
    return *shape;
  }

 private:
  [[noreturn]] void fail_shape(std::int64_t c, const CellFaces& f) const {
    const std::string what = std::to_string(f.n) + " faces (" + std::to_string(f.tri) + " triangles, " +
                             std::to_string(f.quad) + " quadrilaterals, " + std::to_string(f.polygons) +
                             " of more points)";
    throw InputError(dir_.string() + ": cell " + std::to_string(c) + " has " + what +
                     ": meshmorph reads tetrahedra, prisms, pyramids and hexahedra only");
  }
  [[noreturn]] void fail_closed(std::int64_t c, const Shape& s) const {
    throw InputError(dir_.string() + ": cell " + std::to_string(c) + ": its faces do not close a " +
                     std::string(name_of(s.type)));
  }

  fs::path dir_;
};

// The polyMesh's files: `points` may be a time folder's, the topology the case's.
struct Files {
  fs::path dir;     // where faces, owner, neighbour and boundary are
  fs::path points;  // the points file
};

Files locate(const fs::path& path) {
  std::error_code ec;
  const fs::path base = path.extension() == ".foam" && !fs::is_directory(path, ec) ? path.parent_path() : path;
  const fs::path folder = base.empty() ? fs::path(".") : base;
  const auto has_mesh = [&](const fs::path& d) {
    return fs::exists(d / "faces", ec) || fs::exists(d / "faces.gz", ec);
  };
  if (has_mesh(folder / "constant" / "polyMesh"))
    return {folder / "constant" / "polyMesh", folder / "constant" / "polyMesh" / "points"};
  if (has_mesh(folder)) return {folder, folder / "points"};
  if (fs::exists(folder / "polyMesh" / "points", ec)) {
    if (has_mesh(folder / "polyMesh")) return {folder / "polyMesh", folder / "polyMesh" / "points"};
    const fs::path constant = folder.parent_path() / "constant" / "polyMesh";
    if (has_mesh(constant)) return {constant, folder / "polyMesh" / "points"};
  }
  throw InputError(path.string() +
                   ": no OpenFOAM polyMesh here (a case folder holds constant/polyMesh/faces, "
                   "a time folder polyMesh/points)");
}

fs::path existing(const fs::path& file) {
  std::error_code ec;
  if (!fs::exists(file, ec) && fs::exists(file.string() + ".gz", ec))
    throw InputError(file.string() +
                     ".gz: compressed polyMesh files are not read (gunzip them, or writeCompression off)");
  return file;
}

}  // namespace

Mesh read_foam(const fs::path& path) {
  const Files at = locate(path);
  detail::MeshBuilder builder;
  detail::FoamFile points_file(existing(at.points));
  builder.xyz = points_file.points();
  points_file.expect_end();
  const std::size_t n_points = builder.xyz.size() / 3;
  if (n_points > static_cast<std::size_t>(INT32_MAX))
    points_file.fail_at(points_file.list_at(), "more than 2^31 - 1 points");
  builder.tags.resize(n_points);
  for (std::size_t j = 0; j < n_points; ++j) builder.tags[j] = static_cast<std::int64_t>(j) + 1;

  detail::FoamFile faces_file(existing(at.dir / "faces"));
  const detail::FoamFaces faces = faces_file.faces(static_cast<std::int64_t>(n_points));
  faces_file.expect_end();
  const std::int64_t n_faces = static_cast<std::int64_t>(faces.size());
  detail::FoamFile owner_file(existing(at.dir / "owner"));
  const std::vector<std::int64_t> owner = owner_file.labels("owner cell");
  owner_file.expect_end();
  if (static_cast<std::int64_t>(owner.size()) != n_faces)
    owner_file.fail_at(owner_file.list_at(), "the owner list holds " + std::to_string(owner.size()) + " cells for " +
                                                 std::to_string(n_faces) + " faces");
  detail::FoamFile neighbour_file(existing(at.dir / "neighbour"));
  const std::vector<std::int64_t> neighbour = neighbour_file.labels("neighbour cell");
  neighbour_file.expect_end();
  const auto n_internal = static_cast<std::int64_t>(neighbour.size());
  if (n_internal > n_faces)
    neighbour_file.fail_at(neighbour_file.list_at(), "the neighbour list holds " + std::to_string(n_internal) +
                                                         " cells for " + std::to_string(n_faces) + " faces");
  for (std::int64_t f = 0; f < n_internal; ++f)
    if (neighbour[static_cast<std::size_t>(f)] == owner[static_cast<std::size_t>(f)])
      neighbour_file.fail_at(neighbour_file.list_at(), "face " + std::to_string(f) + ": cell " +
                                                           std::to_string(owner[static_cast<std::size_t>(f)]) +
                                                           " is its owner and its neighbour");
  detail::FoamFile boundary_file(existing(at.dir / "boundary"));
  const std::vector<detail::FoamPatch> patches = boundary_file.patches();
  boundary_file.expect_end();
  std::int64_t next = n_internal;
  for (const detail::FoamPatch& p : patches) {
    if (p.start_face != next || p.n_faces > n_faces - next)
      boundary_file.fail_at(p.at, "patch '" + p.name + "' holds faces " + std::to_string(p.start_face) + ".." +
                                      std::to_string(p.start_face + p.n_faces - 1) + "; the next boundary faces are " +
                                      std::to_string(next) + ".." + std::to_string(n_faces - 1));
    if (const auto bad = group_name_problem(p.name)) boundary_file.fail_at(p.at, "patch name " + *bad);
    next += p.n_faces;
  }
  if (next != n_faces)
    boundary_file.fail_at(boundary_file.list_at(), "the patches leave the boundary faces " + std::to_string(next) +
                                                       ".." + std::to_string(n_faces - 1) + " without a patch");

  // Cells: their faces, oriented out of them.
  std::int64_t n_cells = 0;
  for (const std::int64_t c : owner) n_cells = std::max(n_cells, c + 1);
  for (const std::int64_t c : neighbour) n_cells = std::max(n_cells, c + 1);
  // A cell has 4 faces at least, and a face 2 cells at most.
  if (n_cells > n_faces / 2)
    owner_file.fail_at(owner_file.list_at(),
                       "cell " + std::to_string(n_cells - 1) + " (in owner or neighbour) is beyond the " +
                           std::to_string(n_faces / 2) + " cells that " + std::to_string(n_faces) + " faces can close");
  std::vector<CellFaces> cells(static_cast<std::size_t>(n_cells));
  const auto add = [&](std::int64_t c, std::int64_t f, bool out) {
    CellFaces& cf = cells[static_cast<std::size_t>(c)];
    const std::int64_t* p = faces.points.data() + faces.offsets[static_cast<std::size_t>(f)];
    const auto k =
        static_cast<int>(faces.offsets[static_cast<std::size_t>(f) + 1] - faces.offsets[static_cast<std::size_t>(f)]);
    (k == 3 ? cf.tri : k == 4 ? cf.quad : cf.polygons) += 1;
    if (cf.n < 6 && k <= 4) {
      cf.id[cf.n] = f;
      cf.size[cf.n] = k;
      for (int j = 0; j < k; ++j) cf.v[cf.n][j] = static_cast<std::int32_t>(out ? p[j] : p[(k - j) % k]);
    }
    ++cf.n;  // a cell of more than 6 faces or with a polygon is refused before its faces are looked at
  };
  for (std::int64_t f = 0; f < n_faces; ++f) {
    add(owner[static_cast<std::size_t>(f)], f, true);
    if (f < n_internal) add(neighbour[static_cast<std::size_t>(f)], f, false);
  }
  const CellBuilder cell_builder(at.dir);
  std::array<std::int32_t, 8> nodes{};
  for (std::int64_t c = 0; c < n_cells; ++c) {
    const Shape& s = cell_builder.build(c, cells[static_cast<std::size_t>(c)], nodes);
    builder.block(s.type, 1).push_back(nodes.data(), 0, 0);
  }
  // Boundary faces: a facet group per patch.
  for (std::size_t i = 0; i < patches.size(); ++i) {
    const auto tag = static_cast<std::int32_t>(i + 1);
    builder.named_groups.push_back(PhysicalGroup{2, tag, patches[i].name});
    for (std::int64_t f = patches[i].start_face; f < patches[i].start_face + patches[i].n_faces; ++f) {
      const std::size_t o = static_cast<std::size_t>(faces.offsets[static_cast<std::size_t>(f)]);
      const std::size_t k = static_cast<std::size_t>(faces.offsets[static_cast<std::size_t>(f) + 1]) - o;
      for (std::size_t j = 0; j < k; ++j) nodes[j] = static_cast<std::int32_t>(faces.points[o + j]);
      builder.block(k == 3 ? ElementType::Triangle : ElementType::Quadrilateral, 1).push_back(nodes.data(), tag, 0);
    }
  }
  return builder.finish(at.dir.string());
}

}  // namespace meshmorph
