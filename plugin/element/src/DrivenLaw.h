#pragma once
/// @file
/// Internal to the element layer (not installed): the law of a rope node gripped by something that
/// moves it (MaterialNode::Driven: a winch drum, a drive or idler sheave in stick).

#include "NodeColumns.h"
#include "SimbodyReeving/element/RopeModel.h"

#include <Eigen/Core>

namespace SimbodyReeving::detail {

/// s_k is an external coordinate, given with its rate at every evaluation like the node positions
/// (s_k = s_ref + R theta [m]). The rope's generalized force on it (the axial force difference
/// across the node [N], or the force at an end) is part of the node reduction. Any node; at an end
/// it may be a winch drum (wrapped, with rope stored beyond it).
struct DrivenLaw {
    static constexpr MaterialNode kKind = MaterialNode::Driven;
    static constexpr const char* kName = "Driven";
    static constexpr bool kAtEnd = true, kInterior = true;
    static constexpr const char* kWhereNot = "";
    static constexpr bool kExternal = true;
    static constexpr bool kDependent = false;
    static constexpr bool kDrum = true;
    static constexpr bool kTurningGroove = true;

    int column = -1;  ///< s_k's column in x

    int place(const NodeColumns& c) {
        column = c.external;
        return c.external;
    }
    double coordinate(const Eigen::VectorXd& x) const { return x[column]; }    ///< s_k [m]
    double rate(const Eigen::VectorXd& xdot) const { return xdot[column]; }    ///< sdot_k [m/s]
    /// Whether a solve's s_k still belongs to x (the drum or sheave may have turned since).
    bool agrees(double s, const Eigen::VectorXd& x) const { return s == x[column]; }
};

}  // namespace SimbodyReeving::detail
