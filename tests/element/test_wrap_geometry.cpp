// Wrap geometry: tangent points, fleet angles and wrap angles of spans over groove circles against
// closed forms, and their first and second time derivatives against finite differences.
#include "SimbodyReeving/element/WrapGeometry.h"

#include "support/ExpectThrowMessage.h"

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include <cmath>
#include <functional>

using namespace SimbodyReeving;
using Eigen::Vector3d;

namespace {

constexpr double kPi = 3.14159265358979323846;

// Closed forms are evaluated in double precision from inputs of order 1-10 m; the tangent points
// agree with them to at most 1.3e-15 m (measured over this file's cases): 1e-13 m is an 80x margin,
// and ten times tighter than the 1e-12 m the wrapped-sheave model asks of its geometry.
constexpr double kPositionTolerance = 1e-13;

GrooveCircle groove(const Vector3d& c, const Vector3d& n, double R, int sense) {
    GrooveCircle g;
    g.centre = c;
    g.axis = n;
    g.radius = R;
    g.wrapSense = sense;
    return g;
}

Eigen::Matrix3d rotation(const Vector3d& axis, double angle) {
    return Eigen::AngleAxisd(angle, axis.normalized()).toRotationMatrix();
}

}  // namespace

// Point to circle in the groove's plane: the tangent from P at distance p from the centre touches
// at c + (R^2/p) d + s R sqrt(p^2 - R^2)/p (n x d), d = (P - c)/p, on the side s the rope travels
// the groove's sense (checked on the four cases arriving/leaving x sense +-1).
TEST(WrapGeometry, PointToCircleMatchesTheClosedForm) {
    const Vector3d c(1.0, 2.0, 0.0), n = Vector3d::UnitZ();
    const double R = 0.3;
    const double p = 4.0, theta = 0.7;
    const Vector3d d(std::cos(theta), std::sin(theta), 0.0);
    const Vector3d P = c + p * d;
    const Vector3d along = c + (R * R / p) * d, across = (R * std::sqrt(p * p - R * R) / p) * n.cross(d);
    for (int sense : {1, -1}) {
        const GrooveCircle g = groove(c, n, R, sense);
        // Rope from P onto the groove: travelling sense n x e at T, it must come from P.
        const SpanTangency in = computeSpanTangency(TangencyEnd::point(P), TangencyEnd::circle(g));
        const Vector3d expectedIn = along + sense * across;
        EXPECT_LT((in.end - expectedIn).norm(), kPositionTolerance) << "sense " << sense;
        EXPECT_LT((in.start - P).norm(), 1e-15);
        EXPECT_NEAR(in.length, std::sqrt(p * p - R * R), kPositionTolerance);
        EXPECT_EQ(in.endFleetAngle, 0.0);
        // Leaving the groove towards P: the other tangent.
        const SpanTangency out = computeSpanTangency(TangencyEnd::circle(g), TangencyEnd::point(P));
        const Vector3d expectedOut = along - sense * across;
        EXPECT_LT((out.start - expectedOut).norm(), kPositionTolerance) << "sense " << sense;
    }
    // A concrete picture: a rope from far left, wrapping counter-clockwise, touches the bottom.
    const GrooveCircle ccw = groove(Vector3d::Zero(), n, 0.5, 1);
    const SpanTangency bottom =
        computeSpanTangency(TangencyEnd::point(Vector3d(-1e6, -0.5, 0)), TangencyEnd::circle(ccw));
    EXPECT_LT((bottom.end - Vector3d(0, -0.5, 0)).norm(), 1e-6);  // (the point is 1e6 m away, not at infinity)
}

