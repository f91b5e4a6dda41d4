#pragma once
/// @file
/// A groove placement (GroovePlacement.h): a drum that spools across its width, the groove circle
/// the rope leaves walking along the drum's axis as rope is stored (pure C++17, no Eigen or
/// Simbody include).

#include <cmath>
#include <sstream>
#include <stdexcept>

namespace SimbodyReeving {

/// The groove circle the span leaves lies
///   x(Y) = x0 + dxdY Y  [m]
/// along the groove's axis n from the node's position, Y the node's driven coordinate (the
/// material coordinate at the drum's "up", RopeModel's s_driven; at a drum that grips the rope,
/// RopeModel::setGrip, the groove's own coordinate there, s_driven less the creep
/// RopeData::gripCreep, so the exit point follows the groove's helix): dx/dY = dxdY, d2x/dY2 = 0. A
/// drum with pitch p (the axial advance per turn, about the rope's diameter) and radius R has
/// dxdY = +-p / (2 pi R) (the sign: the way the exit point walks as rope is stored); the tangent
/// point's roll (sigma R phi) does not move it, so a swinging fall shifts the exit point by less
/// than p |delta phi| / (2 pi) from the groove's helix. One layer of unbounded width (no flanges,
/// no second layer); the stored rope's ring stays at the node's position (RopeModel::setStoredRope).
/// For a wrapped Driven end node of a spatial rope (a winch drum, GroovePlacement).
struct WalkingGroove {
    static constexpr const char* kName = "walking";  ///< the unit's name in messages
    static constexpr bool kFollowsDriven = true;     ///< x depends on Y: a Driven node
    static constexpr bool kAtCentre = false;         ///< off the centre: a drum (GroovePlacement)

    double x0 = 0;    ///< x at Y = 0 [m], finite
    double dxdY = 0;  ///< the groove's axial advance per unit of Y [-], finite

    /// @throws std::invalid_argument if x0 or dxdY is not finite.
    void validate() const {
        if (std::isfinite(x0) && std::isfinite(dxdY)) return;
        std::ostringstream msg;
        msg << "a walking groove (x0 = " << x0 << " m, dxdY = " << dxdY << ") must be finite";
        throw std::invalid_argument(msg.str());
    }
    double x(double Y) const { return x0 + dxdY * Y; }  ///< x(Y) [m]
    double dx(double /*Y*/) const { return dxdY; }      ///< dx/dY [-]
    double ddx(double /*Y*/) const { return 0.0; }      ///< d2x/dY2 [1/m]
};

}  // namespace SimbodyReeving
