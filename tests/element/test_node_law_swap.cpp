// RopeModel::withNodeLaw, the phase change of a traction sheave without rebuilding the rope: the
// model with node k's law swapped between Driven (stick) and Slipping (slip with kappa(alpha) =
// kappa0 e^(c alpha)) gives, bit for bit, what the model built from scratch with that kind gives
// (every result of the position and dynamics evaluations, the reduction to the stations, the modal
// accelerations, the mode-acceleration recovery and the queries), shares the spans, kernels and
// groove arcs with the model it came from, and leaves that model as it was. Planar and spatial,
// Dynamic and QuasiStatic spans, on the traction rope of TractionRopeScene (a wrapped drum with
// stored rope, the wrapped traction sheave, a point sheave, an anchor; two nodes on Ground).
#include "SimbodyReeving/element/RopeModel.h"
#include "support/ExpectThrowMessage.h"
#include "support/TractionRopeScene.h"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <vector>

using namespace SimbodyReeving;
using SimbodyReevingTest::TractionRopeScene;

namespace {

void append(std::vector<double>& out, const Eigen::MatrixXd& m) {
    out.push_back(static_cast<double>(m.rows()));
    out.push_back(static_cast<double>(m.cols()));
    for (Eigen::Index j = 0; j < m.cols(); ++j)
        for (Eigen::Index i = 0; i < m.rows(); ++i) out.push_back(m(i, j));
}

// Every result of three evaluations at moving stations (a solve, then the dynamics; the second
// reusing the first's Jacobian structure, the third without forming S), with data from `start`.
template <int Dim>
std::vector<double> results(const RopeModel<Dim>& rope, const TractionRopeScene<Dim>& sc, const RopeData<Dim>& start) {
    std::vector<double> out;
    RopeData<Dim> d = start;
    const Eigen::VectorXd qm = TractionRopeScene<Dim>::modal(rope, 1e-4, 0.3), qmd = TractionRopeScene<Dim>::modal(rope, 1e-3, 1.1);
    for (int pass = 0; pass < 3; ++pass) {
        const double t = 0.01 * pass;
        const typename RopeModel<Dim>::NodeMatrix st = sc.stations + t * sc.stationRates;
        d.formNodeMass = pass != 2;
        rope.solveDependentCoordinates(st, sc.drivenS + t * sc.drivenSdot, qm, d);
        append(out, d.materialCoordinates);
        rope.computeDynamics(st, sc.stationRates, sc.drivenS + t * sc.drivenSdot, sc.drivenSdot, qm, qmd, d);
        for (const Eigen::VectorXd* v : {&d.materialCoordinates, &d.condensedAmplitudes, &d.multipliers, &d.materialRates,
                                         &d.condensedRates, &d.multiplierRates, &d.nodeForce})
            append(out, *v);
        append(out, d.nodeMass);
        out.insert(out.end(), {d.kineticEnergy, d.strainEnergy, d.gravityEnergy, d.dampingPower,
                               static_cast<double>(d.newtonIterations)});
        const int ny = static_cast<int>(d.nodeForce.size());
        Eigen::MatrixXd X(ny, 2), SX;
        for (int i = 0; i < ny; ++i) X.row(i) << std::sin(1.0 + i), std::cos(2.0 * i);
        rope.multiplyByNodeMass(d, X, SX);
        append(out, SX);
        Eigen::VectorXd qdd;
        rope.modalAccelerationsFromLastProduct(d, Eigen::Vector2d(0.5, -1.0), qdd);
        append(out, qdd);
        rope.modalAccelerations(d, X.col(0), qdd);
        append(out, qdd);
        rope.recoverInertialStrain(d, X.col(0), qdd);
        for (int j = 0; j < rope.numSpans(); ++j) {
            Eigen::VectorXd q;
            rope.recoveredSpanCoordinates(j, st, qm, d, q);
            append(out, q);
            append(out, d.spanRates(j));
        }
        append(out, d.reducedMass());
        append(out, d.reducedForce());
        for (int k = 1; k < rope.numSpans(); ++k) out.insert(out.end(), {rope.wrapAngle(d, k), rope.constraintError(d, k)});
        for (int k : {0, 1}) out.insert(out.end(), {rope.surfaceCoordinate(d, k), rope.surfaceRate(d, k)});
        out.insert(out.end(), {rope.storedRopeGravityEnergy(st, d), rope.arcGravityEnergy(st, d)});
    }
    return out;
}

struct Phase {
    MaterialNode kind;
    double kappa0, exponent;
};

template <int Dim>
void swapsEqualFreshModels() {
    const Phase phases[] = {{MaterialNode::Driven, 1.0, 0.0},
                            {MaterialNode::Slipping, 1.6, 0.0},
                            {MaterialNode::Slipping, 1.0, 0.3},
                            {MaterialNode::Slipping, 1.0, -0.3}};
    for (AxialDynamics axial : {AxialDynamics::Dynamic, AxialDynamics::QuasiStatic}) {
        const TractionRopeScene<Dim> sc(axial);
        for (const Phase& from : phases) {
            const RopeModel<Dim> base = sc.build(from.kind, from.kappa0, from.exponent);
            const std::vector<double> baseBefore = results(base, sc, RopeData<Dim>());
            // A simulation's hand-over at the phase change: fresh data for the new phase, warm-started
            // from the material coordinates and amplitudes of the last (as the Simbody layer does).
            RopeData<Dim> running, handover;
            base.computeDynamics(sc.stations, sc.stationRates, sc.drivenS, sc.drivenSdot,
                                 TractionRopeScene<Dim>::modal(base, 1e-4, 0.3),
                                 TractionRopeScene<Dim>::modal(base, 1e-3, 1.1), running);
            handover.materialCoordinates = running.materialCoordinates;
            handover.condensedAmplitudes = running.condensedAmplitudes;
            for (const Phase& to : phases) {
                const RopeModel<Dim> swapped = base.withNodeLaw(TractionRopeScene<Dim>::kTraction, to.kind, to.kappa0, to.exponent);
                const RopeModel<Dim> fresh = sc.build(to.kind, to.kappa0, to.exponent);
                SCOPED_TRACE(testing::Message() << "Dim " << Dim << ", axial " << static_cast<int>(axial) << ": "
                                                << static_cast<int>(from.kind) << " (" << from.kappa0 << ", "
                                                << from.exponent << ") -> " << static_cast<int>(to.kind) << " ("
                                                << to.kappa0 << ", " << to.exponent << ")");
                EXPECT_EQ(swapped.nodeKind(1), to.kind);
                EXPECT_EQ(swapped.slipRatio(1), fresh.slipRatio(1));
                EXPECT_EQ(swapped.slipAngleExponent(1), fresh.slipAngleExponent(1));
                EXPECT_EQ(swapped.numExternalCoordinates(), base.numExternalCoordinates());
                EXPECT_EQ(swapped.numStations(), base.numStations());
                // Bit for bit: from a new RopeData, and from the hand-over.
                const std::vector<double> swappedResults = results(swapped, sc, RopeData<Dim>());
                EXPECT_TRUE(swappedResults == results(fresh, sc, RopeData<Dim>()));
                // (Another phase's results are other results.)
                if (to.kind != from.kind || to.kappa0 != from.kappa0 || to.exponent != from.exponent) {
                    EXPECT_FALSE(swappedResults == baseBefore);
                }
                EXPECT_TRUE(results(swapped, sc, handover) == results(fresh, sc, handover));
                // The elements are the base's own objects, not copies.
                for (int j = 0; j < base.numSpans(); ++j) EXPECT_EQ(&swapped.span(j), &base.span(j));
                EXPECT_EQ(&swapped.arc(0), &base.arc(0));
                EXPECT_EQ(&swapped.arc(1), &base.arc(1));
                EXPECT_NE(&fresh.span(0), &base.span(0));
            }
            // The base model is the same as before.
            EXPECT_TRUE(results(base, sc, RopeData<Dim>()) == baseBefore);
            EXPECT_EQ(base.nodeKind(1), from.kind);
        }
    }
}

}  // namespace

