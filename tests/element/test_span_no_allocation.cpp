// One span evaluation performs no heap allocation.
// This test binary replaces the global operator new/delete with counting versions; the count over
// repeated evaluate() calls must stay zero for planar and spatial spans, both velocity models and
// both energy models, at the largest mode counts. The same holds for a whole rope's evaluation
// (tension-equality Newton, reduction to the nodes, modal accelerations) once its workspace is sized.
#include "SimbodyReeving/element/RopeModel.h"
#include "SimbodyReeving/element/SpanModel.h"
#include "support/SpanTestSupport.h"

#include <gtest/gtest.h>

#include "support/CountingMalloc.h"  // (defines malloc and operator new: this executable only)

using namespace SimbodyReeving;

namespace {

template <int Dim>
long allocationsPerEvaluation(int na, int nt, VelocityModel vm, ElasticEnergyModel em) {
    SpanOptions o;
    o.axialModes = na;
    o.transverseModes = nt;
    o.velocityModel = vm;
    o.elasticModel = em;
    o.axialDynamics = AxialDynamics::Dynamic;  // not the default: the setting these bounds were measured with
    Eigen::Matrix<double, Dim, Dim> ref = Eigen::Matrix<double, Dim, Dim>::Identity();
    // Consistent: the tension-only law (the default); PaperLiteral requires the linear law.
    const SpanModel<Dim> model({0.6, 1e6, 30, em == ElasticEnergyModel::Consistent}, o, Eigen::Matrix<double, Dim, 1>::Constant(-1.0), ref);
    std::mt19937 rng(5);
    const Eigen::VectorXd q = test::randomState(model, rng);
    const Eigen::VectorXd qd = test::randomVelocity(model, rng);
    SpanData<Dim> data;
    model.evaluate(q, qd, data);  // warm-up
    const long before = gAllocations.load();
    for (int k = 0; k < 10; ++k) model.evaluate(q, qd, data);
    return gAllocations.load() - before;
}

/// Allocations over repeated evaluations of a rope of `numSpans` spans (numSpans - 1 sheaves),
/// after one warm-up evaluation at the same mode counts.
template <int Dim>
long allocationsPerRopeEvaluation(int numSpans, int na, int nt,
                                  AxialDynamics axial = AxialDynamics::Dynamic) {
    SpanOptions o;
    o.axialModes = na;
    o.transverseModes = nt;
    o.axialDynamics = axial;
    o.velocityModel = VelocityModel::Simplified;  // not the default: the setting these bounds were measured with
    using Vec = Eigen::Matrix<double, Dim, 1>;
    Vec g = Vec::Zero();
    g[1] = -9.81;
    std::vector<SpanModel<Dim>> spans;
    Eigen::Matrix<double, Dim, Eigen::Dynamic> nodes = Eigen::Matrix<double, Dim, Eigen::Dynamic>::Zero(Dim, numSpans + 1);
    for (int k = 1; k <= numSpans; ++k) {
        nodes(0, k) = 3.0 * k;  // a zig-zag over the sheaves
        nodes(1, k) = (k % 2 == 1) ? -4.0 : 0.0;
    }
    for (int j = 0; j < numSpans; ++j) {
        Eigen::Matrix<double, Dim, Dim> ref = Eigen::Matrix<double, Dim, Dim>::Identity();
        spans.emplace_back(RopeProperties{0.6205, 16.5e6, 30.9}, o, g, ref);
    }
    double length = 0;
    for (int j = 0; j < numSpans; ++j) length += (nodes.col(j + 1) - nodes.col(j)).norm();
    const RopeModel<Dim> rope(std::move(spans), 0.999 * length);
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> u(-1e-3, 1e-3);
    Eigen::VectorXd qm(rope.numModalCoordinates()), qmd(rope.numModalCoordinates());
    for (int i = 0; i < qm.size(); ++i) {
        qm[i] = u(rng);
        qmd[i] = u(rng);
    }
    Eigen::Matrix<double, Dim, Eigen::Dynamic> velocities = Eigen::Matrix<double, Dim, Eigen::Dynamic>::Zero(Dim, numSpans + 1);
    velocities(0, numSpans) = 1.0;
    Eigen::VectorXd nodeAcc = Eigen::VectorXd::Zero(Dim * (numSpans + 1)), qmdd;
    RopeData<Dim> data;
    auto evaluate = [&] {
        rope.solveDependentCoordinates(nodes, qm, data);
        rope.computeDynamics(nodes, velocities, qm, qmd, data);
        rope.modalAccelerations(data, nodeAcc, qmdd);
        rope.recoverInertialStrain(data, nodeAcc, qmdd);
    };
    evaluate();  // warm-up: sizes the workspace
    const long before = gAllocations.load();
    for (int k = 0; k < 10; ++k) {
        nodes(0, numSpans) += 1e-4;  // a new configuration every time (Newton iterates)
        evaluate();
    }
    return gAllocations.load() - before;
}

/// Allocations over repeated evaluations of a rope over one wrapped sheave (radius 0.3 m, the rope
/// from an anchor over its top and down to a moving end) through the station forms (NodeMatrix:
/// the station map's reduction), after one warm-up evaluation; with the node mass formed or not.
template <int Dim>
long allocationsPerWrappedRopeEvaluation(AxialDynamics axial, bool formNodeMass) {
    SpanOptions o;
    o.axialModes = 2;
    o.transverseModes = 1;
    o.axialDynamics = axial;
    using Vec = Eigen::Matrix<double, Dim, 1>;
    Vec g = Vec::Zero();
    g[1] = -9.81;
    std::vector<SpanModel<Dim>> spans;
    for (int j = 0; j < 2; ++j)
        spans.emplace_back(RopeProperties{0.6205, 16.5e6, 30.9}, o, g, Eigen::Matrix<double, Dim, Dim>::Identity());
    Eigen::Matrix<double, Dim, Eigen::Dynamic> nodes = Eigen::Matrix<double, Dim, Eigen::Dynamic>::Zero(Dim, 3);
    nodes(0, 0) = -3.0;
    nodes(1, 0) = 0.3;
    nodes(0, 2) = 0.3;
    nodes(1, 2) = -5.0;
    std::vector<NodeWrap> wraps(3);
    wraps[1].radius = 0.3;
    wraps[1].wrapSense = -1;
    const RopeModel<Dim> rope(std::move(spans), 0.999 * (3.0 + 0.5 * 3.14159265358979 * 0.3 + 5.0),
                              {MaterialNode::Fixed, MaterialNode::Sliding, MaterialNode::Fixed}, wraps);
    Eigen::VectorXd qm = Eigen::VectorXd::Constant(rope.numModalCoordinates(), 1e-4);
    Eigen::VectorXd qmd = Eigen::VectorXd::Constant(rope.numModalCoordinates(), 1e-3);
    Eigen::Matrix<double, Dim, Eigen::Dynamic> velocities = Eigen::Matrix<double, Dim, Eigen::Dynamic>::Zero(Dim, 3);
    velocities(0, 2) = 1.0;
    Eigen::VectorXd nodeAcc = Eigen::VectorXd::Zero(rope.numStations() * Dim), qmdd;
    RopeData<Dim> data;
    data.formNodeMass = formNodeMass;
    auto evaluate = [&] {
        rope.solveDependentCoordinates(nodes, qm, data);
        rope.computeDynamics(nodes, velocities, qm, qmd, data);
        rope.modalAccelerations(data, nodeAcc, qmdd);
        rope.recoverInertialStrain(data, nodeAcc, qmdd);
    };
    evaluate();  // warm-up: sizes the workspace
    const long before = gAllocations.load();
    for (int k = 0; k < 10; ++k) {
        nodes(0, 2) += 1e-4;  // a new configuration every time
        evaluate();
    }
    return gAllocations.load() - before;
}

}  // namespace

