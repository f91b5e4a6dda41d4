// RopeModel's chain solve (band LU of the KKT system in rope order) against the dense
// reduction it replaced: S = Mbar_xx - Mbar_xm Mbar_mm^-1 Mbar_mx, h likewise and the modal
// accelerations, from RopeData::reducedMass / reducedForce (G^T M G formed densely). Ropes: zigzags
// over 1..9 sheaves with quasi-static axial modes (condensation rows and multipliers), with the
// paper's rows (Dynamic axial modes), with Driven nodes (a drum at the start, a turning sheave in
// the path), and a spatial one.
#include "SimbodyReeving/element/RopeModel.h"
#include "support/ExpectThrowMessage.h"

#include <gtest/gtest.h>

#include <Eigen/Cholesky>

#include <algorithm>
#include <random>

using namespace SimbodyReeving;

namespace {

template <int Dim>
struct Case {
    int sheaves = 3, na = 3, nt = 1;
    AxialDynamics axial = AxialDynamics::QuasiStatic;
    bool drivenStart = false, drivenMiddle = false;
};

// Largest relative differences (S, h, qddot_m) of the chain solve against the dense reduction, and of
// multiplyByNodeMass against the formed S.
template <int Dim>
Eigen::Vector4d chainAgainstDense(const Case<Dim>& c, std::mt19937& rng) {
    using NodeMatrix = typename RopeModel<Dim>::NodeMatrix;
    const RopeProperties props{0.6205, 16.5e6, 30.9};
    SpanOptions o;
    o.axialModes = c.na;
    o.transverseModes = c.nt;
    o.axialDynamics = c.axial;
    Eigen::Matrix<double, Dim, 1> g = Eigen::Matrix<double, Dim, 1>::Zero();
    g[1] = -9.81;
    const int N = c.sheaves + 1;
    NodeMatrix nodes(Dim, N + 1), velocities = NodeMatrix::Zero(Dim, N + 1);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    for (int k = 0; k < N; ++k) {
        nodes.col(k).setZero();
        nodes(0, k) = 1.5 * k;
        nodes(1, k) = (k % 2) * 0.7;
        if (Dim == 3) nodes(2, k) = 0.2 * k;
    }
    nodes.col(N) = nodes.col(N - 1);
    nodes(1, N) -= 4.0;
    nodes(0, N) += 0.3;
    for (int k = 0; k <= N; ++k)
        for (int d = 0; d < Dim; ++d) velocities(d, k) = u(rng);
    double path = 0;
    for (int k = 0; k < N; ++k) path += (nodes.col(k + 1) - nodes.col(k)).norm();
    std::vector<SpanModel<Dim>> spans;
    for (int j = 0; j < N; ++j) spans.emplace_back(props, o, g);
    std::vector<MaterialNode> kinds(N + 1, MaterialNode::Sliding);
    kinds.front() = kinds.back() = MaterialNode::Fixed;
    if (c.drivenStart) kinds.front() = MaterialNode::Driven;
    if (c.drivenMiddle) kinds[N / 2] = MaterialNode::Driven;
    RopeModel<Dim> rope(std::move(spans), 0.999 * path, kinds);
    Eigen::VectorXd sDriven(rope.numDrivenNodes()), sDrivenDot(rope.numDrivenNodes());
    int d = 0;
    if (c.drivenStart) {
        sDriven[d] = 0.0;
        sDrivenDot[d++] = 0.3;
    }
    if (c.drivenMiddle) {
        double acc = 0;
        for (int k = 0; k < N / 2; ++k) acc += (nodes.col(k + 1) - nodes.col(k)).norm();
        sDriven[d] = 0.999 * acc;
        sDrivenDot[d++] = -0.2;
    }
    const int nm = rope.numModalCoordinates(), nx = rope.numExternalCoordinates();
    Eigen::VectorXd qm = 1e-3 * Eigen::VectorXd::NullaryExpr(nm, [&] { return u(rng); });
    Eigen::VectorXd qmd = 1e-2 * Eigen::VectorXd::NullaryExpr(nm, [&] { return u(rng); });
    RopeData<Dim> data;
    rope.solveDependentCoordinates(nodes, sDriven, qm, data);
    rope.computeDynamics(nodes, velocities, sDriven, sDrivenDot, qm, qmd, data);
    const Eigen::MatrixXd Mbar = data.reducedMass();
    const Eigen::VectorXd Qbar = data.reducedForce();
    const Eigen::LDLT<Eigen::MatrixXd> Mmm(Mbar.bottomRightCorner(nm, nm));
    const Eigen::MatrixXd coupling = Mmm.solve(Mbar.bottomLeftCorner(nm, nx));
    const Eigen::MatrixXd S = Mbar.topLeftCorner(nx, nx) - Mbar.topRightCorner(nx, nm) * coupling;
    const Eigen::VectorXd h = Qbar.head(nx) - Mbar.topRightCorner(nx, nm) * Mmm.solve(Qbar.tail(nm));
    const Eigen::VectorXd xdd = Eigen::VectorXd::NullaryExpr(nx, [&] { return u(rng); });
    const Eigen::VectorXd qmddDense = Mmm.solve(Qbar.tail(nm) - Mbar.bottomLeftCorner(nm, nx) * xdd);
    Eigen::VectorXd qmdd;
    rope.modalAccelerations(data, xdd, qmdd);
    auto rel = [](const auto& a, const auto& b) { return (a - b).cwiseAbs().maxCoeff() / b.cwiseAbs().maxCoeff(); };
    // multiplyByNodeMass: S X without S, against the formed S (3 columns).
    const Eigen::MatrixXd X = Eigen::MatrixXd::NullaryExpr(nx, 3, [&] { return u(rng); });
    Eigen::MatrixXd SX;
    rope.multiplyByNodeMass(data, X, SX);
    const Eigen::MatrixXd SXref = data.nodeMass * X;
    double product = rel(SX, SXref);
    // formNodeMass = false: the same h, and the same modal accelerations by a solve.
    RopeData<Dim> lean;
    lean.formNodeMass = false;
    rope.solveDependentCoordinates(nodes, sDriven, qm, lean);
    rope.computeDynamics(nodes, velocities, sDriven, sDrivenDot, qm, qmd, lean);
    EXPECT_EQ(lean.nodeMass.size(), 0);
    Eigen::VectorXd qmddLean;
    rope.modalAccelerations(lean, xdd, qmddLean);
    Eigen::VectorXd qmddFormed;
    rope.modalAccelerations(data, xdd, qmddFormed);
    product = std::max(product, rel(lean.nodeForce, data.nodeForce));
    if (nm > 0) product = std::max(product, rel(qmddLean, qmddFormed));
    // modalAccelerationsFromLastProduct: xddot = X c from the last product's solutions, no solve.
    if (nm > 0) {
        const Eigen::VectorXd weights = Eigen::VectorXd::NullaryExpr(X.cols(), [&] { return u(rng); });
        rope.multiplyByNodeMass(lean, X, SX);
        Eigen::VectorXd qmddCombined, qmddSolved;
        rope.modalAccelerationsFromLastProduct(lean, weights, qmddCombined);
        // Before modalAccelerations, whose own one-column product on lean data replaces X's.
        EXPECT_THROW_MESSAGE(
            rope.modalAccelerationsFromLastProduct(lean, Eigen::VectorXd::Zero(X.cols() + 1), qmddCombined),
            std::invalid_argument,
            "RopeModel::modalAccelerationsFromLastProduct: " + std::to_string(X.cols() + 1) + " weights for " +
                std::to_string(X.cols()) + " columns of the last multiplyByNodeMass");
        rope.modalAccelerations(lean, X * weights, qmddSolved);
        product = std::max(product, rel(qmddCombined, qmddSolved));
    }
    // The stored rope of drums is added after the reduction in both; none here.
    return {rel(data.nodeMass, S), rel(data.nodeForce, h), nm > 0 ? rel(qmdd, qmddDense) : 0.0, product};
}

}  // namespace

