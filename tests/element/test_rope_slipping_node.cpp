// RopeModel with a MaterialNode::Slipping node (a traction sheave in slip): at kappa = 1 it is a
// Sliding node plus an unloaded sheave coordinate; at kappa != 1 the axial forces at the node keep
// the capstan ratio P_{k-1} = kappa P_k, and the friction's reaction P_{k-1} - P_k is the rope's force
// on the sheave coordinate. Both axial models. With a wrapped node and the law kappa(l) = e^(c l)
// (setSlipLaw: Euler-Eytelwein with the geometry's wrap angle) the ratio follows the arc, and the
// material rate carries the law's derivative in l.
#include "SimbodyReeving/element/RopeModel.h"
#include "SimbodyReeving/element/WrapStationMap.h"
#include "support/ExpectThrowMessage.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <stdexcept>

using namespace SimbodyReeving;

namespace {

const RopeProperties kRope{0.6205, 16.5e6, 0.0};
const Eigen::Vector2d kGravity(0, -9.81);

std::vector<SpanModel<2>> makeSpans(int na, int nt, AxialDynamics axial) {
    SpanOptions o;
    o.axialModes = na;
    o.transverseModes = nt;
    o.axialDynamics = axial;
    return std::vector<SpanModel<2>>(2, SpanModel<2>(kRope, o, kGravity));
}

// Start anchor, sheave, end anchor: two hanging falls of different length (an Atwood machine held
// at its anchors, so both falls are taut with different tensions).
Eigen::Matrix2Xd atwoodNodes() {
    Eigen::Matrix2Xd n(2, 3);
    n << -0.3, 0.0, 0.3, -8.0, 0.0, -12.0;
    return n;
}

double endForce(const RopeModel<2>& rope, const RopeData<2>& d, int span, SpanEnd end) {
    EndStrain<2> e;
    const Eigen::VectorXd& q = d.spanCoordinates(span);
    rope.span(span).endStrain(q, Eigen::VectorXd::Zero(q.size()), end, e);
    return rope.properties().axialStiffness * e.strain;
}

}  // namespace

TEST(RopeSlippingNode, UnitRatioIsASlidingNodeWithAnUnloadedSheaveCoordinate) {
    for (AxialDynamics axial : {AxialDynamics::Dynamic, AxialDynamics::QuasiStatic}) {
        const double L = 19.99;
        const RopeModel<2> sliding(makeSpans(3, 1, axial), L);
        const RopeModel<2> slipping(makeSpans(3, 1, axial), L,
                                    {MaterialNode::Fixed, MaterialNode::Slipping, MaterialNode::Fixed});
        ASSERT_EQ(slipping.numDrivenNodes(), 1);
        ASSERT_EQ(slipping.numExternalCoordinates(), 7);
        const int nm = sliding.numModalCoordinates();
        ASSERT_EQ(nm, slipping.numModalCoordinates());
        Eigen::VectorXd qm(nm), qmd(nm);
        for (int i = 0; i < nm; ++i) {
            qm[i] = 1e-4 * std::sin(1.0 + i);
            qmd[i] = 1e-3 * std::cos(2.0 + i);
        }
        Eigen::Matrix2Xd vel = Eigen::Matrix2Xd::Zero(2, 3);
        vel.col(2) << 0.4, -0.2;
        RopeData<2> a, b;
        sliding.computeDynamics(atwoodNodes(), vel, qm, qmd, a);
        const Eigen::VectorXd sheave = Eigen::VectorXd::Constant(1, 7.0), sheaveRate = Eigen::VectorXd::Constant(1, 0.5);
        slipping.computeDynamics(atwoodNodes(), vel, sheave, sheaveRate, qm, qmd, b);
        // Dynamic axial modes: the same equations, to round-off. QuasiStatic: a Sliding node's condensed
        // amplitudes solve the constrained stationarity (the tension-equality multiplier nu_k in
        // their rows), a Slipping node's the unconstrained one (nu_k = 0, so that stick and slip
        // share it: continuous transitions; RopeModel::evaluateConstraints), so they agree to the
        // modal truncation. Measured for QuasiStatic: s 3.0e-7 m, node mass 1.0e-6 (2.2e-7 of its
        // largest entry), node force 3.1e-7 N (1.0e-11 of its largest), sheave reaction 7.3e-9 N
        // (2.3e-13), kinetic energy 2.1e-8 relative; bounds 10x those.
        const bool exact = axial == AxialDynamics::Dynamic;
        const double scale = a.nodeMass.cwiseAbs().maxCoeff();
        EXPECT_LE((a.materialCoordinates - b.materialCoordinates).cwiseAbs().maxCoeff(), exact ? 1e-13 : 3e-6);
        EXPECT_LE((a.nodeMass - b.nodeMass.topLeftCorner(6, 6)).cwiseAbs().maxCoeff(), (exact ? 1e-12 : 2.2e-6) * scale);
        EXPECT_EQ(b.nodeMass.row(6).cwiseAbs().maxCoeff(), 0.0);
        EXPECT_EQ(b.nodeMass.col(6).cwiseAbs().maxCoeff(), 0.0);
        const double forceScale = a.nodeForce.cwiseAbs().maxCoeff();
        EXPECT_LE((a.nodeForce - b.nodeForce.head(6)).cwiseAbs().maxCoeff(), (exact ? 1e-12 : 1e-10) * forceScale);
        // The reaction on the sheave coordinate is P_0 - P_1, the tension-equality residual (a few
        // Newton tolerances; its tolerance 1e-14 in strain is 1.7e-7 N here).
        EXPECT_LE(std::abs(b.nodeForce[6]), (exact ? 1e-13 : 2.3e-12) * forceScale);
        EXPECT_NEAR(a.kineticEnergy, b.kineticEnergy, (exact ? 1e-12 : 2e-7) * a.kineticEnergy);
    }
}

