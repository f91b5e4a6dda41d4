// Ropes over wrapped sheaves (NodeWrap): the spans end at the groove's tangent points and the rope
// on the groove arc carries its mass. Checked at the element layer, with the wrap geometry
// (WrapGeometry) mapping a sheave's motion to the rope's external coordinates as a Simbody layer
// does: the Atwood machine's inertia and drive, the rope's length, and the energy of a sheave that
// swings and bounces in a rope loop.
#include "SimbodyReeving/element/GrooveArc.h"
#include "SimbodyReeving/element/RopeModel.h"
#include "SimbodyReeving/element/WrapGeometry.h"

#include "support/ExpectThrowMessage.h"
#include "support/PlanarRopeGeometry.h"

#include <Eigen/Dense>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

using namespace SimbodyReeving;
using Eigen::Vector2d;
using Eigen::Vector3d;

namespace {

using Rope = RopeModel<2>;
constexpr double kG = 9.81;

SpanOptions spanOptions(int axialModes, int transverseModes) {
    SpanOptions o;
    o.axialModes = axialModes;
    o.transverseModes = transverseModes;
    return o;
}

// A rope anchor -> wrapped sheave -> anchor (three nodes; node 1 wrapped and Sliding).
Rope threeNodeRope(const RopeProperties& props, const SpanOptions& o, double L, double R, int sense) {
    const Vector2d g(0.0, -kG);
    std::vector<SpanModel<2>> spans{SpanModel<2>(props, o, g), SpanModel<2>(props, o, g)};
    std::vector<NodeWrap> wraps(3);
    wraps[1].radius = R;
    wraps[1].wrapSense = sense;
    return Rope(std::move(spans), L, {}, wraps);
}

Vector3d lift(const Vector2d& v) { return Vector3d(v[0], v[1], 0.0); }

// The external coordinates of the three-node rope for the sheave at c moving at cdot (anchors
// r0, r2 fixed): x, xdot, the Jacobian J = dx/dc (11 x 2) and the bias b = xddot at cddot = 0.
struct WrapMap {
    Eigen::VectorXd x, xdot, bias;
    Eigen::Matrix<double, Eigen::Dynamic, 2> J;
    double wrapAngle = 0;
};

WrapMap mapSheave(const Rope& rope, const Vector2d& r0, const Vector2d& r2, const Vector2d& c, const Vector2d& cdot,
                  double previousWrapAngle) {
    const double R = rope.arc(1).radius();
    const int sigma = rope.arc(1).wrapSense();
    GrooveCircle groove;
    groove.centre = lift(c);
    groove.radius = R;
    groove.wrapSense = sigma;
    const TangencyEnd a = TangencyEnd::point(lift(r0)), b = TangencyEnd::point(lift(r2)), s = TangencyEnd::circle(groove);
    const SpanTangency in = computeSpanTangency(a, s), out = computeSpanTangency(s, b);
    WrapMap m;
    m.wrapAngle = previousWrapAngle > 0 ? wrapAngle(groove, in.endRadial, out.startRadial, previousWrapAngle)
                                       : wrapAngle(groove, in.endRadial, out.startRadial);
    const int o = rope.nodeCoordinateOffset(1);
    m.x.setZero(rope.numExternalCoordinates());
    m.x.segment<2>(0) = r0;
    m.x.segment<2>(o + Rope::wrappedCentreOffset()) = c;
    m.x.segment<2>(o + Rope::wrappedArrivalOffset()) = in.end.head<2>();
    m.x.segment<2>(o + Rope::wrappedDepartureOffset()) = out.start.head<2>();
    m.x[o + Rope::wrappedArcLengthOffset()] = R * m.wrapAngle;
    m.x.segment<2>(rope.nodeCoordinateOffset(2)) = r2;
    // Columns of J from unit centre velocities; the bias from the actual velocity at zero
    // acceleration (the tangency's second derivatives).
    auto rates = [&](const Vector2d& v, Eigen::VectorXd& first, Eigen::VectorXd& second) {
        EndMotion motion;
        motion.velocity = lift(v);
        TangencyRates ri, ro;
        computeTangencyRates(a, s, in, EndMotion{}, motion, ri);
        computeTangencyRates(s, b, out, motion, EndMotion{}, ro);
        first.setZero(rope.numExternalCoordinates());
        second.setZero(rope.numExternalCoordinates());
        first.segment<2>(o + Rope::wrappedCentreOffset()) = v;
        first.segment<2>(o + Rope::wrappedArrivalOffset()) = ri.endVelocity.head<2>();
        first.segment<2>(o + Rope::wrappedDepartureOffset()) = ro.startVelocity.head<2>();
        first[o + Rope::wrappedArcLengthOffset()] = R * sigma * (ro.startAngleRate - ri.endAngleRate);
        second.segment<2>(o + Rope::wrappedArrivalOffset()) = ri.endAcceleration.head<2>();
        second.segment<2>(o + Rope::wrappedDepartureOffset()) = ro.startAcceleration.head<2>();
        second[o + Rope::wrappedArcLengthOffset()] = R * sigma * (ro.startAngleAcceleration - ri.endAngleAcceleration);
    };
    Eigen::VectorXd unused;
    m.J.resize(rope.numExternalCoordinates(), 2);
    for (int i = 0; i < 2; ++i) {
        Eigen::VectorXd column;
        rates(Vector2d::Unit(i), column, unused);
        m.J.col(i) = column;
    }
    rates(cdot, m.xdot, m.bias);
    return m;
}

// A sheave of mass Ms (translating, frictionless) hanging in a rope loop between two anchors: its
// centre and the rope's modal states, integrated by RK4.
struct HangingSheave {
    Rope rope;
    double sheaveMass;
    Vector2d r0, r2;
    RopeData<2> data;
    double wrapAngle = 0;

