// RopeModel::setGrip: a wrapped drum that grips the rope where it leaves the groove. The material
// there moves with the groove's surface (sdot = v / lambda), the rope creeps against the
// unstretched groove at v (1 / lambda - 1), the wound rope keeps its strain energy EA eps^2 / 2 per
// metre, and so the drum holds the rope with its true (Cauchy) force N = EA eps lambda. Every
// reference is computed here from the geometry: a drum of radius R at the origin, the rope leaving
// its right-hand side straight down to an anchor 10 m below the tangent point, no gravity, one
// span without modes (a uniform strain: lambda = 10 m / (L - s_0)).
#include "SimbodyReeving/element/RopeModel.h"
#include "support/ExpectThrowMessage.h"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

using namespace SimbodyReeving;

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kR = 0.5;      // [m]
constexpr double kEA = 1e6;     // [N]
constexpr double kL = 20.0;     // [m]
constexpr double kFall = 10.0;  // tangent point to anchor [m]

NodeWrap drumWrap() {
    NodeWrap w;
    w.radius = kR;
    w.wrapSense = -1;  // clockwise: the rope leaves the right-hand side going down
    return w;
}

RopeModel<2> drumRope(bool grip, const Eigen::Vector2d& gravity = Eigen::Vector2d::Zero()) {
    SpanOptions o;
    o.axialModes = 0;
    o.transverseModes = 0;
    std::vector<SpanModel<2>> spans{SpanModel<2>(RopeProperties{1.0, kEA, 0.0}, o, gravity)};
    RopeModel<2> rope(std::move(spans), kL, {MaterialNode::Driven, MaterialNode::Fixed}, {drumWrap(), NodeWrap{}});
    rope.setStoredRope(0, 30.0);
    if (grip) rope.setGrip(0);
    return rope;
}

Eigen::Matrix2Xd drumNodes() {
    Eigen::Matrix2Xd n(2, 2);
    n << 0.0, kR, 0.0, -kFall;
    return n;
}

// The drum's surface coordinate Y_s that leaves 10 m / 1.1 of unstretched rope in the fall
// (eps = 0.105): s_0 = Y_s + sigma R phi with phi = -pi/2 (the tangent point's angle from up,
// +y without gravity), sigma = -1.
double surfaceCoordinate() { return kL - kFall / 1.1 - kR * kPi / 2; }

struct Expected {
    double lambda, eps;
};
Expected fromGeometry(double s0) {
    const double lambda = kFall / (kL - s0);
    return {lambda, 0.5 * (lambda * lambda - 1.0)};
}

}  // namespace

// At rest the drum's generalized force (on its surface coordinate Y_s) is the rope's true force
// at the tangent point, N = EA eps lambda, with the grip; without it, EA (eps lambda^2 - eps^2 / 2)
// (the groove carrying R of unstretched rope per radian and the wound rope no strain energy), 8 %
// more here. The anchor's force is N either way. Measured agreement 1e-16 relative; bound 1e-12.
TEST(RopeGrip, DrumHoldsTheRopeWithItsTrueForce) {
    const Eigen::VectorXd Ys = Eigen::VectorXd::Constant(1, surfaceCoordinate()), zero1 = Eigen::VectorXd::Zero(1);
    const Eigen::VectorXd none;
    for (bool grip : {true, false}) {
        const RopeModel<2> rope = drumRope(grip);
        RopeData<2> d;
        rope.computeDynamics(drumNodes(), Eigen::Matrix2Xd::Zero(2, 2), Ys, zero1, none, none, d);
        const Expected e = fromGeometry(d.materialCoordinates[0]);
        ASSERT_NEAR(e.eps, 0.105, 1e-12);  // the tangent point where the test put it
        const double N = kEA * e.eps * e.lambda;
        const double drum = d.nodeForce[d.nodeForce.size() - 1];  // the last station coordinate: Y_s
        const double anchorY = d.nodeForce[3];
        std::printf("%s: drum %.9f N, anchor %.9f N, N = EA eps lambda %.9f N\n", grip ? "grip" : "no grip", drum,
                    anchorY, N);
        EXPECT_NEAR(anchorY, N, 1e-12 * N);
        if (grip)
            EXPECT_NEAR(drum, -N, 1e-12 * N);
        else
            EXPECT_NEAR(drum, -kEA * (e.eps * e.lambda * e.lambda - 0.5 * e.eps * e.eps), 1e-12 * N);
    }
}