TEST(RopeSlippingNode, ForcesKeepTheCapstanRatioAndTheSheaveCarriesTheirDifference) {
    for (AxialDynamics axial : {AxialDynamics::Dynamic, AxialDynamics::QuasiStatic}) {
        for (double kappa : {std::exp(0.3 * std::acos(-1.0)), std::exp(-0.3 * std::acos(-1.0))}) {
            RopeModel<2> rope(makeSpans(3, 1, axial), 19.99,
                              {MaterialNode::Fixed, MaterialNode::Slipping, MaterialNode::Fixed});
            rope.setSlipRatio(1, kappa);
            const int nm = rope.numModalCoordinates();
            const Eigen::VectorXd qm = Eigen::VectorXd::Zero(nm);
            RopeData<2> d;
            const Eigen::VectorXd sheave = Eigen::VectorXd::Constant(1, 7.0), zero1 = Eigen::VectorXd::Zero(1);
            rope.computeDynamics(atwoodNodes(), Eigen::Matrix2Xd::Zero(2, 3), sheave, zero1, qm, qm, d);
            const double pa = endForce(rope, d, 0, SpanEnd::Second), pb = endForce(rope, d, 1, SpanEnd::First);
            ASSERT_GT(pb, 1e3);
            // The Newton's tolerance 1e-14 in strain: 1.7e-7 N of forces of ~1e5 N.
            EXPECT_NEAR(pa / pb, kappa, 1e-11) << "axial " << static_cast<int>(axial);
            EXPECT_NEAR(rope.constraintError(d, 1), pa - pb, 1e-9 * pb);
            // At rest the rope's generalized force on the sheave coordinate is the friction's reaction.
            EXPECT_NEAR(d.nodeForce[6], pa - pb, 1e-9 * pb);
        }
    }
}

namespace {

// x(t) from stations moving as Y + Ydot t (WrapStationMap), and the material coordinate s_1 solved
// there.
struct WrappedSlip {
    RopeModel<2> rope;
    WrapStationMap<2> map;
    explicit WrappedSlip(AxialDynamics axial, double R)
        : rope(makeSpans(3, 1, axial), 19.99, {MaterialNode::Fixed, MaterialNode::Slipping, MaterialNode::Fixed},
               {NodeWrap{}, NodeWrap{R, -1}, NodeWrap{}}),
          map(rope) {}
    double solve(const Eigen::VectorXd& Y, const Eigen::VectorXd& Yd, double t, RopeData<2>& d,
                 WrapStationMapData& m) const {
        map.evaluate(Y + t * Yd, Yd, m);
        const Eigen::VectorXd qm = Eigen::VectorXd::Zero(rope.numModalCoordinates());
        rope.computeDynamicsFromExternal(m.x, m.xdot, qm, qm, d);
        return d.materialCoordinates[1];
    }
};

}  // namespace