    struct State {
        Vector2d c, cdot;
        Eigen::VectorXd qm, qmdot;
    };
    // Accelerations and the total energy at a state.
    void evaluate(const State& y, Vector2d& cddot, Eigen::VectorXd& qmddot, double& energy) {
        const WrapMap m = mapSheave(rope, r0, r2, y.c, y.cdot, wrapAngle);
        rope.computeDynamicsFromExternal(m.x, m.xdot, y.qm, y.qmdot, data);
        const Eigen::MatrixXd& S = data.nodeMass;
        const Vector2d g(0.0, -kG);
        const Eigen::Matrix2d A = sheaveMass * Eigen::Matrix2d::Identity() + m.J.transpose() * S * m.J;
        const Vector2d rhs = sheaveMass * g + m.J.transpose() * (data.nodeForce - S * m.bias);
        cddot = A.ldlt().solve(rhs);
        const Eigen::VectorXd xddot = m.J * cddot + m.bias;
        rope.modalAccelerations(data, xddot, qmddot);
        energy = data.kineticEnergy + data.strainEnergy + data.gravityEnergy + 0.5 * sheaveMass * y.cdot.squaredNorm() -
                 sheaveMass * g.dot(y.c);
    }
    double energyAt(const State& y) {
        Vector2d a;
        Eigen::VectorXd b;
        double e = 0;
        evaluate(y, a, b, e);
        return e;
    }
    void step(State& y, double h) {
        auto deriv = [&](const State& s, State& d) {
            double e = 0;
            d.c = s.cdot;
            d.qm = s.qmdot;
            evaluate(s, d.cdot, d.qmdot, e);
        };
        auto add = [](const State& s, const State& d, double f) {
            return State{s.c + f * d.c, s.cdot + f * d.cdot, s.qm + f * d.qm, s.qmdot + f * d.qmdot};
        };
        State k1, k2, k3, k4;
        deriv(y, k1);
        deriv(add(y, k1, 0.5 * h), k2);
        deriv(add(y, k2, 0.5 * h), k3);
        deriv(add(y, k3, h), k4);
        y.c += h / 6 * (k1.c + 2 * k2.c + 2 * k3.c + k4.c);
        y.cdot += h / 6 * (k1.cdot + 2 * k2.cdot + 2 * k3.cdot + k4.cdot);
        y.qm += h / 6 * (k1.qm + 2 * k2.qm + 2 * k3.qm + k4.qm);
        y.qmdot += h / 6 * (k1.qmdot + 2 * k2.qmdot + 2 * k3.qmdot + k4.qmdot);
        wrapAngle = mapSheave(rope, r0, r2, y.c, y.cdot, wrapAngle).wrapAngle;
    }
};

HangingSheave makeHangingSheave(const SpanOptions& o) {
    // The linear axial law: the sheave's bounce may slacken a tension-only rope, whose kink would
    // limit RK4's order.
    const RopeProperties props{0.5, 2e5, 0.0, false};
    const Vector2d r0(-1.0, 0.0), r2(1.2, 0.0), c0(0.2, -2.0);
    const double R = 0.3;
    const int sigma = wrapSenseFromPath(lift(r0), GrooveCircle{lift(c0), Vector3d::UnitZ(), R, 1}, lift(r2));
    // The rope's length: the geometric path at the start, 0.05 % shorter (pre-stretched).
    GrooveCircle groove{lift(c0), Vector3d::UnitZ(), R, sigma};
    const SpanTangency in = computeSpanTangency(TangencyEnd::point(lift(r0)), TangencyEnd::circle(groove));
    const SpanTangency out = computeSpanTangency(TangencyEnd::circle(groove), TangencyEnd::point(lift(r2)));
    const double alpha = wrapAngle(groove, in.endRadial, out.startRadial);
    const double L = (in.length + R * alpha + out.length) * (1 - 5e-4);
    HangingSheave h{threeNodeRope(props, o, L, R, sigma), 20.0, r0, r2, {}, alpha};
    return h;
}

// Largest |E(t) - E(0)| over 1.5 s of RK4 at step h, relative to the initial kinetic energy.
double energyDrift(const SpanOptions& o, double h) {
    HangingSheave sys = makeHangingSheave(o);
    HangingSheave::State y{Vector2d(0.2, -2.0), Vector2d(0.8, 0.1), Eigen::VectorXd::Zero(sys.rope.numModalCoordinates()),
                           Eigen::VectorXd::Zero(sys.rope.numModalCoordinates())};
    const double e0 = sys.energyAt(y);
    const double kinetic0 = 0.5 * sys.sheaveMass * y.cdot.squaredNorm();
    double worst = 0;
    const int steps = static_cast<int>(std::lround(1.5 / h));
    for (int i = 0; i < steps; ++i) {
        sys.step(y, h);
        worst = std::max(worst, std::abs(sys.energyAt(y) - e0));
    }
    return worst / kinetic0;
}

}  // namespace

