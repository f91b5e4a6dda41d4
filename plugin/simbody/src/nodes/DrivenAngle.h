#pragma once
/// @file
/// Internal to the plugin: how the angle theta [rad] that drives a Driven node's material
/// coordinate (s = s_ref + g(theta), DrivenLaw.h) is measured at run time, one unit per way:
///   - PinAngle: the pin's own coordinate, theta = q, thetadot = u (a point or gripping sheave or
///     drum whose parent keeps its orientation, every TractionSheave);
///   - ParentTurnAngle: a wrapped gripping groove of a planar rope on a parent that turns about
///     the fixed groove axis a: the sheave body's own angle, theta = q + psi (psi the parent's
///     turn about a, ParentTurnAngle::parentTurn), thetadot = a . omega_B;
///   - TurningAxisAngle: a wrapped gripping groove of a spatial rope whose pin axis turns with the
///     parent: theta = q + psi measured about the current axis from "up" projected onto the
///     groove's plane, thetadot = m . omega_B (turningGripAxis).
/// Each unit gives theta, thetadot, the parent's turn it includes (for the half-turn limit) and its
/// row of the coupled solve (DrivenAngleRow: how thetadot depends on the mobilities this
/// evaluation). DrivenAngle holds one of them (std::variant: a closed set dispatched by
/// std::visit, no virtual call, no heap); a new way of measuring is one new unit plus its entry
/// in DrivenAngle::Unit.

#include <Simbody.h>

#include <variant>

namespace SimbodyReeving {
namespace detail {

/// A gripping groove whose axis n turns at omega (TurningAxisAngle): its angle's rate is
/// omega . m with m = (n - a g_up) / (1 - a^2), a = n . g_up (g_up = -g / |g|, "up" of the
/// rope model's grip); mdotOmega = mdot . omega, the rate's bias (omega held) [1/s^2].
inline void turningGripAxis(const SimTK::Vec3& n, const SimTK::Vec3& omega, const SimTK::Vec3& gUp, SimTK::Vec3& m,
                            double& mdotOmega) {
    const double a = SimTK::dot(n, gUp), q = 1 - a * a;
    m = (n - a * gUp) / q;
    const SimTK::Vec3 ndot = SimTK::cross(omega, n);
    const double adot = SimTK::dot(ndot, gUp);
    const SimTK::Vec3 mdot = (ndot - adot * gUp) / q + (n - a * gUp) * (2 * a * adot / (q * q));
    mdotOmega = SimTK::dot(mdot, omega);
}

/// Where a driven angle's rate comes from in one evaluation of the coupled solve:
///   - a mobility row (mobility >= 0): thetadot = u[mobility], thetaddot = udot[mobility], and a
///     generalized force f [N m] on theta is the mobility force f;
///   - a body row (mobility < 0): thetadot = axis . omega_B of body `body`, thetaddot =
///     axis . omegadot_B + bias [rad/s^2], and f is the torque f axis on that body.
struct DrivenAngleRow {
    int mobility = -1;
    SimTK::MobilizedBodyIndex body;
    SimTK::Vec3 axis{0};  // [-], Ground
    double bias = 0;      // [rad/s^2]

    bool onMobility() const { return mobility >= 0; }
    /// thetaddot [rad/s^2] from the bodies' spatial accelerations A_GB and the mobilities' udot.
    double acceleration(const SimTK::Vector_<SimTK::SpatialVec>& A_GB, const SimTK::Vector& udot) const {
        return onMobility() ? udot[mobility] : SimTK::dot(axis, A_GB[body][0]) + bias;
    }
    /// A body row's thetadot [rad/s] for the bodies' spatial velocities V_GB (its Jacobian
    /// column for a unit mobility speed).
    double bodyRate(const SimTK::Vector_<SimTK::SpatialVec>& V_GB) const { return SimTK::dot(axis, V_GB[body][0]); }
    /// A body row's generalized force f [N m] as a spatial force on its body: the torque f axis.
    SimTK::SpatialVec bodyTorque(double f) const { return SimTK::SpatialVec(f * axis, SimTK::Vec3(0)); }
    /// Applies the generalized force f [N m] on theta: to the mobility, or as a torque on the body.
    void addGeneralizedForce(double f, SimTK::Vector& mobilityForces,
                             SimTK::Vector_<SimTK::SpatialVec>& bodyForces) const {
        if (onMobility())
            mobilityForces[mobility] += f;
        else
            bodyForces[body] += bodyTorque(f);
    }
};

/// Where a driven angle is measured: the node's pin (a MobilizedBody::Pin) and "up" of the grip
/// (-g / |g|, +y without gravity).
struct DrivenAngleSite {
    const SimTK::State& state;
    const SimTK::MobilizedBody& pin;
    SimTK::Vec3 gripUp;
};

/// theta = q, thetadot = u: the pin's own coordinate.
struct PinAngle {
    double angle(const DrivenAngleSite& site) const { return site.pin.getOneQ(site.state, 0); }
    double rate(const DrivenAngleSite& site) const { return site.pin.getOneU(site.state, 0); }
    /// Its row: the pin's mobility.
    void row(const DrivenAngleSite& site, DrivenAngleRow& out) const {
        out = DrivenAngleRow{};
        out.mobility = static_cast<int>(site.pin.getFirstUIndex(site.state));
    }
    /// No parent's turn is part of theta.
    bool includesParentTurn(const SimTK::MobilizedBody&) const { return false; }
    double parentTurn(const DrivenAngleSite&) const { return 0.0; }
};

/// theta = q + psi, psi the rotation [rad] of the pin's parent about the fixed groove axis `axis`
/// (Ground; +- a planar rope's plane normal) measured from Ground's orientation in (-pi, pi] (0 on
/// Ground); thetadot = axis . omega_B: the sheave body's own angle, so a parent that turns
/// carries the rope on the groove with it.
struct ParentTurnAngle {
    SimTK::Vec3 axis{0, 0, 1};