// Two coplanar circles, line of centres along x at distance L. Open tangent (equal senses): both
// radial vectors are e = ((R1 - R2)/L, -sqrt(1 - ((R1 - R2)/L)^2)) for counter-clockwise senses
// (the rope runs below the centres, travelling +x). Crossed (opposite senses): e1 = ((R1 + R2)/L,
// -sqrt(1 - ((R1 + R2)/L)^2)), e2 = -e1.
TEST(WrapGeometry, CircleToCircleOpenAndCrossedMatchTheClosedForms) {
    const Vector3d c1(0.5, -1.0, 0.0), n = Vector3d::UnitZ();
    const double L = 3.0, R1 = 0.4, R2 = 0.15;
    const Vector3d c2 = c1 + Vector3d(L, 0, 0);
    {
        const double ex = (R1 - R2) / L;
        const Vector3d e(ex, -std::sqrt(1 - ex * ex), 0);
        const SpanTangency t =
            computeSpanTangency(TangencyEnd::circle(groove(c1, n, R1, 1)), TangencyEnd::circle(groove(c2, n, R2, 1)));
        EXPECT_LT((t.start - (c1 + R1 * e)).norm(), kPositionTolerance);
        EXPECT_LT((t.end - (c2 + R2 * e)).norm(), kPositionTolerance);
        EXPECT_NEAR(t.length, std::sqrt(L * L - (R1 - R2) * (R1 - R2)), kPositionTolerance);
        EXPECT_LE(t.newtonIterations, 6);
        // Mirror: clockwise senses run above.
        const SpanTangency m =
            computeSpanTangency(TangencyEnd::circle(groove(c1, n, R1, -1)), TangencyEnd::circle(groove(c2, n, R2, -1)));
        const Vector3d em(ex, std::sqrt(1 - ex * ex), 0);
        EXPECT_LT((m.start - (c1 + R1 * em)).norm(), kPositionTolerance);
        EXPECT_LT((m.end - (c2 + R2 * em)).norm(), kPositionTolerance);
    }
    {
        const double ex = (R1 + R2) / L;
        const Vector3d e1(ex, -std::sqrt(1 - ex * ex), 0);
        const SpanTangency t =
            computeSpanTangency(TangencyEnd::circle(groove(c1, n, R1, 1)), TangencyEnd::circle(groove(c2, n, R2, -1)));
        EXPECT_LT((t.start - (c1 + R1 * e1)).norm(), kPositionTolerance);
        EXPECT_LT((t.end - (c2 - R2 * e1)).norm(), kPositionTolerance);
        EXPECT_NEAR(t.length, std::sqrt(L * L - (R1 + R2) * (R1 + R2)), kPositionTolerance);
    }
    // The same with the axis reversed and the senses reversed: the same physical wrap.
    const SpanTangency a =
        computeSpanTangency(TangencyEnd::circle(groove(c1, n, R1, 1)), TangencyEnd::circle(groove(c2, n, R2, 1)));
    const SpanTangency b =
        computeSpanTangency(TangencyEnd::circle(groove(c1, -n, R1, -1)), TangencyEnd::circle(groove(c2, -n, R2, -1)));
    EXPECT_LT((a.start - b.start).norm(), kPositionTolerance);
    EXPECT_LT((a.end - b.end).norm(), kPositionTolerance);
}

// Out of the groove's plane: a point h above the plane touches where its projection does, and the
// span leaves the plane at the fleet angle gamma = atan(h / l), l = sqrt(p^2 - R^2) the tangent's
// length in the plane. Two circles in parallel planes h apart: the planar tangent points, and the
// fleet angle atan(h / l) at both ends.
TEST(WrapGeometry, SpatialTangentsHaveTheClosedFormFleetAngle) {
    const Vector3d c(0, 0, 0), n = Vector3d::UnitZ();
    const double R = 0.25, p = 2.0, h = 0.6;
    const double l = std::sqrt(p * p - R * R);
    const GrooveCircle g = groove(c, n, R, 1);
    const SpanTangency t = computeSpanTangency(TangencyEnd::point(Vector3d(p, 0, h)), TangencyEnd::circle(g));
    EXPECT_LT((t.end - Vector3d(R * R / p, R * l / p, 0)).norm(), kPositionTolerance);
    EXPECT_NEAR(t.endFleetAngle, -std::atan2(h, l), 1e-14);  // the span descends towards the groove
    EXPECT_NEAR(t.length, std::hypot(l, h), kPositionTolerance);

    const double L = 2.5, R1 = 0.3, R2 = 0.2;
    const Vector3d c2(L, 0, h);
    const SpanTangency s =
        computeSpanTangency(TangencyEnd::circle(groove(c, n, R1, 1)), TangencyEnd::circle(groove(c2, n, R2, 1)));
    const double ex = (R1 - R2) / L;
    const Vector3d e(ex, -std::sqrt(1 - ex * ex), 0);
    const double lPlanar = std::sqrt(L * L - (R1 - R2) * (R1 - R2));
    EXPECT_LT((s.start - (c + R1 * e)).norm(), kPositionTolerance);
    EXPECT_LT((s.end - (c2 + R2 * e)).norm(), kPositionTolerance);
    EXPECT_NEAR(s.startFleetAngle, std::atan2(h, lPlanar), 1e-14);
    EXPECT_NEAR(s.endFleetAngle, std::atan2(h, lPlanar), 1e-14);
}