TEST(SpanNoAllocation, CounterSeesAllocations) {
    const long before = gAllocations.load();
    {
        Eigen::VectorXd v(100);  // Eigen's heap storage (std::malloc)
        v.setZero();
        EXPECT_GE(gAllocations.load() - before, 1);  // the counter sees Eigen's allocations
    }
    const long mid = gAllocations.load();
    auto* p = new int(3);
    delete p;
    EXPECT_GE(gAllocations.load() - mid, 1);  // and operator new
}

TEST(SpanNoAllocation, EvaluateNeverAllocates) {
    for (auto vm : {VelocityModel::Simplified, VelocityModel::Complete})
        for (auto em : {ElasticEnergyModel::Consistent, ElasticEnergyModel::PaperLiteral}) {
            EXPECT_EQ(allocationsPerEvaluation<2>(3, 1, vm, em), 0);
            EXPECT_EQ(allocationsPerEvaluation<3>(3, 1, vm, em), 0);
            EXPECT_EQ(allocationsPerEvaluation<2>(16, 16, vm, em), 0);
            EXPECT_EQ(allocationsPerEvaluation<3>(16, 16, vm, em), 0);
        }
}

TEST(RopeNoAllocation, RopeEvaluationNeverAllocates) {
    EXPECT_EQ(allocationsPerRopeEvaluation<2>(1, 3, 1), 0);  // no sheave
    EXPECT_EQ(allocationsPerRopeEvaluation<2>(2, 3, 1), 0);  // the paper's pendulum rope
    EXPECT_EQ(allocationsPerRopeEvaluation<2>(4, 2, 2), 0);  // three sheaves
    EXPECT_EQ(allocationsPerRopeEvaluation<3>(3, 3, 2), 0);
    // Quasi-static axial modes: the condensation kernel, its Newton and the recovery.
    EXPECT_EQ(allocationsPerRopeEvaluation<2>(1, 3, 1, AxialDynamics::QuasiStatic), 0);
    EXPECT_EQ(allocationsPerRopeEvaluation<2>(2, 3, 1, AxialDynamics::QuasiStatic), 0);
    EXPECT_EQ(allocationsPerRopeEvaluation<2>(4, 2, 2, AxialDynamics::QuasiStatic), 0);
    EXPECT_EQ(allocationsPerRopeEvaluation<3>(3, 3, 2, AxialDynamics::QuasiStatic), 0);
}

// A wrapped rope evaluated from its stations (the Simbody layer's path): the reduction of the node
// mass, force and modal coupling to the stations keeps its buffers between evaluations.
TEST(RopeNoAllocation, WrappedRopeThroughItsStationsNeverAllocates) {
    for (AxialDynamics axial : {AxialDynamics::Dynamic, AxialDynamics::QuasiStatic})
        for (bool formed : {true, false}) {
            EXPECT_EQ(allocationsPerWrappedRopeEvaluation<2>(axial, formed), 0) << "planar, formed " << formed;
            EXPECT_EQ(allocationsPerWrappedRopeEvaluation<3>(axial, formed), 0) << "spatial, formed " << formed;
        }
}
