#pragma once
/// @file
/// Internal to the element layer (not installed): the capstan law of a slipping rope node, the
/// tension ratio across the node as a function of its wrap angle, written into the node's
/// constraint row with weights of at most 1.

#include <algorithm>
#include <cmath>

namespace SimbodyReeving::detail {

/// The weights (w_before, w_after) [-] of a node's tension row w_before eps_{k-1} - w_after eps_k = 0
/// at one wrap angle alpha, and their first [1/rad] and second [1/rad^2] derivatives in alpha
/// (zero for a ratio that does not depend on the angle). A frictionless sheave's row has (1, 1).
struct SlipWeights {
    double before = 1, after = 1, dBefore = 0, dAfter = 0, ddBefore = 0, ddAfter = 0;
};

/// The capstan law of the slip over a sheave (Euler-Eytelwein with kappa_0 = 1 and c = +-mu):
///     kappa(alpha) = P_{k-1} / P_k = kappa_0 e^(c alpha)   [-],
/// kappa_0 [-] > 0, c [1/rad], alpha [rad] the wrap angle of the current geometry. Its row
/// eps_{k-1} = kappa eps_k is written with the weights (1, kappa) / max(1, kappa): the same
/// equation with coefficients of at most 1, so its round-off stays at the strains' own (about
/// 1e-16) for any kappa. Unscaled, a large kappa (e^(mu alpha) = 4e13 at mu = 10) multiplies the
/// slack side's round-off past the Newton's tolerance.
class CapstanLaw {
public:
    CapstanLaw() = default;  ///< kappa = 1: a frictionless sheave's ratio
    /// @param kappa0        kappa_0 [-], finite and > 0 (the caller validates).
    /// @param angleExponent c [1/rad], finite.
    CapstanLaw(double kappa0, double angleExponent)
        : kappa0_(kappa0),
          exponent_(angleExponent),
          before_(1.0 / std::max(1.0, kappa0)),
          after_(kappa0 / std::max(1.0, kappa0)) {}

    double ratio() const { return kappa0_; }             ///< kappa_0 [-]
    double angleExponent() const { return exponent_; }   ///< c [1/rad]
    bool dependsOnAngle() const { return exponent_ != 0; }

    /// The row's weights at wrap angle alpha [rad] (read only when dependsOnAngle()): for
    /// kappa >= 1 (1 / kappa, 1), below (1, kappa), with their derivatives in alpha.
    SlipWeights weights(double alpha) const {
        SlipWeights w;
        w.before = before_;
        w.after = after_;
        const double c = exponent_;
        if (c == 0) return w;
        const double kappa = kappa0_ * std::exp(c * alpha);
        if (kappa >= 1) {
            w.before = 1.0 / kappa;
            w.after = 1.0;
            w.dBefore = -c * w.before;
            w.ddBefore = c * c * w.before;
        } else {
            w.before = 1.0;
            w.after = kappa;
            w.dAfter = c * kappa;
            w.ddAfter = c * c * kappa;
        }
        return w;
    }

private:
    double kappa0_ = 1, exponent_ = 0;
    double before_ = 1, after_ = 1;  // the weights at c = 0
};

}  // namespace SimbodyReeving::detail
