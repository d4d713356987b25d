// SPDX-License-Identifier: MIT
// Writes sample meshes in every format and encoding to a folder, with a manifest that
// tests/io/meshio_reads_output.py checks with Python's meshio (and vtk_reads_output.py with VTK).
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

#include "meshmorph/fem/structured.h"
#include "meshmorph/io/mesh_io.h"

int main(int argc, char** argv) {
  using namespace meshmorph;
  if (argc != 2) {
    std::fprintf(stderr, "usage: write_samples OUTDIR\n");
    return 2;
  }
  const std::filesystem::path dir = argv[1];
  std::filesystem::create_directories(dir);
  std::ofstream manifest(dir / "manifest.txt");
  const std::pair<ElementType, int> meshes[] = {
      {ElementType::Triangle, 1}, {ElementType::Triangle, 2}, {ElementType::Triangle, 3}, {ElementType::Triangle, 4},
      {ElementType::Quadrilateral, 1}, {ElementType::Quadrilateral, 2}, {ElementType::Quadrilateral, 3},
      {ElementType::Tetrahedron, 1}, {ElementType::Tetrahedron, 2}, {ElementType::Tetrahedron, 3}, {ElementType::Tetrahedron, 4},
      {ElementType::Hexahedron, 1}, {ElementType::Hexahedron, 2}, {ElementType::Hexahedron, 3},
      {ElementType::Prism, 1}, {ElementType::Prism, 2}, {ElementType::Prism, 3}, {ElementType::Prism, 4},
      {ElementType::Pyramid, 1}};
  struct Variant {
    const char* suffix;
    MeshFormat format;
    bool binary;
  };
  const Variant variants[] = {{"_41a.msh", MeshFormat::Msh41, false}, {"_41b.msh", MeshFormat::Msh41, true},
                              {"_22a.msh", MeshFormat::Msh22, false}, {"_22b.msh", MeshFormat::Msh22, true},
                              {"_a.vtu", MeshFormat::Vtu, false},     {"_b.vtu", MeshFormat::Vtu, true}};
  for (const auto& [type, order] : meshes) {
    Mesh m = structured_mesh(type, order, 2);
    // A node field, written as VTU PointData and MSH $NodeData.
    m.node_fields["phi"] = (m.x.transpose() * Eigen::VectorXd::LinSpaced(m.dim, 1, m.dim)).array() + 0.5;
    std::size_t n_facets = 0;
    for (const CellBlock& b : m.facets) n_facets += b.n_cells();
    const Eigen::VectorXd sum = m.x.rowwise().sum();
    for (const Variant& v : variants) {
      const std::string name = std::string(name_of(type)) + std::to_string(order) + v.suffix;
      WriteOptions opt;
      opt.format = v.format;
      opt.binary = v.binary;
      write_mesh(dir / name, m, opt);
      // file, family, order, dim, points, cells, facets, sum x, sum y, sum z, sum phi
      manifest << name << ' ' << name_of(type) << ' ' << order << ' ' << m.dim << ' ' << m.n_nodes() << ' '
               << m.n_cells() << ' ' << n_facets << ' ' << sum(0) << ' ' << sum(1) << ' ' << (m.dim == 3 ? sum(2) : 0.0)
               << ' ' << m.node_fields["phi"].sum() << '\n';
    }
  }
  return 0;
}
