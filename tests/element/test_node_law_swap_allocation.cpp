// What RopeModel::withNodeLaw allocates: the node laws' layout (index maps, chain order, band
// offsets), not the spans, their condensation kernels or the groove arcs, which it shares with the
// model it came from. Measured with the counting malloc (tests/support/CountingMalloc.h) against
// copying the elements and building the model from scratch; and the swapped model's evaluations,
// like any model's, allocate nothing once their workspace is sized (both laws of the traction
// sheave, on the traction rope of TractionRopeScene: wrapped drum with stored rope, wrapped sheave;
// evaluated from its external coordinates).
#include "SimbodyReeving/element/RopeModel.h"
#include "SimbodyReeving/element/WrapStationMap.h"
#include "support/TractionRopeScene.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <vector>

#include "support/CountingMalloc.h"  // (defines malloc and operator new: this executable only)

using namespace SimbodyReeving;
using SimbodyReevingTest::TractionRopeScene;

namespace {

struct Count {
    long calls = 0, bytes = 0;
};
template <class F>
Count counted(const F& f) {
    const long calls = gAllocations.load(), bytes = gAllocatedBytes.load();
    f();
    return {gAllocations.load() - calls, gAllocatedBytes.load() - bytes};
}

template <int Dim>
void swapAllocatesTheLayoutOnly(AxialDynamics axial) {
    const TractionRopeScene<Dim> sc(axial);
    const RopeModel<Dim> base = sc.build(MaterialNode::Driven);
    const Count elements = counted([&] {
        std::vector<SpanModel<Dim>> spans;
        for (int j = 0; j < base.numSpans(); ++j) spans.push_back(base.span(j));
    });
    const Count copy = counted([&] { const RopeModel<Dim> c = base; });
    const Count fresh = counted([&] { const RopeModel<Dim> m = sc.build(MaterialNode::Slipping, 1.0, 0.3); });
    const Count swap = counted([&] { const RopeModel<Dim> m = base.withNodeLaw(1, MaterialNode::Slipping, 1.0, 0.3); });
    std::printf("Dim %d, axial %d: withNodeLaw %ld allocations, %ld bytes; a copy of the model %ld, %ld; "
                "from scratch %ld, %ld; the spans alone %ld, %ld\n",
                Dim, static_cast<int>(axial), swap.calls, swap.bytes, copy.calls, copy.bytes, fresh.calls, fresh.bytes,
                elements.calls, elements.bytes);
    // withNodeLaw is a copy of the model's node tables (the copy shares the elements) and a new
    // layout: fewer allocations and bytes than building from scratch less the spans' copy (so no
    // span is copied; nor are the kernels and arcs, which building from scratch makes too).
    EXPECT_LT(swap.calls, fresh.calls - elements.calls);
    EXPECT_LT(swap.bytes, fresh.bytes - elements.bytes);
}

// Allocations of 10 evaluations of the rope at moving stations after a warm-up, from the external
// coordinates (the station map's x and xdot, evaluated before counting: the map and the reduction
// to the stations, RopeModel's NodeMatrix forms, allocate as they do for any rope with wrapped
// nodes, 9 times per computeDynamics measured).
template <int Dim>
long allocationsPerEvaluation(const RopeModel<Dim>& rope, const TractionRopeScene<Dim>& sc) {
    const Eigen::VectorXd qm = TractionRopeScene<Dim>::modal(rope, 1e-4, 0.3), qmd = TractionRopeScene<Dim>::modal(rope, 1e-3, 1.1);
    const WrapStationMap<Dim> map(rope);
    std::vector<WrapStationMapData> maps(11);
    Eigen::VectorXd Y(map.numStationCoordinates()), Ydot(map.numStationCoordinates());
    for (int k = 0; k < 11; ++k) {
        for (int n = 0; n < rope.numStations(); ++n) {
            Y.template segment<Dim>(Dim * n) = sc.stations.col(n) + 1e-4 * k * sc.stationRates.col(n);
            Ydot.template segment<Dim>(Dim * n) = sc.stationRates.col(n);
        }
        Y.tail(2) = sc.drivenS + 1e-4 * k * sc.drivenSdot;
        Ydot.tail(2) = sc.drivenSdot;
        map.evaluate(Y, Ydot, maps[k]);
    }
    RopeData<Dim> d;
    Eigen::VectorXd qdd;
    const Eigen::VectorXd xdd = Eigen::VectorXd::Constant(rope.numExternalCoordinates(), 0.1);
    auto evaluate = [&](const WrapStationMapData& m) {
        rope.solveDependentCoordinatesFromExternal(m.x, qm, d);
        rope.computeDynamicsFromExternal(m.x, m.xdot, qm, qmd, d);
        rope.modalAccelerations(d, xdd, qdd);
        rope.recoverInertialStrain(d, xdd, qdd);
    };
    evaluate(maps[0]);
    return counted([&] {
               for (int k = 1; k < 11; ++k) evaluate(maps[k]);
           })
        .calls;
}

}  // namespace

TEST(NodeLawSwapAllocation, SwapAllocatesTheLayoutNotTheElements) {
    for (AxialDynamics axial : {AxialDynamics::Dynamic, AxialDynamics::QuasiStatic}) {
        swapAllocatesTheLayoutOnly<2>(axial);
        swapAllocatesTheLayoutOnly<3>(axial);
    }
}

TEST(NodeLawSwapAllocation, SwappedModelsEvaluateWithoutAllocating) {
    for (AxialDynamics axial : {AxialDynamics::Dynamic, AxialDynamics::QuasiStatic}) {
        const TractionRopeScene<2> planar(axial);
        const RopeModel<2> stick = planar.build(MaterialNode::Driven);
        EXPECT_EQ(allocationsPerEvaluation(stick, planar), 0);
        EXPECT_EQ(allocationsPerEvaluation(stick.withNodeLaw(1, MaterialNode::Slipping, 1.0, 0.3), planar), 0);
        const TractionRopeScene<3> spatial(axial);
        const RopeModel<3> slip = spatial.build(MaterialNode::Slipping, 1.0, 0.3);
        EXPECT_EQ(allocationsPerEvaluation(slip, spatial), 0);
        EXPECT_EQ(allocationsPerEvaluation(slip.withNodeLaw(1, MaterialNode::Driven), spatial), 0);
    }
}