    double angle(const DrivenAngleSite& site) const { return site.pin.getOneQ(site.state, 0) + parentTurn(site); }
    double rate(const DrivenAngleSite& site) const {
        return SimTK::dot(axis, site.pin.getBodyAngularVelocity(site.state));
    }
    /// Its row: the sheave body's angular velocity about `axis` (no bias: the axis is fixed).
    void row(const DrivenAngleSite& site, DrivenAngleRow& out) const {
        out = DrivenAngleRow{};
        out.body = site.pin.getMobilizedBodyIndex();
        out.axis = axis;
    }
    /// theta holds the parent's turn unless the parent is Ground.
    bool includesParentTurn(const SimTK::MobilizedBody& pin) const {
        return !pin.getParentMobilizedBody().isGround();
    }
    /// psi = atan2(a . (e x R_GP e), e . R_GP e), e perpendicular to a [rad].
    double parentTurn(const DrivenAngleSite& site) const;
};

/// A spatial rope's gripping groove whose pin axis turns with the parent: theta = q + psi, psi the
/// angle of a parent direction (parentPerp, normal to the pin axis parentAxis, parent frame)
/// about the current axis n from "up" projected onto the groove's plane, less its value with the
/// parent at Ground's orientation; thetadot = omega_B . m, m = (n - a g_up) / (1 - a^2),
/// a = n . g_up, n = R_GB bodyAxis (turningGripAxis), with the bias mdot . omega_B.
struct TurningAxisAngle {
    SimTK::Vec3 bodyAxis{0, 0, 1}, parentAxis{0, 0, 1}, parentPerp{1, 0, 0};

    double angle(const DrivenAngleSite& site) const { return site.pin.getOneQ(site.state, 0) + parentTurn(site); }
    double rate(const DrivenAngleSite& site) const {
        DrivenAngleRow r;
        row(site, r);
        return SimTK::dot(r.axis, site.pin.getBodyAngularVelocity(site.state));
    }
    /// Its row: the sheave body's angular velocity about m, with the bias mdot . omega_B.
    void row(const DrivenAngleSite& site, DrivenAngleRow& out) const {
        out = DrivenAngleRow{};
        out.body = site.pin.getMobilizedBodyIndex();
        turningGripAxis(site.pin.getBodyRotation(site.state) * bodyAxis, site.pin.getBodyAngularVelocity(site.state),
                        site.gripUp, out.axis, out.bias);
    }
    bool includesParentTurn(const SimTK::MobilizedBody& pin) const {
        return !pin.getParentMobilizedBody().isGround();
    }
    /// psi in (-pi, pi] [rad] (0 on Ground).
    double parentTurn(const DrivenAngleSite& site) const;
};

/// A Driven node's angle measure: one of the units above (PinAngle unless the node's wrap says
/// otherwise, grippingSheaveWrap).
struct DrivenAngle {
    using Unit = std::variant<PinAngle, ParentTurnAngle, TurningAxisAngle>;
    Unit unit;

    /// theta [rad].
    double angle(const DrivenAngleSite& site) const {
        return std::visit([&](const auto& u) { return u.angle(site); }, unit);
    }
    /// thetadot [rad/s].
    double rate(const DrivenAngleSite& site) const {
        return std::visit([&](const auto& u) { return u.rate(site); }, unit);
    }
    /// Its row of the coupled solve in this evaluation (Stage::Velocity: a turning axis's bias).
    void row(const DrivenAngleSite& site, DrivenAngleRow& out) const {
        std::visit([&](const auto& u) { u.row(site, out); }, unit);
    }
    /// True if theta holds a turn of the pin's parent (measured within half a turn: the run must
    /// end before it passes pi, ReevingSubsystem::Guts::limitMargin).
    bool includesParentTurn(const SimTK::MobilizedBody& pin) const {
        return std::visit([&](const auto& u) { return u.includesParentTurn(pin); }, unit);
    }
    /// The parent's turn psi in theta [rad], in (-pi, pi] (0 for PinAngle and on Ground).
    double parentTurn(const DrivenAngleSite& site) const {
        return std::visit([&](const auto& u) { return u.parentTurn(site); }, unit);
    }
};

}  // namespace detail
}  // namespace SimbodyReeving