// A rigid motion of the whole arrangement (a slewing jib) moves the tangent points with it, for
// circles with non-parallel axes too (no closed form there: the tangency conditions and the
// travelling senses are checked instead).
TEST(WrapGeometry, TiltedCirclesSatisfyTheTangencyAndFollowRigidMotions) {
    const GrooveCircle a = groove(Vector3d(0, 0, 0), Vector3d(0.1, 0.2, 1.0), 0.35, 1);
    const GrooveCircle b = groove(Vector3d(0.4, -3.0, 0.7), Vector3d(1.0, 0.3, -0.2), 0.2, -1);
    const SpanTangency t = computeSpanTangency(TangencyEnd::circle(a), TangencyEnd::circle(b));
    const Vector3d na = a.axis.normalized(), nb = b.axis.normalized();
    EXPECT_LT(std::abs(t.direction.dot(t.startRadial)), 1e-15);
    EXPECT_LT(std::abs(t.direction.dot(t.endRadial)), 1e-15);
    EXPECT_GT(a.wrapSense * na.cross(t.startRadial).dot(t.direction), 0);
    EXPECT_GT(b.wrapSense * nb.cross(t.endRadial).dot(t.direction), 0);
    EXPECT_NEAR((t.start - a.centre).norm(), a.radius, 1e-15);
    EXPECT_NEAR(t.startRadial.dot(na), 0, 1e-15);

    const Eigen::Matrix3d Q = rotation(Vector3d(0.3, -1.0, 0.5), 1.1);
    const Vector3d shift(5, -2, 7);
    GrooveCircle a2 = a, b2 = b;
    a2.centre = Q * a.centre + shift;
    a2.axis = Q * a.axis;
    b2.centre = Q * b.centre + shift;
    b2.axis = Q * b.axis;
    const SpanTangency u = computeSpanTangency(TangencyEnd::circle(a2), TangencyEnd::circle(b2));
    EXPECT_LT((u.start - (Q * t.start + shift)).norm(), kPositionTolerance);
    EXPECT_LT((u.end - (Q * t.end + shift)).norm(), kPositionTolerance);
    EXPECT_NEAR(u.startFleetAngle, t.startFleetAngle, 1e-13);

    // Warm start from the solution of a nearby configuration converges to the same tangent.
    GrooveCircle b3 = b;
    b3.centre += Vector3d(1e-3, 2e-3, -1e-3);
    const SpanTangency cold = computeSpanTangency(TangencyEnd::circle(a), TangencyEnd::circle(b3));
    const SpanTangency warm = computeSpanTangency(TangencyEnd::circle(a), TangencyEnd::circle(b3), &t);
    EXPECT_LT((cold.start - warm.start).norm(), 1e-14);
    EXPECT_LT((cold.end - warm.end).norm(), 1e-14);
    EXPECT_LE(warm.newtonIterations, 4);
}