// Atwood machine over a fixed frictionless wrapped sheave: moving the masses along the rope (m1
// down, m2 up, the rope sliding over the groove) the rope's effective mass is its whole mass rhoA L
// (the arc's included) and its drive the weight of the longer side's excess rhoA g (x1 - x2), so
//     (m1 + m2 + rhoA L) a = (m1 - m2) g + rhoA g (x1 - x2).
// A stiff rope (strain 1e-6) departs from that inextensible limit by the strain's order: measured
// 7.5e-8 relative in a (bound 5e-6, 67x) and 1.4e-6 in the rope's inertia (bound 5e-5, 36x); the
// wrapped-sheave model asks 1e-4 of the Atwood check.
TEST(RopeWrappedNodes, AtwoodMachineOverAWrappedSheaveHasTheRopesWholeMassInItsInertia) {
    const RopeProperties props{1.5, 1e9, 0.0};
    const double R = 0.25, m1 = 30.0, m2 = 20.0, x1 = 3.0, x2 = 1.2;
    const double Lgeo = x1 + x2 + 3.14159265358979323846 * R;
    for (int na : {0, 2}) {
        const Rope rope = threeNodeRope(props, spanOptions(na, 0), Lgeo * (1 - 1e-6), R, -1);
        const Vector2d c(0.0, 0.0), r0(-R, -x1), r2(R, -x2);
        const WrapMap m = mapSheave(rope, r0, r2, c, Vector2d::Zero(), 0.0);
        EXPECT_NEAR(m.x[rope.nodeCoordinateOffset(1) + Rope::wrappedArcLengthOffset()], 3.14159265358979323846 * R, 1e-15);
        RopeData<2> data;
        const Eigen::VectorXd none;
        rope.computeDynamicsFromExternal(m.x, m.xdot, none, none, data);
        // The masses' vertical motion along the rope: node 0 down, node 2 up.
        Eigen::VectorXd u = Eigen::VectorXd::Zero(rope.numExternalCoordinates());
        u[1] = -1.0;
        u[rope.nodeCoordinateOffset(2) + 1] = 1.0;
        const double ropeInertia = u.dot(data.nodeMass * u), ropeDrive = u.dot(data.nodeForce);
        const double a = ((m1 - m2) * kG + ropeDrive) / (m1 + m2 + ropeInertia);
        const double expected = ((m1 - m2) * kG + props.massPerLength * kG * (x1 - x2)) /
                                (m1 + m2 + props.massPerLength * Lgeo);
        EXPECT_NEAR(a, expected, 5e-6 * expected) << "n_a = " << na;
        EXPECT_NEAR(ropeInertia, props.massPerLength * Lgeo, 5e-5 * props.massPerLength * Lgeo) << "n_a = " << na;
        // Without the arc's mass the inertia would miss rhoA pi R: 0.16 of rhoA L here.
    }
}

