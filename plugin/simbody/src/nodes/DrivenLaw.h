#pragma once
/// @file
/// Internal to the plugin: the driven relation of a Driven node, s = s_ref + g(theta): the rope's
/// material coordinate s [m] at the node as a function of the node's angle theta [rad]
/// (DrivenAngle.h). s_ref [m] is the node's offset (its spec's, or a TractionSheave's stick
/// offset, which is state); the law is g with its derivatives, one unit per shape:
///   - LinearDrivenLaw: g = dsdTheta theta (a drum or gripping sheave of radius R: dsdTheta =
///     +-R).
/// DrivenLaw holds one of them (std::variant, dispatched by std::visit); a new shape is one new
/// unit plus its entry in DrivenLaw::Unit. The generic code asks the law, never a slope of its
/// own: the coupled solve's row of s is g'(theta) times theta's row (DrivenAngleRow) and its
/// acceleration sddot = g' thetaddot + g'' thetadot^2 (law.acceleration).

#include <variant>

namespace SimbodyReeving {
namespace detail {

/// s = s_ref + dsdTheta theta, dsdTheta [m/rad].
struct LinearDrivenLaw {
    double dsdTheta = 0;

    /// s [m] at angle theta [rad] with offset sRef [m]: sRef + dsdTheta theta.
    double materialCoordinate(double sRef, double theta) const { return sRef + dsdTheta * theta; }
    /// sdot [m/s]: dsdTheta thetadot.
    double materialRate(double /*theta*/, double thetaDot) const { return dsdTheta * thetaDot; }
    /// sddot [m/s^2]: dsdTheta thetaddot (g'' = 0).
    double acceleration(double /*theta*/, double /*thetaDot*/, double thetaDDot) const { return dsdTheta * thetaDDot; }
    /// ds/dtheta [m/rad]: dsdTheta.
    double slope(double /*theta*/) const { return dsdTheta; }
    /// The offset that puts s at angle theta: s - dsdTheta theta [m].
    double offsetOf(double s, double theta) const { return s - dsdTheta * theta; }
};

/// A Driven node's relation s = s_ref + g(theta): one of the units above.
struct DrivenLaw {
    using Unit = std::variant<LinearDrivenLaw>;
    Unit unit;

    /// s = sRef + g(theta) [m].
    double materialCoordinate(double sRef, double theta) const {
        return std::visit([&](const auto& u) { return u.materialCoordinate(sRef, theta); }, unit);
    }
    /// sdot = g'(theta) thetadot [m/s].
    double materialRate(double theta, double thetaDot) const {
        return std::visit([&](const auto& u) { return u.materialRate(theta, thetaDot); }, unit);
    }
    /// sddot = g'(theta) thetaddot + g''(theta) thetadot^2 [m/s^2].
    double acceleration(double theta, double thetaDot, double thetaDDot) const {
        return std::visit([&](const auto& u) { return u.acceleration(theta, thetaDot, thetaDDot); }, unit);
    }
    /// g'(theta) = ds/dtheta [m/rad]: the scale from theta's row to s's, and from a force on s [N]
    /// to the generalized force on theta [N m].
    double slope(double theta) const {
        return std::visit([&](const auto& u) { return u.slope(theta); }, unit);
    }
    /// The offset sRef [m] that puts s at angle theta: s - g(theta) (a TractionSheave's stick
    /// offset taking over from its slip state, s continuous).
    double offsetOf(double s, double theta) const {
        return std::visit([&](const auto& u) { return u.offsetOf(s, theta); }, unit);
    }
};

}  // namespace detail
}  // namespace SimbodyReeving
