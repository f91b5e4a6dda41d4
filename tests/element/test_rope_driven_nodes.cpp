// RopeModel with MaterialNode::Driven nodes (winch drums, turning sheaves): a held Driven end
// reproduces the Fixed anchor; the rope's generalized force on a Driven material coordinate is
// minus the derivative of its reduced potential; material running out and bad node kinds are clear
// errors.
#include "SimbodyReeving/element/RopeModel.h"
#include "support/ExpectThrowMessage.h"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <string>

using namespace SimbodyReeving;

namespace {

const RopeProperties kRope{0.6205, 16.5e6, 30.9};
const Eigen::Vector2d kGravity(0, -9.81);

std::vector<SpanModel<2>> makeSpans(int n, int na, int nt, AxialDynamics axial) {
    SpanOptions o;
    o.axialModes = na;
    o.transverseModes = nt;
    o.axialDynamics = axial;
    o.velocityModel = VelocityModel::Simplified;  // not the default: the setting these bounds were measured with
    return std::vector<SpanModel<2>>(n, SpanModel<2>(kRope, o, kGravity));
}

// Three nodes: start anchor, sheave, payload end (the paper's pendulum geometry).
Eigen::Matrix2Xd pendulumNodes() {
    Eigen::Matrix2Xd n(2, 3);
    n << 0, 3, 3.4, 0, 0, -20.05;
    return n;
}

}  // namespace

// A Driven end node held at s = L with zero rate is the Fixed anchor: same material coordinates,
// same reduced node mass and force on the node positions, same modal response.
TEST(RopeDrivenNodes, HeldDrivenEndReproducesTheFixedAnchor) {
    for (AxialDynamics axial : {AxialDynamics::Dynamic, AxialDynamics::QuasiStatic}) {
        const double L = 23.0;
        const RopeModel<2> fixed(makeSpans(2, 2, 1, axial), L);
        const RopeModel<2> driven(makeSpans(2, 2, 1, axial), L,
                                  {MaterialNode::Fixed, MaterialNode::Sliding, MaterialNode::Driven});
        ASSERT_EQ(driven.numDrivenNodes(), 1);
        ASSERT_EQ(driven.numExternalCoordinates(), 7);
        ASSERT_EQ(fixed.numModalCoordinates(), driven.numModalCoordinates());
        const int nm = fixed.numModalCoordinates();
        Eigen::VectorXd qm(nm), qmd(nm);
        for (int i = 0; i < nm; ++i) {
            qm[i] = 1e-4 * std::sin(1.0 + i);
            qmd[i] = 1e-3 * std::cos(2.0 + i);
        }
        const Eigen::Matrix2Xd nodes = pendulumNodes();
        Eigen::Matrix2Xd vel = Eigen::Matrix2Xd::Zero(2, 3);
        vel.col(2) << 1.0, 0.2;
        RopeData<2> a, b;
        fixed.computeDynamics(nodes, vel, qm, qmd, a);
        const Eigen::VectorXd sL = Eigen::VectorXd::Constant(1, L), zero = Eigen::VectorXd::Zero(1);
        driven.computeDynamics(nodes, vel, sL, zero, qm, qmd, b);
        const double scale = a.nodeMass.cwiseAbs().maxCoeff();
        EXPECT_LE((a.materialCoordinates - b.materialCoordinates).cwiseAbs().maxCoeff(), 1e-13);
        EXPECT_LE((a.nodeMass - b.nodeMass.topLeftCorner(6, 6)).cwiseAbs().maxCoeff(), 1e-12 * scale);
        EXPECT_LE((a.nodeForce - b.nodeForce.head(6)).cwiseAbs().maxCoeff(),
                  1e-12 * a.nodeForce.cwiseAbs().maxCoeff());
        EXPECT_NEAR(a.kineticEnergy, b.kineticEnergy, 1e-12 * a.kineticEnergy);
        EXPECT_NEAR(a.strainEnergy, b.strainEnergy, 1e-12 * a.strainEnergy);
        Eigen::VectorXd xa = Eigen::VectorXd::Zero(6), xb = Eigen::VectorXd::Zero(7), qa, qb;
        xa.segment<2>(4) = xb.segment<2>(4) = Eigen::Vector2d(0.3, -9.0);
        fixed.modalAccelerations(a, xa, qa);
        driven.modalAccelerations(b, xb, qb);
        EXPECT_LE((qa - qb).cwiseAbs().maxCoeff(), 1e-10 * qa.cwiseAbs().maxCoeff());
        // At the held end, the rope's generalized force on s is the force that holds its material:
        // about the axial force there (EA eps, ~9.9 kN for the 1000 kg payload's configuration).
        EXPECT_GT(std::abs(b.nodeForce[6]), 1e3);
    }
}

