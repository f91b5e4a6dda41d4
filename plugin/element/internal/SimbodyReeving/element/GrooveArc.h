#pragma once
/// @file
/// The rope lying on the groove of a wrapped sheave or drum (pure C++/Eigen): its kinetic energy,
/// mass matrix, quadratic-velocity forces and gravity, from the same Lagrangian as the spans'.

#include "SimbodyReeving/element/RopeProperties.h"

#include <Eigen/Core>

namespace SimbodyReeving {

/// Results of a GrooveArc evaluation, in the arc's coordinate layout (GrooveArc::Coordinates).
template <int Dim>
struct GrooveArcData {
    /// Number of the arc's coordinates: [c, T, (n), s, l] (GrooveArc).
    static constexpr int kNumCoordinates = 2 * Dim + (Dim == 3 ? 3 : 0) + 2;
    using Vector = Eigen::Matrix<double, kNumCoordinates, 1>;                ///< a coordinate vector
    using Matrix = Eigen::Matrix<double, kNumCoordinates, kNumCoordinates>;  ///< a coordinate matrix

    /// M(x) with T = 1/2 xdot^T M xdot; symmetric, positive semi-definite (the arc length l has a
    /// zero row: l changes which material lies on the arc, not how fast it moves) [kg, kg m].
    Matrix massMatrix = Matrix::Zero();
    /// Q_v = dT/dx - Mdot xdot, so that the arc's share of Lagrange's equations is
    /// M xddot - Q_v - Q_g [N].
    Vector velocityForces = Vector::Zero();
    /// Q_g = -dU_g/dx [N].
    Vector gravityForces = Vector::Zero();
    double kineticEnergy = 0;  ///< T [J]
    double gravityEnergy = 0;  ///< U_g = -int rhoA g . r ds [J]
};

/// The rope on a groove arc: the material between the point T where the rope arrives on a groove
/// circle (the end of the span before it, in the rope's direction of travel from start to end)
/// and the point where it leaves it, an arc of length l = R alpha (alpha the wrap angle) on the
/// circle of radius R about the centre c, in the plane normal to the axis n, turning in the wrap
/// sense sigma (GrooveCircle). The rope on the arc is inextensible (its strain, of the order of
/// the spans' end strains, changes its material length by a relative eps and is not modelled):
/// the material coordinate of the departing span's start is s + l, s the arriving span's end.
///
/// **Kinematics.** With d = T - c, n_e = sigma n and theta = (s' - s) / R the angle of the material
/// point s' in [s, s + l] from T about n_e,
///     r(s') = c + cos(theta) d + sin(theta) n_e x d,
/// a point the groove carries (c, T and n move with the sheave's body and the spans' directions)
/// while the material slides along it (theta-dot = -s-dot / R at fixed s').
///
/// **Energies** (integrated in closed form over theta in [0, alpha], alpha = l / R):
///     T   = 1/2 rhoA R int |rdot|^2 dtheta,   rdot = A_0 + cos(theta) A_1 + sin(theta) A_2,
///           A_0 = cdot,  A_1 = ddot - (sdot / R) n_e x d,  A_2 = n_e-dot x d + n_e x ddot + (sdot / R) d;
///     U_g = -rhoA R g . [alpha c + sin(alpha) d + (1 - cos(alpha)) n_e x d].
/// For a fixed sheave, T = 1/2 rhoA l sdot^2: the arc adds its mass rhoA l to the rope's inertia
/// along its length; a sheave translating with the rope at rest on it adds 1/2 rhoA l |cdot|^2.
///
/// **Coordinates** x, in this order (kNumCoordinates of them; the rope model treats them as
/// external or its own as a span's):
/// - c: the groove's centre [m] (Dim);
/// - T: the arrival tangent point [m] (Dim); |T - c| = R and (T - c) . n = 0 are the caller's
///   (the wrap geometry's), not checked;
/// - n: the groove's unit axis [-] (Dim = 3 only; a planar arc turns about +z);
/// - s: the material coordinate of the rope at T [m];
/// - l: the arc's length R alpha [m], >= 0.
/// They may be redundant (T and l follow from the bodies' positions and the spans): Lagrange's
/// equations in any coordinates the caller maps them from follow by the chain rule, so the rope's
/// T + U stays an invariant when the caller's x(q) is consistent with its velocities and
/// accelerations.
///
/// **How the arc's inertia meets the spans.** At a frictionless sheave the rope model keeps the
/// axial forces of the two spans equal at the arc's ends (the tension equality, a holonomic
/// constraint on s): the arc's mass enters the rope's equations through the mass matrix (its
/// inertia along the rope and with the sheave) and its weight through Q_g, and the force that
/// accelerates it along the groove is carried by the constraint's reaction, not by a tension
/// difference. The physical tension difference rhoA l s-ddot (plus the arc's weight component
/// along it) changes the end strains by that over EA, which the model does not resolve; the
/// motion and T + U are exact for the model.
///
/// @tparam Dim 2 (planar: the groove's axis is +z, n is not a coordinate) or 3.
template <int Dim>
class GrooveArc {
public:
    static constexpr int kNumCoordinates = GrooveArcData<Dim>::kNumCoordinates;  ///< 2 Dim + 2 (+ 3 in 3D)
    using Vec = Eigen::Matrix<double, Dim, 1>;                ///< a point or vector [m]
    using Coordinates = typename GrooveArcData<Dim>::Vector;  ///< x, or its rates
    using Data = GrooveArcData<Dim>;                          ///< the results of evaluate

