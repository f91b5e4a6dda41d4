#pragma once
/// @file
/// Internal to the element layer (not installed): the law of a rope node slipping over a sheave
/// whose groove grips it (MaterialNode::Slipping: a traction sheave in slip).

#include "CapstanLaw.h"
#include "NodeColumns.h"
#include "SimbodyReeving/element/RopeModel.h"
#include "TensionRow.h"

#include <Eigen/Core>

namespace SimbodyReeving::detail {

/// s_k is a dependent coordinate, solved from the capstan law of the slip, P_{k-1}(s_k) =
/// kappa(alpha) P_k(s_k) (CapstanLaw; a tension row with the law's weights, alpha the wrap angle
/// of the current geometry when the law follows it). The friction force F_f = P_k - P_{k-1} [N]
/// acts on the material there (the massless material point at the node is in balance) and its
/// reaction -F_f on the node's external coordinate, the sheave's surface s_sheave = s_ref + R theta
/// [m], which the node has like a Driven node: so a sheave switches between Driven (stick) and
/// Slipping (slip) without changing the rope's external coordinates. With condensed spans its
/// multiplier nu_k is held at zero (its row reads nu_k = 0): the capstan row alone fixes s_k, no
/// multiplier of the ratio enters the condensed amplitudes' stationarity, and they solve the same
/// equations in stick and in slip (the dependent coordinates are continuous at a transition where
/// the ratio holds). Interior nodes only, not on a groove whose axis turns.
struct SlippingLaw {
    static constexpr MaterialNode kKind = MaterialNode::Slipping;
    static constexpr const char* kName = "Slipping";
    static constexpr bool kAtEnd = false, kInterior = true;
    static constexpr const char* kWhereNot = "a sheave needs a span on both sides";
    static constexpr bool kExternal = true;
    static constexpr bool kDependent = true;
    static constexpr bool kDrum = false;
    static constexpr bool kTurningGroove = false;

    CapstanLaw capstan;    ///< kappa(alpha)
    int sheaveColumn = -1;  ///< the sheave's surface coordinate's column in x

    int place(const NodeColumns& c) {
        sheaveColumn = c.external;
        return c.dependent;
    }
    /// Its tension row at this evaluation: the capstan law's weights, at the wrap angle angleOf()
    /// (a detail::SlipAngle<Dim>, taken only when the law follows the angle).
    template <int Dim, class AngleOf>
    void tensionRow(const AngleOf& angleOf, TensionRow<Dim>& row) const {
        row.angleLaw = capstan.dependsOnAngle();
        row.angle = row.angleLaw ? angleOf() : SlipAngle<Dim>{};
        row.weights = capstan.weights(row.angle.alpha);
    }
    /// The row of its multiplier: nu_k = 0 (holdAtZero() writes it).
    template <class Stationarity, class Hold>
    void multiplierRow(const Stationarity& /*stationarity*/, const Hold& holdAtZero) const {
        holdAtZero();
    }
    /// nu_k = 0: no products in the stationarity rows (product is not called).
    template <class Product>
    void multiplierProducts(const Product& /*product*/) const {}
    /// The friction F_f = -(P_{k-1} - P_k) [N] (forceDifference(): P_{k-1} - P_k) into the rope's
    /// generalized forces Qz: on the material s_k (materialColumn) and its reaction on the sheave.
    template <class Difference>
    void addFriction(const Difference& forceDifference, Eigen::VectorXd& Qz, int materialColumn) const {
        const double friction = -forceDifference();
        Qz[materialColumn] += friction;
        Qz[sheaveColumn] -= friction;
    }
};

}  // namespace SimbodyReeving::detail