TEST(RopeChainSolve, MatchesTheDenseReductionOnPlanarAndSpatialRopes) {
    std::mt19937 rng(11);
    Eigen::Vector4d worst = Eigen::Vector4d::Zero();
    for (int sheaves : {1, 2, 5, 9})
        for (int na : {0, 1, 3}) {
            Case<2> c;
            c.sheaves = sheaves;
            c.na = na;
            worst = worst.cwiseMax(chainAgainstDense(c, rng));
            c.axial = AxialDynamics::Dynamic;  // the paper's tension-equality rows only
            worst = worst.cwiseMax(chainAgainstDense(c, rng));
            c.axial = AxialDynamics::QuasiStatic;
            c.drivenStart = c.drivenMiddle = sheaves > 1;
            worst = worst.cwiseMax(chainAgainstDense(c, rng));
        }
    for (int na : {0, 2}) {
        Case<3> c;
        c.sheaves = 4;
        c.na = na;
        c.nt = 2;
        worst = worst.cwiseMax(chainAgainstDense(c, rng));
    }
    std::printf("chain vs dense: S %.3g, h %.3g, qddot_m %.3g; S X %.3g\n", worst[0], worst[1], worst[2], worst[3]);
    // Measured S 2.9e-13, h 1.3e-12, qddot_m 2.2e-12 (round-off of two different eliminations); S X,
    // and h and qddot_m without the formed S, against the formed ones: 4.7e-15; bounds about 100x.
    EXPECT_LE(worst[0], 3e-11);
    EXPECT_LE(worst[1], 1e-10);
    EXPECT_LE(worst[2], 2e-10);
    EXPECT_LE(worst[3], 5e-13);
}