TEST(NodeLawSwap, SwappedModelIsTheFreshModelBitForBitPlanar) { swapsEqualFreshModels<2>(); }
TEST(NodeLawSwap, SwappedModelIsTheFreshModelBitForBitSpatial) { swapsEqualFreshModels<3>(); }

// A swap back returns the base's results, and a copy of a model shares its elements too.
TEST(NodeLawSwap, SwapBackIsTheBaseAndCopiesShareTheElements) {
    const TractionRopeScene<2> sc(AxialDynamics::QuasiStatic);
    const RopeModel<2> stick = sc.build(MaterialNode::Driven);
    const RopeModel<2> back = stick.withNodeLaw(1, MaterialNode::Slipping, 1.0, 0.3).withNodeLaw(1, MaterialNode::Driven);
    EXPECT_TRUE(results(back, sc, RopeData<2>()) == results(stick, sc, RopeData<2>()));
    EXPECT_EQ(&back.span(2), &stick.span(2));
    const RopeModel<2> copy = stick;
    EXPECT_EQ(&copy.span(0), &stick.span(0));
    EXPECT_TRUE(results(copy, sc, RopeData<2>()) == results(stick, sc, RopeData<2>()));
}

TEST(NodeLawSwap, BadSwapsAreInvalidArguments) {
    const TractionRopeScene<2> sc(AxialDynamics::Dynamic);
    const RopeModel<2> rope = sc.build(MaterialNode::Driven);
    EXPECT_THROW_MESSAGE(rope.withNodeLaw(0, MaterialNode::Slipping), std::invalid_argument,
                         "RopeModel::withNodeLaw: node 0 is not an interior node");
    EXPECT_THROW_MESSAGE(rope.withNodeLaw(3, MaterialNode::Driven), std::invalid_argument, "node 3 is not an interior node");
    EXPECT_THROW_MESSAGE(rope.withNodeLaw(2, MaterialNode::Slipping), std::invalid_argument,
                         "node 2 is Sliding, asked to be Slipping: a law changes only between Driven and Slipping");
    EXPECT_THROW_MESSAGE(rope.withNodeLaw(1, MaterialNode::Sliding), std::invalid_argument,
                         "node 1 is Driven, asked to be Sliding");
    EXPECT_THROW_MESSAGE(rope.withNodeLaw(1, MaterialNode::Fixed), std::invalid_argument,
                         "RopeModel: interior node 1 cannot be Fixed");
    EXPECT_THROW_MESSAGE(rope.withNodeLaw(1, MaterialNode::Driven, 2.0), std::invalid_argument,
                         "a Driven node has no capstan law (kappa0 = 2, angleExponent = 0 1/rad given");
    EXPECT_THROW_MESSAGE(rope.withNodeLaw(1, MaterialNode::Slipping, 0.0), std::invalid_argument,
                         "RopeModel::withNodeLaw: kappa = 0 must be finite and > 0");
    EXPECT_THROW_MESSAGE(rope.withNodeLaw(1, MaterialNode::Slipping, 1.0, std::nan("")), std::invalid_argument,
                         "RopeModel::withNodeLaw: angleExponent = nan 1/rad must be finite");
    // A sheave on a turning groove has no slipping law.
    SpanOptions o;
    o.axialModes = 2;
    std::vector<SpanModel<3>> spans(2, SpanModel<3>(RopeProperties{0.6, 1e6, 0.0}, o, Eigen::Vector3d(0, -9.81, 0)));
    NodeWrap turning{0.4, 1};
    turning.turningAxis = true;
    const RopeModel<3> boom(spans, 10.0, {MaterialNode::Fixed, MaterialNode::Driven, MaterialNode::Fixed},
                            {NodeWrap{}, turning, NodeWrap{}});
    EXPECT_THROW_MESSAGE(boom.withNodeLaw(1, MaterialNode::Slipping), std::invalid_argument,
                         "RopeModel::withNodeLaw: node 1: a turning groove axis (NodeWrap::turningAxis) is built for "
                         "Sliding and Driven nodes");
}