// Rope length from the geometry, not from the model's material bookkeeping (whose sum of span
// ranges and arc length equals L by construction): the tangent points in closed form from the
// anchors and the sheave's centre (support/PlanarRopeGeometry.h), the arc R alpha from their angle,
// each span's material as its sampled length (401 points) over the stretch sqrt(1 + 2 eps). Over
// a swing that changes the wrap angle by 0.05 rad or more:
//  - the model's arc length l equals R alpha of the closed-form tangent points: measured 4.4e-16 m;
//    bound 1e-14 m;
//  - spans + R alpha = L: measured 3.3e-9 m of 5.25 m, the sampled spans' discretisation (8.0e-10 m
//    with 801 points: second order); bound 1e-7 m.
TEST(RopeWrappedNodes, RopeLengthFromTheGeometryIsConserved) {
    namespace t = SimbodyReevingTest;
    HangingSheave sys = makeHangingSheave(spanOptions(0, 1));
    HangingSheave::State y{Vector2d(0.2, -2.0), Vector2d(2.0, 0.1), Eigen::VectorXd::Zero(sys.rope.numModalCoordinates()),
                           Eigen::VectorXd::Zero(sys.rope.numModalCoordinates())};
    const double R = sys.rope.arc(1).radius();
    double alphaMin = 10, alphaMax = 0, worstArc = 0, worstLength = 0;
    auto spanMaterial = [&](int j) {
        const Eigen::VectorXd& q = sys.data.spanCoordinates(j);
        const auto& span = sys.rope.span(j);
        const double s1 = q[span.s1Index()], s2 = q[span.s2Index()];
        const int n = 401;
        std::vector<Vector2d> points(n);
        std::vector<double> strains(n);
        for (int i = 0; i < n; ++i) {
            const double s = s1 + (s2 - s1) * i / (n - 1);
            points[i] = span.position(q, s);
            strains[i] = span.strain(q, s);
        }
        return t::materialLengthFromGeometry(points, strains);
    };
    for (int i = 0; i < 300; ++i) {
        sys.step(y, 2e-3);
        sys.energyAt(y);  // the rope's data at y
        // The path turns at the sheave the way the rope wraps it.
        const Vector2d in = y.c - sys.r0, out = sys.r2 - y.c;
        const int sense = in.x() * out.y() - in.y() * out.x() > 0 ? 1 : -1;
        const t::PlanarGroove start{sys.r0, 0.0, 1}, groove{y.c, R, sense}, end{sys.r2, 0.0, 1};
        const Vector2d arrival = t::spanTangentPoints(start, groove).second;
        const Vector2d departure = t::spanTangentPoints(groove, end).first;
        const double alpha = t::grooveWrapAngle(groove, arrival, departure);
        const double l = sys.rope.arc(1).radius() * sys.wrapAngle;
        worstArc = std::max(worstArc, std::abs(l - R * alpha));
        worstLength = std::max(worstLength, std::abs(spanMaterial(0) + R * alpha + spanMaterial(1) -
                                                     sys.rope.unstretchedLength()));
        alphaMin = std::min(alphaMin, alpha);
        alphaMax = std::max(alphaMax, alpha);
    }
    std::printf("wrapped node: arc vs R alpha of the tangent points %.1e m, length from the geometry %.1e m of %.3f m\n",
                worstArc, worstLength, sys.rope.unstretchedLength());
    EXPECT_LE(worstArc, 1e-14);
    EXPECT_LE(worstLength, 1e-7);
    EXPECT_GT(alphaMax - alphaMin, 0.05);  // the wrap angle did change
}

// A sheave hanging in a rope loop, swinging and bouncing (wrap angle, tangent points and arc
// length changing, the arc's material sliding and moving with the sheave): T + U of the sheave and
// the rope (spans and arc) is conserved up to the integrator's error, which falls by RK4's 16x when
// the step halves. Measured drift over 1.5 s relative to the initial kinetic energy: 1.9e-6 at
// h = 2e-3 s, 6.0e-8 at h = 1e-3 s (ratio 32, n_a = 0 and 2); bound 2e-6 at the fine step (33x)
// and a ratio above 8. Dropping the arc's quadratic-velocity forces leaves a drift of 4e-5 that
// does not fall with h; dropping the arc length's share of the tension-equality Jacobian, 2e-3.
TEST(RopeWrappedNodes, SwingingSheaveConservesEnergy) {
    for (int na : {0, 2}) {
        const SpanOptions o = spanOptions(na, 1);
        const double coarse = energyDrift(o, 2e-3), fine = energyDrift(o, 1e-3);
        EXPECT_LT(fine, 2e-6) << "n_a = " << na;
        EXPECT_GT(coarse / fine, 8.0) << "n_a = " << na;
    }
}

