// SPDX-License-Identifier: MIT
// Reads a mesh with an installed meshmorph and prints its size and inverted cells.
#include <iostream>

#include "meshmorph/fem/validity.h"
#include "meshmorph/io/mesh_io.h"

int main(int argc, char** argv) {
  if (argc != 2) return 2;
  const meshmorph::Mesh mesh = meshmorph::read_mesh(argv[1]);
  std::cout << mesh.n_nodes() << " nodes, " << mesh.n_cells() << " cells, " << meshmorph::count_invalid_cells(mesh)
            << " inverted\n";
}