// Wrap angle of a sheave between two point ends: the rope's direction turns by the deflection of
// the path through the centre plus asin(R / d) at each side (the tangents lean towards the
// groove): alpha = delta + asin(R/d1) + asin(R/d2). The Atwood picture (both falls vertical below
// the groove's horizontal diameter) wraps exactly pi.
TEST(WrapGeometry, WrapAngleMatchesTheDeflectionOfThePath) {
    const Vector3d c(0.2, 5.0, 0.0), n = Vector3d::UnitZ();
    const double R = 0.3;
    const Vector3d P1(-4.0, 1.0, 0.0), P2(3.0, 0.5, 0.0);
    GrooveCircle g = groove(c, n, R, 1);
    g.wrapSense = wrapSenseFromPath(P1, g, P2);
    EXPECT_EQ(g.wrapSense, -1);  // up on the left, over the top, down on the right: clockwise about +z
    const SpanTangency in = computeSpanTangency(TangencyEnd::point(P1), TangencyEnd::circle(g));
    const SpanTangency out = computeSpanTangency(TangencyEnd::circle(g), TangencyEnd::point(P2));
    const Vector3d a = (c - P1), b = (P2 - c);
    const double delta = std::atan2(g.wrapSense * n.dot(a.cross(b)), a.dot(b));
    const double expected = delta + std::asin(R / a.norm()) + std::asin(R / b.norm());
    EXPECT_NEAR(wrapAngle(g, in.endRadial, out.startRadial), expected, 1e-14);

    const double H = 7.0;
    const SpanTangency left = computeSpanTangency(TangencyEnd::point(c + Vector3d(-R, -H, 0)), TangencyEnd::circle(g));
    const SpanTangency right = computeSpanTangency(TangencyEnd::circle(g), TangencyEnd::point(c + Vector3d(R, -H, 0)));
    EXPECT_NEAR(wrapAngle(g, left.endRadial, right.startRadial), kPi, 1e-15);
    EXPECT_LT((left.end - (c + Vector3d(-R, 0, 0))).norm(), 1e-15);

    // Continuity through full turns: with a previous value near 2 pi + alpha the angle follows.
    const double alpha = wrapAngle(g, left.endRadial, right.startRadial);
    EXPECT_NEAR(wrapAngle(g, left.endRadial, right.startRadial, alpha + 2 * kPi + 0.1), alpha + 2 * kPi, 1e-14);
}

namespace {

struct Configuration {
    TangencyEnd start, end;
};

// End i at parameter x: the centre or point moved by x along its velocity direction, the axis
// turned about a fixed unit vector by x (rates: exact derivatives of these curves).
struct EndPath {
    bool circle = false;
    GrooveCircle g;
    Vector3d v = Vector3d::Zero(), acc = Vector3d::Zero();
    Vector3d spin = Vector3d::Zero();  // angular velocity of the axis (its direction fixed)
    double spinRate = 0;               // d|omega|/dt along the same direction

