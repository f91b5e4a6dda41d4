#pragma once
/// @file
/// A groove placement (GroovePlacement.h): the groove circle stays at the node's centre, the
/// default of every node (pure C++17, no Eigen or Simbody include).

namespace SimbodyReeving {

/// The groove circle lies in the plane through the node's position normal to its axis n: its
/// axial offset x = 0 [m] whatever the node's driven coordinate Y. Every node, point or wrapped,
/// planar or spatial; no parameters.
struct CentredGroove {
    static constexpr const char* kName = "centred";  ///< the unit's name in messages
    /// x does not depend on Y: the station map adds no Y columns and no lay terms for it.
    static constexpr bool kFollowsDriven = false;
    /// x = 0 identically: the node may be any node (GroovePlacement).
    static constexpr bool kAtCentre = true;

    /// Nothing to check (no parameters).
    void validate() const {}
    double x(double /*Y*/) const { return 0.0; }    ///< x(Y) [m]
    double dx(double /*Y*/) const { return 0.0; }   ///< dx/dY [-]
    double ddx(double /*Y*/) const { return 0.0; }  ///< d2x/dY2 [1/m]
};

}  // namespace SimbodyReeving