// A rope slipping over a wrapped sheave (R = 0.4 m, both falls hanging from it, held at their
// anchors) with kappa(l) = e^(mu l / R), mu = 0.3: P_0 / P_1 = e^(mu alpha), alpha = l / R the wrap
// angle of the current geometry (the anchors moving changes it), to the Newton's tolerance
// (measured 1.3e-15 Dynamic, 1.3e-14 QuasiStatic, relative; bound 1e-11 as the constant law's).
// The material rate the model finds (its Jacobian, with the law's column at l) against 4th-order
// central differences of the solved s_1 along the stations' path (0.44 m/s): measured 3.7e-13 and
// 8.8e-14 m/s; bound 1e-7 m/s. Without the column at l the rate is off by 3.6e-3 m/s.
TEST(RopeSlippingNode, GeometricWrapAngleSetsTheRatioAndItsRate) {
    const double R = 0.4, mu = 0.3;
    for (AxialDynamics axial : {AxialDynamics::Dynamic, AxialDynamics::QuasiStatic}) {
        WrappedSlip w(axial, R);
        w.rope.setSlipLaw(1, 1.0, mu);
        EXPECT_EQ(w.rope.slipAngleExponent(1), mu);
        Eigen::VectorXd Y(7), Yd(7);
        Y << -R - 0.3, -8.0, 0.0, 0.0, R + 1.5, -11.0, 7.0;
        Yd << 0.6, -0.3, 0.0, 0.0, -0.8, 0.5, 0.2;
        RopeData<2> d;
        WrapStationMapData m;
        w.solve(Y, Yd, 0.0, d, m);
        const double l = m.x[w.rope.nodeCoordinateOffset(1) + RopeModel<2>::wrappedArcLengthOffset()];
        // The anchors stand outside the tangent points: the falls lean out, less than half a turn.
        EXPECT_GT(l / R, 2.5);
        EXPECT_LT(l / R, std::acos(-1.0));
        const double pa = endForce(w.rope, d, 0, SpanEnd::Second), pb = endForce(w.rope, d, 1, SpanEnd::First);
        ASSERT_GT(pb, 1e3);
        EXPECT_NEAR(pa / pb, std::exp(mu * l / R), 1e-11 * std::exp(mu * l / R)) << static_cast<int>(axial);
        const double h = 1e-3;
        RopeData<2> e;
        WrapStationMapData n;
        const double s2m = w.solve(Y, Yd, -2 * h, e, n), s1m = w.solve(Y, Yd, -h, e, n);
        const double s1p = w.solve(Y, Yd, h, e, n), s2p = w.solve(Y, Yd, 2 * h, e, n);
        const double rate = (s2m - 8 * s1m + 8 * s1p - s2p) / (12 * h);
        w.solve(Y, Yd, 0.0, d, m);
        EXPECT_NEAR(d.materialRates[1], rate, 1e-7) << static_cast<int>(axial);
    }
}