    TangencyEnd at(double t) const {
        GrooveCircle h = g;
        h.centre = g.centre + v * t + 0.5 * acc * t * t;
        const double angle = spin.norm() * t + 0.5 * spinRate * t * t;
        if (spin.norm() > 0) h.axis = rotation(spin, angle) * g.axis.normalized();
        return circle ? TangencyEnd::circle(h) : TangencyEnd::point(h.centre);
    }
    EndMotion motion() const {
        EndMotion m;
        m.velocity = v;
        m.acceleration = acc;
        const Vector3d n = g.axis.normalized();
        if (circle && spin.norm() > 0) {
            const Vector3d omega = spin;
            const Vector3d omegaDot = spinRate * spin.normalized();
            m.axisRate = omega.cross(n);
            m.axisAcceleration = omegaDot.cross(n) + omega.cross(omega.cross(n));
        }
        return m;
    }
};

// Angle of the radial vector about its axis: the angle rate is (n x e) . edot, so by central
// differences of e and n.
struct Sample {
    Vector3d T1, T2, e1, e2, n1, n2;
};

Sample sample(const EndPath& a, const EndPath& b, double t, const SpanTangency* warm) {
    const TangencyEnd s = a.at(t), e = b.at(t);
    const SpanTangency tg = computeSpanTangency(s, e, warm);
    return {tg.start, tg.end, tg.startRadial, tg.endRadial, s.groove().axis.normalized(), e.groove().axis.normalized()};
}

void checkRatesAgainstDifferences(const EndPath& a, const EndPath& b, const char* label) {
    SCOPED_TRACE(label);
    const TangencyEnd s = a.at(0), e = b.at(0);
    const SpanTangency t0 = computeSpanTangency(s, e);
    TangencyRates r;
    computeTangencyRates(s, e, t0, a.motion(), b.motion(), r);

    // Fourth-order central differences (error O(h^4) + O(eps/h^2) ~ 1e-10 at h = 1e-3).
    const double h = 1e-3;
    Sample f[5];
    for (int k = -2; k <= 2; ++k) f[k + 2] = sample(a, b, k * h, &t0);
    auto d1 = [&](auto get) -> Vector3d {
        const Vector3d a0 = get(f[0]), a1 = get(f[1]), a3 = get(f[3]), a4 = get(f[4]);
        return (a0 - 8 * a1 + 8 * a3 - a4) / (12 * h);
    };
    auto d2 = [&](auto get) -> Vector3d {
        const Vector3d a0 = get(f[0]), a1 = get(f[1]), a2 = get(f[2]), a3 = get(f[3]), a4 = get(f[4]);
        return (-a0 + 16 * a1 - 30 * a2 + 16 * a3 - a4) / (12 * h * h);
    };
    const Vector3d T1d = d1([](const Sample& x) { return x.T1; }), T2d = d1([](const Sample& x) { return x.T2; });
    const Vector3d T1dd = d2([](const Sample& x) { return x.T1; }), T2dd = d2([](const Sample& x) { return x.T2; });
    // Relative to the size of the derivatives (scales of order 1). Measured differences: rates
    // <= 3.0e-12, accelerations <= 7.5e-10 (the difference formulas' own error): bounds 1e-10 and
    // 1e-8 keep margins of 30x and 13x, and stay below the 1e-7 the wrapped-sheave model asks.
    const double scale1 = std::max({T1d.norm(), T2d.norm(), 1.0});
    const double scale2 = std::max({T1dd.norm(), T2dd.norm(), 1.0});
    constexpr double kRateTolerance = 1e-10, kAccelerationTolerance = 1e-8;
    EXPECT_LT((r.startVelocity - T1d).norm(), kRateTolerance * scale1);
    EXPECT_LT((r.endVelocity - T2d).norm(), kRateTolerance * scale1);
    EXPECT_LT((r.startAcceleration - T1dd).norm(), kAccelerationTolerance * scale2);
    EXPECT_LT((r.endAcceleration - T2dd).norm(), kAccelerationTolerance * scale2);
    // Angle rates and accelerations: phidot = w . edot, phiddot = wdot . edot + w . eddot.
    auto angle = [&](bool first) {
        auto e_ = [first](const Sample& x) { return first ? x.e1 : x.e2; };
        auto w_ = [first](const Sample& x) { return Vector3d((first ? x.n1 : x.n2).cross(first ? x.e1 : x.e2)); };
        const Vector3d ed = d1(e_), edd = d2(e_), wd = d1(w_), w = w_(f[2]);
        return std::make_pair(w.dot(ed), wd.dot(ed) + w.dot(edd));
    };
    if (a.circle) {
        const auto [rate, acc] = angle(true);
        EXPECT_NEAR(r.startAngleRate, rate, kRateTolerance * std::max(1.0, std::abs(rate)));
        EXPECT_NEAR(r.startAngleAcceleration, acc, kAccelerationTolerance * std::max(1.0, std::abs(acc)));
    }
    if (b.circle) {
        const auto [rate, acc] = angle(false);
        EXPECT_NEAR(r.endAngleRate, rate, kRateTolerance * std::max(1.0, std::abs(rate)));
        EXPECT_NEAR(r.endAngleAcceleration, acc, kAccelerationTolerance * std::max(1.0, std::abs(acc)));
    }

    // The Jacobian gives the same rates, and J a + bias the same accelerations (the same arithmetic
    // regrouped: measured <= 2.5e-16, bound 1e-14).
    TangencyJacobian J;
    computeTangencyJacobian(s, e, t0, J);
    Eigen::Matrix<double, 12, 1> qd, qdd;
    const EndMotion ma = a.motion(), mb = b.motion();
    qd << ma.velocity, ma.axisRate, mb.velocity, mb.axisRate;
    qdd << ma.acceleration, ma.axisAcceleration, mb.acceleration, mb.axisAcceleration;
    const Eigen::Matrix<double, 8, 1> rateJ = J * qd;
    EXPECT_LT((rateJ.segment<3>(0) - r.startVelocity).norm(), 1e-14 * scale1);
    EXPECT_LT((rateJ.segment<3>(3) - r.endVelocity).norm(), 1e-14 * scale1);
    EXPECT_NEAR(rateJ(6), r.startAngleRate, 1e-14 * std::max(1.0, std::abs(r.startAngleRate)));
    EXPECT_NEAR(rateJ(7), r.endAngleRate, 1e-14 * std::max(1.0, std::abs(r.endAngleRate)));
    EndMotion ba = ma, bb = mb;
    ba.acceleration.setZero();
    ba.axisAcceleration.setZero();
    bb.acceleration.setZero();
    bb.axisAcceleration.setZero();
    TangencyRates bias;
    computeTangencyRates(s, e, t0, ba, bb, bias);
    const Eigen::Matrix<double, 8, 1> accJ = J * qdd;
    EXPECT_LT((accJ.segment<3>(0) + bias.startAcceleration - r.startAcceleration).norm(), 1e-14 * scale2);
    EXPECT_LT((accJ.segment<3>(3) + bias.endAcceleration - r.endAcceleration).norm(), 1e-14 * scale2);
    EXPECT_NEAR(accJ(7) + bias.endAngleAcceleration, r.endAngleAcceleration,
                1e-14 * std::max(1.0, std::abs(r.endAngleAcceleration)));

    // Jacobian columns against central differences of the positions (h = 1e-6; measured <= 2.7e-10,
    // bound 1e-8).
    const double hp = 1e-6;
    for (int col = 0; col < 12; ++col) {
        const int block = col / 3, k = col % 3;
        if ((block == 1 && !a.circle) || (block == 3 && !b.circle)) {
            EXPECT_EQ(J.col(col).norm(), 0.0);
            continue;
        }
        auto perturbed = [&](double x) {
            GrooveCircle ga = a.g, gb = b.g;
            ga.axis.normalize();
            gb.axis.normalize();
            (block == 0 ? ga.centre : block == 1 ? ga.axis : block == 2 ? gb.centre : gb.axis)[k] += x;
            const TangencyEnd ps = a.circle ? TangencyEnd::circle(ga) : TangencyEnd::point(ga.centre);
            const TangencyEnd pe = b.circle ? TangencyEnd::circle(gb) : TangencyEnd::point(gb.centre);
            return computeSpanTangency(ps, pe, &t0);
        };
        // The axis columns act on the unit axis: perturbing it by x along a coordinate moves the
        // normalized axis by x (I - n n^T) to first order, and only that normal part counts.
        const SpanTangency plus = perturbed(hp), minus = perturbed(-hp);
        const Vector3d dT1 = (plus.start - minus.start) / (2 * hp), dT2 = (plus.end - minus.end) / (2 * hp);
        const double jscale = std::max(1.0, J.block<6, 12>(0, 0).cwiseAbs().maxCoeff());
        EXPECT_LT((J.block<3, 1>(0, col) - dT1).norm(), kAccelerationTolerance * jscale) << "column " << col;
        EXPECT_LT((J.block<3, 1>(3, col) - dT2).norm(), kAccelerationTolerance * jscale) << "column " << col;
    }
}

}  // namespace