// At rest, Qbar on the external coordinates is -dV/dx of the reduced potential V(x, q_m) (the
// dependents solved at every x): checked for a Driven interior node (a turning sheave) and a Driven
// start (a drum), with Sliding sheaves on both sides, both axial models.
TEST(RopeDrivenNodes, GeneralizedForceOnDrivenCoordinateIsMinusPotentialGradient) {
    for (AxialDynamics axial : {AxialDynamics::Dynamic, AxialDynamics::QuasiStatic}) {
        const RopeModel<2> rope(makeSpans(4, 2, 1, axial), 40.0,
                                {MaterialNode::Driven, MaterialNode::Sliding, MaterialNode::Driven,
                                 MaterialNode::Sliding, MaterialNode::Fixed});
        Eigen::Matrix2Xd nodes(2, 5);
        nodes << 0, 0.4, 0.8, 1.2, 1.6, 0, -9.0, 0.0, -9.5, 0.0;
        const int nm = rope.numModalCoordinates();
        Eigen::VectorXd qm(nm);
        for (int i = 0; i < nm; ++i) qm[i] = 2e-4 * std::sin(3.0 + i);
        const Eigen::VectorXd zero = Eigen::VectorXd::Zero(nm), zero2 = Eigen::VectorXd::Zero(2);
        Eigen::VectorXd sd(2);
        sd << 1.0, 19.5;  // drum at s_0 = 1 m, turning sheave at s_2 = 19.5 m
        auto potential = [&](const Eigen::VectorXd& s) {
            RopeData<2> d;
            rope.computeDynamics(nodes, Eigen::Matrix2Xd::Zero(2, 5), s, zero2, qm, zero, d);
            return d.strainEnergy + d.gravityEnergy;
        };
        RopeData<2> d;
        rope.computeDynamics(nodes, Eigen::Matrix2Xd::Zero(2, 5), sd, zero2, qm, zero, d);
        for (int i = 0; i < 2; ++i) {
            const double h = 1e-6;
            Eigen::VectorXd sp = sd, sm = sd;
            sp[i] += h;
            sm[i] -= h;
            const double dV = (potential(sp) - potential(sm)) / (2 * h);
            const double Q = d.reducedForce()[10 + i];
            // Central differences at h = 1e-6: measured at most 3.9e-8 N of 27 N; margin 51x.
            EXPECT_NEAR(Q, -dV, 2e-6) << "driven coordinate " << i;
        }
    }
}

TEST(RopeDrivenNodes, NoMaterialLeftIsARuntimeErrorNamingTheNodes) {
    const RopeModel<2> rope(makeSpans(2, 1, 1, AxialDynamics::Dynamic), 23.0,
                            {MaterialNode::Fixed, MaterialNode::Sliding, MaterialNode::Driven});
    RopeData<2> d;
    const Eigen::VectorXd qm = Eigen::VectorXd::Zero(rope.numModalCoordinates());
    EXPECT_THROW_MESSAGE(rope.solveDependentCoordinates(pendulumNodes(), Eigen::VectorXd::Constant(1, -0.5), qm, d),
                         std::runtime_error, "RopeModel: no rope material between node 0 (s = 0 m) and node 2");
    EXPECT_THROW_MESSAGE(rope.solveDependentCoordinates(pendulumNodes(), Eigen::VectorXd::Constant(1, -0.5), qm, d),
                         std::runtime_error, "the spans between them would have a non-positive unstretched length");
    // The old interface on a rope with Driven nodes: the missing coordinates are named.
    EXPECT_THROW_MESSAGE(rope.solveDependentCoordinates(pendulumNodes(), qm, d), std::invalid_argument,
                         "RopeModel: 0 driven material coordinates given for 1 Driven nodes");
}

TEST(RopeDrivenNodes, BadNodeKindsAreInvalidArguments) {
    EXPECT_THROW_MESSAGE(RopeModel<2>(makeSpans(2, 0, 1, AxialDynamics::Dynamic), 23.0,
                                      {MaterialNode::Fixed, MaterialNode::Fixed, MaterialNode::Fixed}),
                         std::invalid_argument,
                         "RopeModel: interior node 1 cannot be Fixed");  // a fastened interior node
    EXPECT_THROW_MESSAGE(RopeModel<2>(makeSpans(2, 0, 1, AxialDynamics::Dynamic), 23.0,
                                      {MaterialNode::Sliding, MaterialNode::Sliding, MaterialNode::Fixed}),
                         std::invalid_argument,
                         "RopeModel: end node 0 cannot be Sliding");  // a sheave kind on an end node
    EXPECT_THROW_MESSAGE(RopeModel<2>(makeSpans(2, 0, 1, AxialDynamics::Dynamic), 23.0,
                                      {MaterialNode::Fixed, MaterialNode::Fixed}),
                         std::invalid_argument, "RopeModel: 2 node kinds given for 3 nodes");  // wrong count
}

