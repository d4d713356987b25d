// SPDX-License-Identifier: MIT
#pragma once
#include "meshmorph/quality/metric.h"

namespace meshmorph {

/// Parameters of the edge-based quality functional (paper 001).
struct EdgeQualityOptions {
  double delta = 0.0;  ///< δ ≥ 0 of the regularized volume h(V) (eq. 10); 0 = unregularized
  double n = -1.0;     ///< exponent n < 0 of F = q*ⁿ (eq. 2, 11)
};

/// Edge-based simplex quality functional F(T) = q*(T)ⁿ with q* = C·h(V)/Σⱼ lⱼᵈ,
/// h(V) = ½(V + √(V² + 4δ²)) (paper 001, eq. 3–4, 10–11); C = 4√3 (triangle), 36√2
/// (tetrahedron), so that q* = 1 on the regular simplex when δ = 0.
///
/// The element is T applied to the regular simplex of unit edge: lⱼ = |T eⱼ| over its
/// d(d+1)/2 edges eⱼ and V = det T · V_reg (V_reg = √3/4, √2/12). Hence the reference is
/// the regular simplex: with T = A W⁻¹, a target W maps the unit reference simplex to the
/// element the metric treats as ideal. W = the regular-simplex Jacobian (unit edge) makes V
/// and lⱼ the current element's own volume and edges, as in the paper; W = the input
/// element's Jacobian gives eq. 8 (g(T T'⁻¹), "reference element" compensation), and then V
/// and δ are relative to the regular simplex (V = V_reg when the volume is kept).
///
/// With δ > 0, F is finite and smooth for every T, inverted (τ ≤ 0) included; with δ = 0
/// it is +∞ for τ ≤ 0. Not invariant under T → sT when δ > 0. docs/metrics.md#edge_quality.
template <int d>
class EdgeQuality final : public Metric<d> {
 public:
  /// Throws std::invalid_argument for δ < 0 or n ≥ 0.
  explicit EdgeQuality(EdgeQualityOptions options = {});
  MetricEval<d> eval(const MatT<d>& T, Want want) const override;
  std::string_view name() const override { return "edge_quality"; }

  /// V of eq. 10 for T: τ·V_reg, the volume of T applied to the unit-edge regular simplex.
  static double volume(const MatT<d>& T);

  /// Derivatives of F in δ, for the δ update of paper 001 eq. 13: ∂F/∂δ, ∂²F/∂δ² and the
  /// mixed one along dT, (∂²F/∂δ∂T) : dT. Not finite where F is not.
  struct DeltaDerivatives {
    double d_delta = 0.0;
    double d2_delta = 0.0;
    double d2_delta_dT = 0.0;
  };
  DeltaDerivatives delta_derivatives(const MatT<d>& T, const MatT<d>& dT) const;
  const EdgeQualityOptions& options() const { return options_; }

 private:
  EdgeQualityOptions options_;
};

extern template class EdgeQuality<2>;
extern template class EdgeQuality<3>;

}  // namespace meshmorph