// First and second time derivatives (and the Jacobian) against central differences, for every
// pairing of ends, in 3D with moving centres and axes turning about tilted directions.
TEST(WrapGeometry, DerivativesMatchCentralDifferences) {
    EndPath point;
    point.g.centre = Vector3d(-3.0, 0.4, 1.2);
    point.v = Vector3d(0.3, -0.2, 0.5);
    point.acc = Vector3d(-1.0, 0.7, 0.2);

    EndPath sheave;
    sheave.circle = true;
    sheave.g = groove(Vector3d(0.5, 0.1, -0.3), Vector3d(0.2, 0.1, 1.0), 0.4, 1);
    sheave.v = Vector3d(-0.4, 0.6, 0.1);
    sheave.acc = Vector3d(0.5, -0.3, 0.9);
    sheave.spin = Vector3d(0.3, -0.8, 0.4);
    sheave.spinRate = 1.5;

    EndPath drum;
    drum.circle = true;
    drum.g = groove(Vector3d(2.5, 3.0, 0.8), Vector3d(1.0, -0.2, 0.3), 0.25, -1);
    drum.v = Vector3d(0.1, 0.2, -0.3);
    drum.acc = Vector3d(0.2, 0.1, -0.4);
    drum.spin = Vector3d(-0.5, 0.2, 0.9);
    drum.spinRate = -0.7;

    checkRatesAgainstDifferences(point, sheave, "point to circle");
    checkRatesAgainstDifferences(sheave, point, "circle to point");
    checkRatesAgainstDifferences(sheave, drum, "circle to circle, crossed-sense spatial");
    EndPath drumOpen = drum;
    drumOpen.g.wrapSense = 1;
    checkRatesAgainstDifferences(sheave, drumOpen, "circle to circle, other tangent");
    checkRatesAgainstDifferences(point, EndPath{[&] {
                                     EndPath q = point;
                                     q.g.centre = Vector3d(1, 2, 3);
                                     q.v = Vector3d(-0.1, 0.3, 0.2);
                                     return q;
                                 }()},
                                 "point to point");
}