// computeDynamics returns at once when called again with the positions, velocities and dependent
// coordinates of its last evaluation (a repeated Simbody realization); any change recomputes. The
// results after A, B, A equal those of fresh data at A, bit for bit.
TEST(RopeChainSolve, RepeatedEvaluationsGiveTheResultsOfFreshData) {
    using NodeMatrix = RopeModel<2>::NodeMatrix;
    const RopeProperties props{0.6205, 16.5e6, 30.9};
    SpanOptions o;
    o.axialModes = 1;
    o.transverseModes = 2;
    o.axialDynamics = AxialDynamics::QuasiStatic;
    const Eigen::Vector2d g(0.0, -9.81);
    const int N = 4;
    NodeMatrix nodes(2, N + 1);
    nodes << 0.0, 1.5, 3.0, 4.5, 4.8, 0.0, 0.7, 0.0, 0.7, -3.3;
    double path = 0;
    for (int k = 0; k < N; ++k) path += (nodes.col(k + 1) - nodes.col(k)).norm();
    std::vector<SpanModel<2>> spans(N, SpanModel<2>(props, o, g));
    const RopeModel<2> rope(std::move(spans), 0.999 * path);
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    const NodeMatrix vA = NodeMatrix::NullaryExpr(2, N + 1, [&] { return u(rng); });
    NodeMatrix vB = vA;
    vB(1, 2) += 1e-3;
    const int nm = rope.numModalCoordinates();
    const Eigen::VectorXd qm = 1e-3 * Eigen::VectorXd::NullaryExpr(nm, [&] { return u(rng); });
    const Eigen::VectorXd qmd = 1e-2 * Eigen::VectorXd::NullaryExpr(nm, [&] { return u(rng); });
    auto evaluate = [&](RopeData<2>& d, const NodeMatrix& v) { rope.computeDynamics(nodes, v, qm, qmd, d); };
    RopeData<2> reused, freshA, freshB;
    rope.solveDependentCoordinates(nodes, qm, reused);
    evaluate(reused, vA);
    evaluate(reused, vA);  // the same again: returns at once
    evaluate(freshA, vA);
    EXPECT_EQ(reused.nodeForce, freshA.nodeForce);
    EXPECT_EQ(reused.nodeMass, freshA.nodeMass);
    EXPECT_EQ(reused.kineticEnergy, freshA.kineticEnergy);
    evaluate(reused, vB);  // another velocity: recomputed
    evaluate(freshB, vB);
    EXPECT_EQ(reused.nodeForce, freshB.nodeForce);
    EXPECT_EQ(reused.materialRates, freshB.materialRates);
    EXPECT_NE(reused.nodeForce, freshA.nodeForce);
    evaluate(reused, vA);  // back to A: recomputed, A's results again
    EXPECT_EQ(reused.nodeForce, freshA.nodeForce);
    EXPECT_EQ(reused.materialRates, freshA.materialRates);
    Eigen::VectorXd aReused, aFresh;
    const Eigen::VectorXd xdd = Eigen::VectorXd::NullaryExpr(rope.numExternalCoordinates(), [&] { return u(rng); });
    rope.modalAccelerations(reused, xdd, aReused);
    rope.modalAccelerations(freshA, xdd, aFresh);
    EXPECT_EQ(aReused, aFresh);
}