// A drum that turned a long way since the last evaluation (an interpolated report metres of rope
// later): the warm start is mapped into the new material range and, failing that, Newton restarts
// cold; the result is the cold solution.
TEST(RopeDrivenNodes, LargeDrumTurnBetweenEvaluationsStillConverges) {
    for (AxialDynamics axial : {AxialDynamics::Dynamic, AxialDynamics::QuasiStatic}) {
        std::vector<MaterialNode> kinds(13, MaterialNode::Sliding);
        kinds.front() = MaterialNode::Driven;
        kinds.back() = MaterialNode::Fixed;
        const RopeModel<2> rope(makeSpans(12, 1, 1, axial), 12 * 10.0, kinds);
        Eigen::Matrix2Xd nodes(2, 13);
        for (int k = 0; k <= 12; ++k) nodes.col(k) << 0.1 * k, (k % 2 == 1 ? -10.0 : 0.0);
        const Eigen::VectorXd qm = Eigen::VectorXd::Zero(rope.numModalCoordinates());
        RopeData<2> warm, cold;
        rope.solveDependentCoordinates(nodes, Eigen::VectorXd::Constant(1, 0.0), qm, warm);
        // 8.5 m hauled in while the hook block rose 8.5 / 12 m.
        for (int k = 1; k <= 12; k += 2) nodes(1, k) += 8.5 / 12;
        rope.solveDependentCoordinates(nodes, Eigen::VectorXd::Constant(1, 8.5), qm, warm);
        rope.solveDependentCoordinates(nodes, Eigen::VectorXd::Constant(1, 8.5), qm, cold);
        EXPECT_LE((warm.materialCoordinates - cold.materialCoordinates).cwiseAbs().maxCoeff(), 1e-9);
    }
}

// Rope stored on a drum (setStoredRope): the drum's generalized force does not depend on the
// height datum, and at rest it is -dV/ds of the potential including the stored rope.
TEST(RopeDrivenNodes, StoredRopeMakesTheDrumForceDatumFree) {
    for (AxialDynamics axial : {AxialDynamics::Dynamic, AxialDynamics::QuasiStatic}) {
        auto make = [&] {
            RopeModel<2> rope(makeSpans(2, 2, 1, axial), 23.0,
                              {MaterialNode::Driven, MaterialNode::Sliding, MaterialNode::Fixed});
            rope.setStoredRope(0, 40.0);
            return rope;
        };
        const RopeModel<2> rope = make();
        const int nm = rope.numModalCoordinates();
        Eigen::VectorXd qm(nm);
        for (int i = 0; i < nm; ++i) qm[i] = 1e-4 * std::sin(2.0 + i);
        const Eigen::VectorXd zero = Eigen::VectorXd::Zero(nm), zero1 = Eigen::VectorXd::Zero(1);
        const Eigen::VectorXd sd = Eigen::VectorXd::Constant(1, 0.5);
        Eigen::Matrix2Xd nodes = pendulumNodes();
        RopeData<2> a, b;
        rope.computeDynamics(nodes, Eigen::Matrix2Xd::Zero(2, 3), sd, zero1, qm, zero, a);
        nodes.row(1).array() += 25.0;  // the same machine 25 m higher
        rope.computeDynamics(nodes, Eigen::Matrix2Xd::Zero(2, 3), sd, zero1, qm, zero, b);
        // Measured 1.4e-16 relative (round-off); margin 74x.
        EXPECT_NEAR(a.nodeForce[6], b.nodeForce[6], 1e-14 * std::abs(a.nodeForce[6]));
        auto potential = [&](double s0) {
            RopeData<2> d;
            rope.computeDynamics(nodes, Eigen::Matrix2Xd::Zero(2, 3), Eigen::VectorXd::Constant(1, s0), zero1, qm,
                                 zero, d);
            return d.strainEnergy + d.gravityEnergy;
        };
        const double h = 1e-6, dV = (potential(0.5 + h) - potential(0.5 - h)) / (2 * h);
        // Qbar holds the spans' generalized force; the stored rope adds rhoA g . r_0 (slope +1).
        const double stored = kRope.massPerLength * kGravity.dot(nodes.col(0));
        // Central differences of a potential 25 m above the datum (round-off eps V / h): measured
        // 1.9e-4 N of 4.3e5 N; margin 27x.
        EXPECT_NEAR(b.reducedForce()[6] + stored, -dV, 5e-3);
        EXPECT_THROW_MESSAGE(RopeModel<2>(make()).setStoredRope(1, 1.0), std::invalid_argument,
                             "RopeModel::setStoredRope: node 1 is not a Driven end node");
    }
}
