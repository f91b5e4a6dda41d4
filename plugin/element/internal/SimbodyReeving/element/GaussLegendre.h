#pragma once
/// @file
/// Gauss-Legendre and midpoint quadrature on the unit interval [0, 1].

#include <vector>

namespace SimbodyReeving {

/// Nodes and weights of the N-point Gauss-Legendre rule mapped to [0, 1]:
///   integral_0^1 f(xi) dxi  ~=  sum_k weights[k] f(nodes[k]).
/// Exact for polynomials of degree <= 2N - 1; for the trigonometric integrands of the span
/// element the error decays faster than geometrically once N exceeds the number of
/// half-waves of the integrand (see SpanModel for the rule used).
struct GaussLegendreRule {
    std::vector<double> nodes;    ///< xi_k in (0, 1), ascending
    std::vector<double> weights;  ///< w_k > 0, summing to 1
};

/// Computes the N-point rule by Newton iteration on the Legendre polynomial P_N
/// (nodes accurate to a few ulp for N <= 200).
/// @throws std::invalid_argument if numPoints < 1 or numPoints > 200.
GaussLegendreRule makeGaussLegendreRule(int numPoints);

/// Nodes xi_j = (j + 1/2) / N and weights 1/N of the N-point midpoint rule on [0, 1] (returned in
/// the same struct). It integrates every cosine series sum_k c_k cos(k pi xi) with k < 2N exactly:
/// sum_j cos(k pi (j + 1/2) / N) = 0 for every integer k that is not a multiple of 2N, and so is
/// int_0^1 cos(k pi xi) dxi for k >= 1. SpanModel uses it for the strain integrals, which are such
/// series (see SpanModel::automaticStrainPoints). It is not exact for sines or polynomials of
/// degree >= 2.
/// @throws std::invalid_argument if numPoints < 1 or numPoints > 200.
GaussLegendreRule makeMidpointRule(int numPoints);

}  // namespace SimbodyReeving
