#pragma once
/// @file
/// Internal to the element layer (not installed): the law of a rope end fastened to its node
/// (MaterialNode::Fixed).

#include "NodeColumns.h"
#include "SimbodyReeving/element/RopeModel.h"

#include <Eigen/Core>

namespace SimbodyReeving::detail {

/// A fastened rope end: its material coordinate is a constant, s_0 = 0 at the rope's start,
/// s_N = L (the unstretched length [m]) at its end. No external coordinate, no equation.
struct FixedLaw {
    static constexpr MaterialNode kKind = MaterialNode::Fixed;
    static constexpr const char* kName = "Fixed";
    static constexpr bool kAtEnd = true, kInterior = false;  ///< where it may stand
    static constexpr const char* kWhereNot = "a rope fastened mid-path is two ropes";
    static constexpr bool kExternal = false;   ///< no external coordinate
    static constexpr bool kDependent = false;  ///< s_k is known, not solved
    static constexpr bool kDrum = false;       ///< no rope stored beyond it, no wrapped end
    static constexpr bool kTurningGroove = false;  ///< (an end node has no groove)

    double value = 0;  ///< s_k [m]

    /// Puts the law at its columns; returns its material coordinate's column in z.
    int place(const NodeColumns& c) { return c.constant; }
    /// s_k [m] at the external coordinates x.
    double coordinate(const Eigen::VectorXd& /*x*/) const { return value; }
    /// sdot_k [m/s] at their rates xdot.
    double rate(const Eigen::VectorXd& /*xdot*/) const { return 0.0; }
    /// Whether a solve's s_k still belongs to x: a constant, written by every solve.
    bool agrees(double /*s*/, const Eigen::VectorXd& /*x*/) const { return true; }
};

}  // namespace SimbodyReeving::detail