// The same law at a point node (the paper's sheave): alpha the turning angle between the two
// chords, pi - angle(r_0 - r_1, r_2 - r_1) (closed form, bound 1e-14 rad: round-off of acos).
// P_0 / P_1 = e^(mu alpha) to the Newton's tolerance (measured 3.6e-14 Dynamic, 4.2e-13
// QuasiStatic, relative; bound 1e-11 as above), and the material rate with the law's columns at
// the three positions against 4th-order central differences along the nodes' path (measured
// 1.6e-12 and 1.7e-12 m/s, the differences' own error; bound 1e-10 m/s; without the columns the
// rate is off by 1.9e-4 m/s).
TEST(RopeSlippingNode, ChordAngleOfAPointNodeSetsTheRatioAndItsRate) {
    const double mu = 0.3;
    for (AxialDynamics axial : {AxialDynamics::Dynamic, AxialDynamics::QuasiStatic}) {
        RopeModel<2> rope(makeSpans(3, 1, axial), 19.99, {MaterialNode::Fixed, MaterialNode::Slipping, MaterialNode::Fixed});
        rope.setSlipLaw(1, 1.0, mu);
        EXPECT_EQ(rope.slipAngleExponent(1), mu);
        Eigen::Matrix2Xd n0 = atwoodNodes(), nd(2, 3);
        nd << 0.6, 0.1, -0.8, -0.3, 0.05, 0.5;
        const Eigen::VectorXd drivenS = Eigen::VectorXd::Constant(1, 7.0), drivenSd = Eigen::VectorXd::Constant(1, 0.2);
        const Eigen::VectorXd qm = Eigen::VectorXd::Zero(rope.numModalCoordinates());
        auto solve = [&](double t, RopeData<2>& d) {
            const Eigen::Matrix2Xd n = n0 + t * nd;
            rope.computeDynamics(n, nd, drivenS, drivenSd, qm, qm, d);
            return d.materialCoordinates[1];
        };
        RopeData<2> d;
        solve(0.0, d);
        const Eigen::Vector2d a = n0.col(0) - n0.col(1), b = n0.col(2) - n0.col(1);
        const double alpha = std::acos(-1.0) - std::acos(a.dot(b) / (a.norm() * b.norm()));
        EXPECT_NEAR(rope.wrapAngle(d, 1), alpha, 1e-14);
        const double pa = endForce(rope, d, 0, SpanEnd::Second), pb = endForce(rope, d, 1, SpanEnd::First);
        ASSERT_GT(pb, 1e3);
        EXPECT_NEAR(pa / pb, std::exp(mu * alpha), 1e-11 * std::exp(mu * alpha)) << static_cast<int>(axial);
        const double h = 1e-3;
        RopeData<2> e;
        const double s2m = solve(-2 * h, e), s1m = solve(-h, e), s1p = solve(h, e), s2p = solve(2 * h, e);
        const double rate = (s2m - 8 * s1m + 8 * s1p - s2p) / (12 * h);
        solve(0.0, d);
        EXPECT_NEAR(d.materialRates[1], rate, 1e-10) << static_cast<int>(axial);
    }
}

// The chord angle at a point node of a spatial rope: alpha = pi - angle(r_0 - r_1, r_2 - r_1) of
// the 3D chords (here 0.25 m out of the plane of the first chord and gravity), in the plane the
// two chords span. The stations move in all three directions, so that plane turns. Measured:
// alpha against acos 8.9e-16 rad (bound 1e-14: round-off of acos); P_0 / P_1 against
// e^(mu alpha) 2.0e-13 Dynamic and 4.8e-14 QuasiStatic relative (bound 1e-11); the material rate,
// with the law's columns at the three positions, against 4th-order central differences along the
// path 6.7e-14 and 4.7e-13 m/s (bound 1e-11 m/s).
TEST(RopeSlippingNode, ChordAngleOfAPointNodeOfASpatialRopeSetsTheRatioAndItsRate) {
    const double mu = 0.3;
    for (AxialDynamics axial : {AxialDynamics::Dynamic, AxialDynamics::QuasiStatic}) {
        SpanOptions o;
        o.axialModes = 3;
        o.transverseModes = 1;
        o.axialDynamics = axial;
        RopeModel<3> rope(std::vector<SpanModel<3>>(2, SpanModel<3>(kRope, o, Eigen::Vector3d(0, -9.81, 0))), 19.99,
                          {MaterialNode::Fixed, MaterialNode::Slipping, MaterialNode::Fixed});
        rope.setSlipLaw(1, 1.0, mu);
        Eigen::Matrix3Xd n0(3, 3), nd(3, 3);
        n0 << -0.3, 0.0, 0.3, -8.0, 0.0, -12.0, 0.0, 0.0, 0.25;
        nd << 0.6, 0.1, -0.8, -0.3, 0.05, 0.5, 0.2, -0.1, 0.4;
        const Eigen::VectorXd drivenS = Eigen::VectorXd::Constant(1, 7.0), drivenSd = Eigen::VectorXd::Constant(1, 0.2);
        const Eigen::VectorXd qm = Eigen::VectorXd::Zero(rope.numModalCoordinates());
        auto solve = [&](double t, RopeData<3>& d) {
            const Eigen::Matrix3Xd n = n0 + t * nd;
            rope.computeDynamics(n, nd, drivenS, drivenSd, qm, qm, d);
            return d.materialCoordinates[1];
        };
        RopeData<3> d;
        solve(0.0, d);
        const Eigen::Vector3d a = n0.col(0) - n0.col(1), b = n0.col(2) - n0.col(1);
        const double alpha = std::acos(-1.0) - std::acos(a.dot(b) / (a.norm() * b.norm()));
        EXPECT_NEAR(rope.wrapAngle(d, 1), alpha, 1e-14);
        EndStrain<3> e;
        rope.span(0).endStrain(d.spanCoordinates(0), Eigen::VectorXd::Zero(d.spanCoordinates(0).size()), SpanEnd::Second, e);
        const double pa = kRope.axialStiffness * e.strain;
        rope.span(1).endStrain(d.spanCoordinates(1), Eigen::VectorXd::Zero(d.spanCoordinates(1).size()), SpanEnd::First, e);
        const double pb = kRope.axialStiffness * e.strain;
        ASSERT_GT(pb, 1e3);
        EXPECT_NEAR(pa / pb, std::exp(mu * alpha), 1e-11 * std::exp(mu * alpha)) << static_cast<int>(axial);
        const double h = 1e-3;
        RopeData<3> f;
        const double s2m = solve(-2 * h, f), s1m = solve(-h, f), s1p = solve(h, f), s2p = solve(2 * h, f);
        const double rate = (s2m - 8 * s1m + 8 * s1p - s2p) / (12 * h);
        solve(0.0, d);
        EXPECT_NEAR(d.materialRates[1], rate, 1e-11) << static_cast<int>(axial);
        std::printf("spatial chord angle (axial %d): alpha off %.2e rad, ratio off %.2e, rate off %.2e m/s\n",
                    static_cast<int>(axial), std::abs(rope.wrapAngle(d, 1) - alpha),
                    std::abs(pa / pb / std::exp(mu * alpha) - 1), std::abs(d.materialRates[1] - rate));
    }
}

