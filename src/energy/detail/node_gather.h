// SPDX-License-Identifier: MIT
#pragma once
#include <cstdint>
#include <vector>

#include "energy/detail/hessian_kernels.h"
#include "meshmorph/energy/assembler.h"
#include "meshmorph/error.h"
#include "meshmorph/threads.h"

namespace meshmorph {

/// EnergyAssembler::gather (declared in assembler.h), for the products of the Hessian action.
template <int d>
template <class Store>
void EnergyAssembler<d>::gather(const std::vector<double>& local, int width, int threads, Store store) const {
  constexpr int max_width = detail::k_packed(d);
  MESHMORPH_CHECK(width <= max_width, "EnergyAssembler::gather: too wide");
  const auto n_nodes = static_cast<std::ptrdiff_t>(mesh_->n_nodes());
#pragma omp parallel for num_threads(resolve_threads(threads)) schedule(static)
  for (std::ptrdiff_t i = 0; i < n_nodes; ++i) {
    // Slot by slot, all entries at once: each entry still sums its slots in slot order.
    double sum[max_width] = {};
    for (std::int64_t s = node_slot_offset_[static_cast<std::size_t>(i)]; s < node_slot_offset_[static_cast<std::size_t>(i) + 1]; ++s) {
      const double* l = local.data() + width * node_slots_[static_cast<std::size_t>(s)];
      for (int k = 0; k < width; ++k) sum[k] += l[k];
    }
    for (int k = 0; k < width; ++k) store(i, k, sum[k]);
  }
}

}  // namespace meshmorph