TEST(RopeWrappedNodes, RejectsBadWraps) {
    const RopeProperties props{1.0, 1e6, 0.0};
    const Vector2d g(0.0, -kG);
    auto spans = [&] {
        return std::vector<SpanModel<2>>{SpanModel<2>(props, SpanOptions{}, g), SpanModel<2>(props, SpanOptions{}, g)};
    };
    std::vector<NodeWrap> wraps(3);
    wraps[0].radius = 0.2;
    EXPECT_THROW_MESSAGE(Rope(spans(), 5.0, {}, wraps), std::invalid_argument, "end node 0 can be wrapped only as a Driven node");
    wraps[0].radius = 0;
    wraps[1].radius = -0.1;
    EXPECT_THROW_MESSAGE(Rope(spans(), 5.0, {}, wraps), std::invalid_argument,
                         "node 1's wrap radius R = -0.1 m must be finite and >= 0");
    wraps[1].radius = 0.1;
    wraps[1].wrapSense = 2;
    EXPECT_THROW_MESSAGE(Rope(spans(), 5.0, {}, wraps), std::invalid_argument, "node 1's wrapSense = 2 must be +1 or -1");
    EXPECT_THROW_MESSAGE(Rope(spans(), 5.0, {}, std::vector<NodeWrap>(2)), std::invalid_argument,
                         "2 node wraps given for 3 nodes");
    wraps[1].wrapSense = 1;
    const Rope rope(spans(), 5.0, {}, wraps);
    EXPECT_EQ(rope.numExternalCoordinates(), 2 + Rope::wrappedBlockSize() + 2);
    RopeData<2> data;
    Eigen::Matrix<double, 2, Eigen::Dynamic> nodes(2, 3);
    nodes << 0, 1, 2, 0, -1, 0;
    const Eigen::VectorXd qm = Eigen::VectorXd::Zero(rope.numModalCoordinates());
    // A rope with wrapped nodes takes its stations (WrapStationMap), planar or spatial: in the
    // plane z = 0 with the groove's axis +z, the spatial rope's material coordinates are the
    // planar one's (measured to round-off; bound 1e-12 m).
    rope.solveDependentCoordinates(nodes, qm, data);
    EXPECT_GT(data.materialCoordinates[1], 0.0);
    const Eigen::Vector3d g3(0.0, -kG, 0.0);
    auto spans3 = [&]() {
        return std::vector<SpanModel<3>>{SpanModel<3>(props, SpanOptions{}, g3), SpanModel<3>(props, SpanOptions{}, g3)};
    };
    const RopeModel<3> rope3(spans3(), 5.0, {}, wraps);
    RopeData<3> data3;
    Eigen::Matrix<double, 3, Eigen::Dynamic> nodes3 = Eigen::Matrix<double, 3, Eigen::Dynamic>::Zero(3, 3);
    nodes3.topRows<2>() = nodes;
    rope3.solveDependentCoordinates(nodes3, Eigen::VectorXd::Zero(rope3.numModalCoordinates()), data3);
    EXPECT_NEAR(data3.materialCoordinates[1], data.materialCoordinates[1], 1e-12);
    // A spatial groove's axis must be a finite unit vector.
    std::vector<NodeWrap> badAxis = wraps;
    badAxis[1].axis = Eigen::Vector3d(0.0, 0.0, 0.0);
    EXPECT_THROW_MESSAGE(RopeModel<3>(spans3(), 5.0, {}, badAxis), std::invalid_argument,
                         "node 1's groove axis (0 0 0) must be a finite unit vector");
    badAxis[1].axis = Eigen::Vector3d(0.0, 0.0, 2.0);
    EXPECT_THROW_MESSAGE(RopeModel<3>(spans3(), 5.0, {}, badAxis), std::invalid_argument,
                         "must be a finite unit vector (|n| = 2)");
    EXPECT_THROW_MESSAGE(rope.solveDependentCoordinatesFromExternal(Eigen::VectorXd::Zero(3), qm, data),
                         std::invalid_argument, "3 external coordinates given for 11");
    EXPECT_THROW_MESSAGE(rope.arc(0), std::invalid_argument, "node 0 is not a wrapped node");
}
