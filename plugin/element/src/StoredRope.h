#pragma once
/// @file
/// Internal to the element layer (not installed): the rope stored on a winch drum at an end node of
/// a RopeModel, as a node law of its own (RopeModel::setStoredRope): its length, kinetic and
/// gravity energies and its share of the rope's effective mass S and force h at the external
/// coordinates it depends on.

#include <Eigen/Core>

#include <array>

namespace SimbodyReeving::detail {

/// The stored rope's contribution at the external coordinates x of its rope: for the columns
/// cols[0..count), the mass block (S += mass) and force (h += force) the Lagrangian of the stored
/// rope adds, and its energies. Fixed size: no allocation per evaluation.
template <int Dim>
struct StoredRopeTerms {
    static constexpr int kMaxColumns = 3 * Dim + 1;  ///< centre, tangent point, axis (turning), s
    int count = 0;
    std::array<int, kMaxColumns> cols{};
    Eigen::Matrix<double, kMaxColumns, kMaxColumns> mass = Eigen::Matrix<double, kMaxColumns, kMaxColumns>::Zero();
    Eigen::Matrix<double, kMaxColumns, 1> force = Eigen::Matrix<double, kMaxColumns, 1>::Zero();
    double kineticEnergy = 0;  ///< [J]
    double gravityEnergy = 0;  ///< [J]
};

/// Rope wound on a drum at end node k (a Driven node): the material beyond the node's material
/// coordinate s_k, of length l = l_0 + kappa s_k (kappa = +1 at the rope's start, -1 at its end:
/// hauling material out of the spans stores it).
///
/// **Point drum** (the node a point r): the rope is held as a ring moving with the node at the
/// rope's own rate at the node,
///     T = 1/2 rhoA l (|rdot|^2 + sdot_k^2),   U = -rhoA l g . r.
/// (At a point drum s_k is the drum's surface coordinate, so sdot_k is the drum's surface speed.)
///
/// **Wrapped drum** (the groove a circle of radius R about the centre c in the plane normal to
/// its axis n, +z in a planar rope; the rope leaving it at the tangent point T, wrap sense sigma):
/// the stored rope lies on the groove and turns with the drum. A material point s on it sits at
/// the angle psi(s) = sigma (s - Y_s) / R from "up" (counter-clockwise about n, against gravity
/// projected onto the groove's plane; +y without gravity), Y_s = s_k - sigma R phi the drum's
/// surface coordinate at "up" and phi the tangent point's angle; its velocity is
/// cdot - sigma v u'(psi), v = Ydot_s = sdot_k - sigma R phidot the drum's surface speed (at a
/// gripping drum, RopeModel::setGrip, the caller passes the groove's rate for sdot_k), whatever
/// the tangent point does. Integrated over the stored material (from the tangent point to the
/// far end at psi_e = phi - sigma kappa l / R):
///     T = 1/2 rhoA [l (|cdot|^2 + v^2) - 2 R kappa v cdot . (u(phi) - u(psi_e))],
///     U = -rhoA l g . c + rhoA |g| sigma kappa R^2 (sin phi - sin psi_e),
/// u(psi) = cos psi up + sin psi n x up, |g| the magnitude of gravity in the groove's plane. The
/// last terms are the partial turn's: the energy of a full turn does not depend on where the drum
/// stands. These are exact for a single layer of any number of turns in the groove's plane (the
/// ring does not advance across the drum), with the axis constant (a drum whose body keeps its
/// orientation).
///
/// **Wrapped drum whose axis turns** (Dim = 3, setTurningAxis: a drum on a slewing or luffing
/// body; n = a - c from an axis station a, |n| = 1): the stored rope turns rigidly with the drum.
/// Its angular velocity is Omega_s n + Omega_perp, Omega_perp = n x ndot (the axis' tumbling) and
/// Omega_s = f . (Tdot - cdot) / R - sigma sdot_k / R the spin about n (f = n x e, e = (T - c) / R
/// the tangent point's radial: the tangent radial's turn less the material's slide past it).
/// With the stored arc's moments I1 = int u dlambda, I2 = int u u^T dlambda over its length (u the
/// radial of the material at lambda from the tangent point, turned by -sigma kappa lambda / R
/// about n from e), integrated in closed form,
///     T = 1/2 rhoA [l |cdot|^2 + 2 R Omega_s cdot . (n x I1) + 2 R cdot . (Omega_perp x I1)
///                   + R^2 l Omega_s^2 + R^2 (l |Omega_perp|^2 - Omega_perp^T I2 Omega_perp)],
///     U = -rhoA (l g . c + R g . I1).
/// (The spin and tumbling cross term vanishes: n x u is normal to Omega_perp x u.) With the axis
/// fixed it is the law above. Its mass block and force at (c, T, n, s) are the Lagrangian's
/// derivatives, taken by forward automatic differentiation of T's velocity map and U.
template <int Dim>
class StoredRope {
public:
    using Vec = Eigen::Matrix<double, Dim, 1>;