// The wrap angle's rate is sigma (phidot_out - phidot_in): checked by central differences on a
// sheave between two moving points.
TEST(WrapGeometry, WrapAngleRateFollowsFromTheAngleRates) {
    EndPath before, after, sheave;
    before.g.centre = Vector3d(-2.0, -5.0, 0.3);
    before.v = Vector3d(0.4, 0.1, -0.2);
    after.g.centre = Vector3d(3.0, -4.0, -0.5);
    after.v = Vector3d(-0.3, 0.5, 0.1);
    sheave.circle = true;
    sheave.g = groove(Vector3d(0.1, 0.2, 0.0), Vector3d(0.1, -0.1, 1.0), 0.3, -1);
    sheave.v = Vector3d(0.2, -0.1, 0.3);
    sheave.spin = Vector3d(0.2, 0.4, -0.1);
    auto alphaAt = [&](double t) {
        const TangencyEnd s = sheave.at(t);
        const SpanTangency in = computeSpanTangency(before.at(t), s);
        const SpanTangency out = computeSpanTangency(s, after.at(t));
        return wrapAngle(s.groove(), in.endRadial, out.startRadial);
    };
    const TangencyEnd s = sheave.at(0);
    const SpanTangency in = computeSpanTangency(before.at(0), s), out = computeSpanTangency(s, after.at(0));
    TangencyRates rin, rout;
    computeTangencyRates(before.at(0), s, in, before.motion(), sheave.motion(), rin);
    computeTangencyRates(s, after.at(0), out, sheave.motion(), after.motion(), rout);
    const double rate = sheave.g.wrapSense * (rout.startAngleRate - rin.endAngleRate);
    const double h = 1e-4;
    const double fd = (alphaAt(-2 * h) - 8 * alphaAt(-h) + 8 * alphaAt(h) - alphaAt(2 * h)) / (12 * h);
    EXPECT_NEAR(rate, fd, 1e-10 * std::max(1.0, std::abs(fd)));  // measured 9.3e-13
    EXPECT_GT(std::abs(rate), 0.01);  // the case moves the wrap angle
}

// Bad input: one clear exception each.
TEST(WrapGeometry, RejectsImpossibleGeometryWithAClearMessage) {
    const GrooveCircle g = groove(Vector3d::Zero(), Vector3d::UnitZ(), 0.5, 1);
    EXPECT_THROW_MESSAGE(computeSpanTangency(TangencyEnd::point(Vector3d(0.2, 0.1, 3.0)), TangencyEnd::circle(g)),
                         std::domain_error, "on or inside the circle");
    GrooveCircle bad = g;
    bad.radius = 0;
    EXPECT_THROW_MESSAGE(validateGrooveCircle(bad), std::invalid_argument, "radius");
    bad = g;
    bad.axis = Vector3d::Zero();
    EXPECT_THROW_MESSAGE(validateGrooveCircle(bad), std::invalid_argument, "axis");
    bad = g;
    bad.wrapSense = 0;
    EXPECT_THROW_MESSAGE(validateGrooveCircle(bad), std::invalid_argument, "wrapSense");
    bad = g;
    bad.centre.x() = std::nan("");
    EXPECT_THROW_MESSAGE(computeSpanTangency(TangencyEnd::circle(bad), TangencyEnd::point(Vector3d(3, 0, 0))),
                         std::invalid_argument, "centre");
    // Crossed tangent between overlapping circles does not exist.
    const GrooveCircle other = groove(Vector3d(0.8, 0, 0), Vector3d::UnitZ(), 0.5, -1);
    EXPECT_THROW_MESSAGE(computeSpanTangency(TangencyEnd::circle(g), TangencyEnd::circle(other)), std::domain_error,
                         "computeSpanTangency");
    EXPECT_THROW_MESSAGE(wrapSenseFromPath(Vector3d(-1, 0, 0), g, Vector3d(1, 0, 0)), std::invalid_argument,
                         "straight");
    EXPECT_THROW_MESSAGE(wrapSenseFromPath(Vector3d(-1, 0, -1), g, Vector3d(1, 0, -1)), std::invalid_argument,
                         "plane containing the groove's axis");
}
