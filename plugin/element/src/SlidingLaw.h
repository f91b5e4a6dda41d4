#pragma once
/// @file
/// Internal to the element layer (not installed): the law of a rope node over a frictionless,
/// massless sheave (MaterialNode::Sliding).

#include "CapstanLaw.h"
#include "NodeColumns.h"
#include "SimbodyReeving/element/RopeModel.h"
#include "TensionRow.h"

#include <Eigen/Core>

namespace SimbodyReeving::detail {

/// s_k is a dependent coordinate, solved from the tension equality of the two spans meeting at the
/// node, eps_{k-1}(s_k) = eps_k(s_k) (paper eq 32; a row with weights (1, 1)). With condensed
/// (quasi-static) spans its multiplier nu_k [-] is a dependent coordinate too, with the
/// stationarity of the strain energy in s_k as its row, and it enters the stationarity rows of
/// its neighbours. Interior nodes only.
struct SlidingLaw {
    static constexpr MaterialNode kKind = MaterialNode::Sliding;
    static constexpr const char* kName = "Sliding";
    static constexpr bool kAtEnd = false, kInterior = true;
    static constexpr const char* kWhereNot = "a sheave needs a span on both sides";
    static constexpr bool kExternal = false;
    static constexpr bool kDependent = true;
    static constexpr bool kDrum = false;
    static constexpr bool kTurningGroove = true;

    int place(const NodeColumns& c) { return c.dependent; }
    /// Its tension row at this evaluation: unit weights, no angle (angleOf is not called).
    template <int Dim, class AngleOf>
    void tensionRow(const AngleOf& /*angleOf*/, TensionRow<Dim>& row) const {
        row = TensionRow<Dim>{};
    }
    /// The row of its multiplier: the stationarity in s_k (stationarity() writes it).
    template <class Stationarity, class Hold>
    void multiplierRow(const Stationarity& stationarity, const Hold& /*holdAtZero*/) const {
        stationarity();
    }
    /// Its multiplier's products nu_k dC_k/d(.) in the stationarity rows, with its row's weights.
    template <class Product>
    void multiplierProducts(const Product& product) const {
        product(SlipWeights{});
    }
    /// A frictionless sheave: no friction on the rope's material (forceDifference is not called).
    template <class Difference>
    void addFriction(const Difference& /*forceDifference*/, Eigen::VectorXd& /*Qz*/, int /*materialColumn*/) const {}
};

}  // namespace SimbodyReeving::detail
