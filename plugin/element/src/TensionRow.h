#pragma once
/// @file
/// Internal to the element layer (not installed): the tension row of a rope node whose material
/// coordinate is solved (a sheave), at one evaluation: its weights and, for a ratio that follows
/// the wrap angle, the angle with its gradient, and the terms the angle adds to the row's
/// Jacobian and acceleration bias. Written once for both of RopeModel's constraint forms (the
/// spans' end strains, and the condensed spans' kernels).

#include "CapstanLaw.h"

#include <array>

namespace SimbodyReeving::detail {

/// A node's wrap angle alpha [rad] as a function of the rope's external coordinates x (RopeModel's
/// slipAngle): its value, its gradient (count entries [rad/m or 1/m] at columns cols of x), and with
/// rates xdot its rate [rad/s] and the quadratic-velocity part of its second derivative [rad/s^2]
/// (alphaddot = grad . xddot + bias).
template <int Dim>
struct SlipAngle {
    double alpha = 0, rate = 0, bias = 0;
    int count = 0;
    std::array<int, 3 * Dim> cols{};
    std::array<double, 3 * Dim> grad{};
};

/// Node k's row C_k = w_before(alpha) eps_{k-1} - w_after(alpha) eps_k at one evaluation (eps the
/// two spans' strains at the node, of the spans' end strains or of the condensed kernels).
template <int Dim>
struct TensionRow {
    SlipWeights weights;
    bool angleLaw = false;  ///< the weights follow the wrap angle (angle is then set)
    SlipAngle<Dim> angle;

    /// dC/dalpha [1/rad] at the strains a = eps_{k-1}, b = eps_k [-].
    double angleSlope(double a, double b) const { return weights.dBefore * a - weights.dAfter * b; }
    /// The acceleration bias's terms of the angle [1/s^2]: those in alphadot (with the strains'
    /// rates aRate, bRate [1/s]) and alpha's own bias.
    double angleBias(double a, double b, double aRate, double bRate) const {
        const double ad = angle.rate;
        return 2.0 * ad * (weights.dBefore * aRate - weights.dAfter * bRate) +
               ad * ad * (weights.ddBefore * a - weights.ddAfter * b) + angleSlope(a, b) * angle.bias;
    }
};

}  // namespace SimbodyReeving::detail