    /// @param node          k, 0 or N.
    /// @param lengthAtZero  l_0 [m].
    /// @param massPerLength rhoA [kg/m].
    /// @param gravity       g [m/s^2].
    StoredRope(int node, double lengthAtZero, double slope, double massPerLength, const Vec& gravity)
        : node_(node), lengthAtZero_(lengthAtZero), slope_(slope), rhoA_(massPerLength), gravity_(gravity) {}

    /// Declares the drum wrapped: the groove's radius R [m] > 0 and wrap sense sigma (+-1), the
    /// external coordinates of its centre, of its tangent point and (Dim = 3) of its axis.
    void setWrapped(double radius, int wrapSense, int centreOffset, int tangentOffset, int axisOffset = 0) {
        radius_ = radius;
        sense_ = wrapSense;
        centreOffset_ = centreOffset;
        tangentOffset_ = tangentOffset;
        axisOffset_ = axisOffset;
    }
    /// Declares the wrapped drum's axis turning: its x columns at the axis offset are n = a - c,
    /// whose rates enter the law (Dim = 3 only).
    void setTurningAxis() { turningAxis_ = true; }
    bool hasTurningAxis() const { return turningAxis_; }
    /// The external coordinate of the node's position (a point drum).
    void setPointOffset(int offset) { centreOffset_ = offset; }
    /// The external coordinate of the node's material coordinate s_k.
    void setMaterialOffset(int offset) { materialOffset_ = offset; }

    int node() const { return node_; }
    double slope() const { return slope_; }
    double lengthAtZero() const { return lengthAtZero_; }
    void setLengthAtZero(double l0) { lengthAtZero_ = l0; }
    bool isWrapped() const { return radius_ > 0; }
    /// l [m] at the node's material coordinate s [m].
    double length(double s) const { return lengthAtZero_ + slope_ * s; }

    /// The terms at x, xdot (external coordinates and rates) with the node's s_k, sdot_k.
    void evaluate(const Eigen::VectorXd& x, const Eigen::VectorXd& xdot, double s, double sdot,
                  StoredRopeTerms<Dim>& out) const;
    /// U [J] at x and s (no rates).
    double gravityEnergy(const Eigen::VectorXd& x, double s) const;

private:
    void evaluatePoint(const Eigen::VectorXd& x, const Eigen::VectorXd& xdot, double s, double sdot,
                       StoredRopeTerms<Dim>& out) const;
    void evaluateWrapped(const Eigen::VectorXd& x, const Eigen::VectorXd& xdot, double s, double sdot,
                         StoredRopeTerms<Dim>& out) const;
    // StoredRopeTurningAxis.cpp.
    void evaluateTurningAxis(const Eigen::VectorXd& x, const Eigen::VectorXd& xdot, double s, double sdot,
                             StoredRopeTerms<Dim>& out) const;
    int node_;
    double lengthAtZero_, slope_, rhoA_;
    Vec gravity_;
    double radius_ = 0;
    int sense_ = 1;
    int centreOffset_ = 0, tangentOffset_ = 0, axisOffset_ = 0, materialOffset_ = 0;
    bool turningAxis_ = false;
};

// (Defined in StoredRopeTurningAxis.cpp; the planar one throws std::logic_error.)
template <>
void StoredRope<3>::evaluateTurningAxis(const Eigen::VectorXd& x, const Eigen::VectorXd& xdot, double s, double sdot,
                                        StoredRopeTerms<3>& out) const;
template <>
void StoredRope<2>::evaluateTurningAxis(const Eigen::VectorXd& x, const Eigen::VectorXd& xdot, double s, double sdot,
                                        StoredRopeTerms<2>& out) const;

}  // namespace SimbodyReeving::detail
