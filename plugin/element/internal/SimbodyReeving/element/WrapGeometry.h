#pragma once
/// @file
/// Wrap geometry of a rope over sheaves and drums of finite radius (pure C++/Eigen): the tangent
/// points where a straight span leaves or reaches a groove circle, in 3D with fleet angles, the
/// wrap angle of the rope on each groove, and their first and second time derivatives.

#include <Eigen/Core>

namespace SimbodyReeving {

/// The groove of a sheave or drum, where the rope's centre line runs: the circle of radius R about
/// the centre c in the plane normal to the unit axis n, with the sense in which the rope wraps it.
///
/// **Wrap sense sigma.** Travelling along the rope from its start towards its end, the rope on the
/// groove turns about +n (sigma = +1: counter-clockwise seen from the tip of n) or about -n
/// (sigma = -1). At a point of the groove with radial unit vector e (from c towards the point) the
/// rope's direction of travel is sigma n x e. wrapSenseFromPath gives sigma from the path's
/// geometry (the side the rope is deflected to); a rope keeps it for the whole run.
struct GrooveCircle {
    Eigen::Vector3d centre = Eigen::Vector3d::Zero();  ///< c [m], finite
    /// n [-], finite and non-zero (normalized where used: only its direction counts).
    Eigen::Vector3d axis = Eigen::Vector3d::UnitZ();
    double radius = 0;  ///< R [m] of the rope's centre line on the groove, finite and > 0
    int wrapSense = 1;  ///< sigma: +1 or -1
};

/// One end of a straight span as the tangency sees it: a point (a rope anchor, a point sheave, a
/// drum's or sheave's node when its arc is not modelled) or a groove circle that the span leaves
/// (span start) or reaches (span end) tangentially.
class TangencyEnd {
public:
    /// A point end at p [m].
    static TangencyEnd point(const Eigen::Vector3d& p) {
        TangencyEnd e;
        e.circle_.centre = p;
        e.onCircle_ = false;
        return e;
    }
    /// A groove circle end.
    static TangencyEnd circle(const GrooveCircle& c) {
        TangencyEnd e;
        e.circle_ = c;
        e.onCircle_ = true;
        return e;
    }
    /// true for a groove circle end, false for a point end.
    bool isCircle() const { return onCircle_; }
    /// The point of a point end, the centre of a circle end [m].
    const Eigen::Vector3d& position() const { return circle_.centre; }
    /// The groove circle of a circle end (for a point end: its centre is the point).
    const GrooveCircle& groove() const { return circle_; }

private:
    TangencyEnd() = default;
    GrooveCircle circle_;
    bool onCircle_ = false;
};

/// The straight span between two ends, touching each circle end tangentially: T_1 (start) and
/// T_2 (end) such that the span's direction u = (T_2 - T_1) / |T_2 - T_1| is perpendicular to the
/// groove's radius e at every circle end (tangency: the span, projected onto the groove's plane,
/// touches the circle at T), and the rope travels on in the groove's sense there:
/// sigma (n x e) . u > 0. In 3D the span may leave the groove's plane: the fleet angle
/// gamma = asin(u . n) is the angle between the span and that plane (positive towards +n).
///
/// Which of the (up to four) common tangents of two circles is taken follows from their senses:
/// point-to-circle and circle-to-circle, open (the rope stays on one side of the line of centres,
/// e.g. coplanar circles with equal senses about the same axis) and crossed (it crosses that line,
/// opposite senses).
struct SpanTangency {
    Eigen::Vector3d start = Eigen::Vector3d::Zero();  ///< T_1 [m]
    Eigen::Vector3d end = Eigen::Vector3d::Zero();    ///< T_2 [m]
    /// Unit radial vector e (from the centre to T_1) at a circle start; zero at a point end.
    Eigen::Vector3d startRadial = Eigen::Vector3d::Zero();
    Eigen::Vector3d endRadial = Eigen::Vector3d::Zero();  ///< e at T_2 (as startRadial)
    Eigen::Vector3d direction = Eigen::Vector3d::Zero();  ///< u [-]
    double length = 0;                                   ///< |T_2 - T_1| [m]
    double startFleetAngle = 0;                          ///< gamma at T_1 [rad]; 0 at a point end
    double endFleetAngle = 0;                            ///< gamma at T_2 [rad]; 0 at a point end
    int newtonIterations = 0;                            ///< of a circle-to-circle solve
};

/// Motion of one end: the velocity [m/s] and acceleration [m/s^2] of its point or centre, and the
/// first and second time derivatives of its unit axis, n' [1/s] and n'' [1/s^2] (for an axis fixed
/// on a body turning at omega: n' = omega x n, n'' = omegadot x n + omega x (omega x n); only their
/// components normal to n matter). Zero by default.
struct EndMotion {
    Eigen::Vector3d velocity = Eigen::Vector3d::Zero();          ///< of the point or centre [m/s]
    Eigen::Vector3d axisRate = Eigen::Vector3d::Zero();          ///< n' [1/s]
    Eigen::Vector3d acceleration = Eigen::Vector3d::Zero();      ///< of the point or centre [m/s^2]
    Eigen::Vector3d axisAcceleration = Eigen::Vector3d::Zero();  ///< n'' [1/s^2]
};

/// Time derivatives of a SpanTangency. The angle rate of a circle end is the rate at which its
/// radial vector e turns about the axis n, phidot = (n x e) . edot [rad/s] (e also tilts with the
/// axis: edot = phidot n x e - n (e . n')); at a point end it is 0.
struct TangencyRates {
    Eigen::Vector3d startVelocity = Eigen::Vector3d::Zero();  ///< T_1' [m/s]
    Eigen::Vector3d endVelocity = Eigen::Vector3d::Zero();    ///< T_2' [m/s]
    double startAngleRate = 0;                                ///< phidot at T_1 [rad/s]
    double endAngleRate = 0;                                  ///< phidot at T_2 [rad/s]
    Eigen::Vector3d startAcceleration = Eigen::Vector3d::Zero();  ///< T_1'' [m/s^2]
    Eigen::Vector3d endAcceleration = Eigen::Vector3d::Zero();    ///< T_2'' [m/s^2]
    double startAngleAcceleration = 0;  ///< phiddot at T_1, the time derivative of phidot [rad/s^2]
    double endAngleAcceleration = 0;    ///< phiddot at T_2 [rad/s^2]
};

/// Jacobian of a tangency: rows [T_1 (3), T_2 (3), phi_1, phi_2] with respect to the columns
/// [p_1 (3), n_1 (3), p_2 (3), n_2 (3)], p the point or centre and n the axis of each end (the
/// axis columns of a point end are zero). Rates are J [p_1', n_1', p_2', n_2'], accelerations
/// J [p_1'', n_1'', p_2'', n_2''] plus the bias acceleration (tangencyRates with zero second
/// derivatives).
using TangencyJacobian = Eigen::Matrix<double, 8, 12>;

/// Checks a groove circle.
/// @throws std::invalid_argument naming the field: non-finite centre or axis, zero axis, radius
///         not finite and > 0, wrap sense not +1 or -1.
void validateGrooveCircle(const GrooveCircle& circle);

/// The tangent points of the span from `start` to `end`.
/// Point-to-point: the chord. Point-to-circle: closed form in the groove's plane. Circle-to-circle:
/// Newton's method on the two radial angles (to a tangency residual of 1e-15 of the span's size),
/// from `warmStart`'s radial vectors when given (the previous evaluation's), else from the
/// point-to-circle tangents towards the other end, refined by two alternations.
/// @throws std::invalid_argument for an invalid groove circle (validateGrooveCircle) or a
///         non-finite point.
/// @throws std::domain_error when no tangent exists: a point end (or, for two circles, the other
///         circle) lies on or inside a groove circle's projection onto its plane, two circles
///         overlap for a crossed tangent, the span would run along a groove's axis, or the Newton
///         solve does not converge to the tangent of the given senses.
SpanTangency computeSpanTangency(const TangencyEnd& start, const TangencyEnd& end,
                                 const SpanTangency* warmStart = nullptr);

/// First and second time derivatives of the tangency for the ends' motions (analytic: the
/// tangency conditions differentiated once and twice in time).
/// @throws std::domain_error if the tangency is singular (the span along a groove's axis).
void computeTangencyRates(const TangencyEnd& start, const TangencyEnd& end, const SpanTangency& tangency,
                          const EndMotion& startMotion, const EndMotion& endMotion, TangencyRates& rates);

/// The Jacobian J of the tangency (see TangencyJacobian). With axisColumns false the axis columns
/// (n_1, n_2) are left zero: for ends whose axes do not move (a planar rope's grooves).
/// @throws std::domain_error as computeTangencyRates.
void computeTangencyJacobian(const TangencyEnd& start, const TangencyEnd& end, const SpanTangency& tangency,
                             TangencyJacobian& jacobian, bool axisColumns = true);

/// Wrap angle alpha [rad] of the rope on a groove, from the radial vector where it arrives (the end
/// of the span before the groove) to where it leaves (the start of the span after it), measured in
/// the groove's wrap sense: alpha = sigma (phi_out - phi_in), in [0, 2 pi) when `previous` is not
/// given; with `previous` (the last evaluation's wrap angle) the value alpha + 2 pi k closest to it,
/// so the angle stays continuous through full turns (double wrap). Its rate is
/// alphadot = sigma (phidot_out - phidot_in) from the two spans' TangencyRates.
double wrapAngle(const GrooveCircle& circle, const Eigen::Vector3d& arrivalRadial,
                 const Eigen::Vector3d& departureRadial, double previous);
/// As above without a previous value: alpha in [0, 2 pi).
double wrapAngle(const GrooveCircle& circle, const Eigen::Vector3d& arrivalRadial,
                 const Eigen::Vector3d& departureRadial);

/// The wrap sense of a groove from the path's geometry: the rope comes from `before`, passes the
/// groove's centre and goes on to `after`; it wraps the groove on the side it is deflected to,
/// sigma = sign(n . ((c - before) x (after - c))).
/// @throws std::invalid_argument if the three points are collinear (or nearly: the deflection's
///         sine is below 1e-9), the path's turn is normal to the groove's plane, or the input is
///         not finite.
int wrapSenseFromPath(const Eigen::Vector3d& before, const GrooveCircle& circle, const Eigen::Vector3d& after);

}  // namespace SimbodyReeving