// The drum paying out at v = 0.3 m/s, the anchor still: the rope's material leaves the groove at
// sdot_0 = v / lambda, creeps against the unstretched groove at cdot = v (1 / lambda - 1) and the
// wound rope's strain energy changes at dU_w/dt = EA eps^2 / 2 sdot_0 (the rope wound on at a
// start drum is s_0's increase). Measured 1e-16 relative; bound 1e-12.
TEST(RopeGrip, MaterialMovesWithTheGroovesSurface) {
    const double v = 0.3;
    const Eigen::VectorXd Ys = Eigen::VectorXd::Constant(1, surfaceCoordinate()), rate = Eigen::VectorXd::Constant(1, v);
    const Eigen::VectorXd none;
    const RopeModel<2> rope = drumRope(true);
    RopeData<2> d;
    rope.computeDynamics(drumNodes(), Eigen::Matrix2Xd::Zero(2, 2), Ys, rate, none, none, d);
    const Expected e = fromGeometry(d.materialCoordinates[0]);
    EXPECT_NEAR(d.materialRates[0], v / e.lambda, 1e-12 * v);
    ASSERT_EQ(d.gripCreepRates.size(), 1);
    EXPECT_NEAR(d.gripCreepRates[0], v * (1.0 / e.lambda - 1.0), 1e-12 * v);
    const double power = 0.5 * kEA * e.eps * e.eps * v / e.lambda;
    EXPECT_NEAR(d.gripHeldEnergyRates[0], power, 1e-12 * power);
}

// Under gravity (9.81 m/s^2, rhoA 1 kg/m) the stored ring lies on the groove it covers, short of
// the material wound on by the creep; the creep's mass is held at the tangent point's height (its
// weight's energy, rhoA phi_T cdot, is part of gripHeldEnergyRates), so the rope's mass is
// conserved and no force depends on where y = 0 is. The whole drum and fall moved up by 15 m: the
// drum's force on Y_s and the anchor's are unchanged (measured identical; bound 1e-12); without the
// creep's weight the drum's would change by rhoA g 15 m (1 - 1 / lambda) = 13 N. The held energy's
// rate is EA eps^2 / 2 sdot + rhoA phi_T v (1 / lambda - 1), phi_T = -g . r_T, to 1e-16 (bound
// 1e-12 of its terms).
TEST(RopeGrip, ForcesDoNotDependOnTheHeightDatum) {
    const double v = 0.3, g = 9.81, lift = 15.0;
    const Eigen::VectorXd Ys = Eigen::VectorXd::Constant(1, surfaceCoordinate()), rate = Eigen::VectorXd::Constant(1, v);
    const Eigen::VectorXd none;
    const RopeModel<2> rope = drumRope(true, Eigen::Vector2d(0, -g));
    double drum[2], anchor[2];
    for (int i = 0; i < 2; ++i) {
        Eigen::Matrix2Xd nodes = drumNodes();
        nodes.row(1).array() += i * lift;
        RopeData<2> d;
        rope.computeDynamics(nodes, Eigen::Matrix2Xd::Zero(2, 2), Ys, rate, none, none, d);
        drum[i] = d.nodeForce[d.nodeForce.size() - 1];
        anchor[i] = d.nodeForce[3];
        const Expected e = fromGeometry(d.materialCoordinates[0]);
        const double yT = nodes(1, 0);  // the tangent point, at the drum's height (its right-hand side)
        const double strain = 0.5 * kEA * e.eps * e.eps * v / e.lambda, weight = 1.0 * g * yT * v * (1 / e.lambda - 1);
        std::printf("datum +%.0f m: drum %.9f N, anchor %.9f N; held energy rate %.9e W (strain %.6e, creep's weight "
                    "%.6e)\n",
                    i * lift, drum[i], anchor[i], d.gripHeldEnergyRates[0], strain, weight);
        EXPECT_NEAR(d.gripHeldEnergyRates[0], strain + weight, 1e-12 * (std::abs(strain) + std::abs(weight)));
    }
    EXPECT_NEAR(drum[1], drum[0], 1e-12 * std::abs(drum[0]));
    EXPECT_NEAR(anchor[1], anchor[0], 1e-12 * std::abs(anchor[0]));
}

// Only a wrapped Driven end node (a drum whose rope leaves at its tangent point) can grip.
TEST(RopeGrip, OnlyAWrappedDrumGrips) {
    const char* what = "is not a wrapped Driven end node";
    RopeModel<2> rope = drumRope(false);
    EXPECT_THROW_MESSAGE(rope.setGrip(1), std::invalid_argument, what);  // the Fixed anchor
    EXPECT_THROW_MESSAGE(rope.setGrip(2), std::invalid_argument, what);  // no such node
    EXPECT_FALSE(rope.grips(0));
    rope.setGrip(0);
    rope.setGrip(0);  // twice: once
    EXPECT_TRUE(rope.grips(0));
    SpanOptions o;
    o.axialModes = 0;
    o.transverseModes = 0;
    const SpanModel<2> span(RopeProperties{1.0, kEA, 0.0}, o, Eigen::Vector2d::Zero());
    RopeModel<2> pointDrum({span}, kL, {MaterialNode::Driven, MaterialNode::Fixed});
    EXPECT_THROW_MESSAGE(pointDrum.setGrip(0), std::invalid_argument, what);
    RopeModel<2> turningSheave({span, span}, kL, {MaterialNode::Fixed, MaterialNode::Driven, MaterialNode::Fixed},
                               {NodeWrap{}, drumWrap(), NodeWrap{}});
    EXPECT_THROW_MESSAGE(turningSheave.setGrip(1), std::invalid_argument, what);
}