    /// First of the Dim centre coordinates c.
    static constexpr int centreIndex() { return 0; }
    /// First of the Dim arrival tangent point coordinates T.
    static constexpr int tangentPointIndex() { return Dim; }
    /// First of the 3 axis coordinates (Dim = 3 only).
    static constexpr int axisIndex() { return 2 * Dim; }
    /// The material coordinate s at T.
    static constexpr int materialIndex() { return kNumCoordinates - 2; }
    /// The arc length l.
    static constexpr int lengthIndex() { return kNumCoordinates - 1; }

    /// @param properties the rope's properties (rhoA [kg/m] is used; see RopeProperties).
    /// @param radius     R [m] of the rope's centre line on the groove, finite and > 0.
    /// @param wrapSense  sigma: +1 or -1 (GrooveCircle::wrapSense).
    /// @param gravity    g [m/s^2], finite.
    /// @throws std::invalid_argument for properties outside RopeProperties' ranges, a radius not
    ///         finite and > 0, a wrap sense other than +1 or -1, or non-finite gravity.
    GrooveArc(const RopeProperties& properties, double radius, int wrapSense, const Vec& gravity);

    double radius() const { return radius_; }               ///< R [m]
    int wrapSense() const { return wrapSense_; }            ///< sigma
    const Vec& gravity() const { return gravity_; }         ///< g [m/s^2]
    double massPerLength() const { return massPerLength_; } ///< rhoA [kg/m]

    /// Mass matrix, quadratic-velocity and gravity forces, energies at (x, xdot). Allocation-free.
    /// @throws std::invalid_argument if l < 0 or an entry of x or xdot is not finite.
    void evaluate(const Coordinates& x, const Coordinates& xdot, Data& data) const;

    /// T [J] alone (closed form, as evaluate).
    double kineticEnergy(const Coordinates& x, const Coordinates& xdot) const;
    /// U_g [J] alone.
    double gravityEnergy(const Coordinates& x) const;
    /// Position [m] of the material point at arc length a in [0, l] from T.
    Vec materialPosition(const Coordinates& x, double arcLength) const;
    /// Velocity [m/s] of the material point at arc length a from T (material fixed: s' = s + a).
    Vec materialVelocity(const Coordinates& x, const Coordinates& xdot, double arcLength) const;

private:
    double massPerLength_ = 0, radius_ = 0;
    int wrapSense_ = 1;
    Vec gravity_ = Vec::Zero();
};

}  // namespace SimbodyReeving