TEST(RopeSlippingNode, BadUseIsAnInvalidArgument) {
    RopeModel<2> rope(makeSpans(1, 0, AxialDynamics::Dynamic), 19.99,
                      {MaterialNode::Fixed, MaterialNode::Slipping, MaterialNode::Fixed});
    EXPECT_THROW_MESSAGE(rope.setSlipRatio(0, 2.0), std::invalid_argument,
                         "RopeModel::setSlipRatio: node 0 is not a Slipping node");
    EXPECT_THROW_MESSAGE(rope.setSlipRatio(1, 0.0), std::invalid_argument,
                         "RopeModel::setSlipRatio: kappa = 0 must be finite and > 0");
    EXPECT_THROW_MESSAGE(rope.setSlipRatio(1, std::nan("")), std::invalid_argument,
                         "RopeModel::setSlipRatio: kappa = nan must be finite and > 0");
    EXPECT_NO_THROW(rope.setSlipRatio(1, 2.0));
    EXPECT_THROW_MESSAGE(rope.setSlipLaw(1, 1.0, std::nan("")), std::invalid_argument,
                         "RopeModel::setSlipLaw: angleExponent = nan 1/rad must be finite");
    EXPECT_THROW_MESSAGE(rope.setSlipLaw(0, 1.0, 0.5), std::invalid_argument,
                         "RopeModel::setSlipRatio: node 0 is not a Slipping node");
    RopeData<2> none;
    EXPECT_THROW_MESSAGE(rope.wrapAngle(none, 1), std::invalid_argument,
                         "RopeModel::wrapAngle: data holds no evaluation from node positions");
    EXPECT_THROW_MESSAGE(rope.wrapAngle(none, 0), std::invalid_argument,
                         "RopeModel::wrapAngle: node 0 is not an interior node");
    EXPECT_THROW_MESSAGE(RopeModel<2>(makeSpans(1, 0, AxialDynamics::Dynamic), 19.99,
                                      {MaterialNode::Slipping, MaterialNode::Sliding, MaterialNode::Fixed}),
                         std::invalid_argument, "RopeModel: end node 0 cannot be Slipping (a sheave needs a span on both sides)");
}
