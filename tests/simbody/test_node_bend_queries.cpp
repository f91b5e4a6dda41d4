// What a node does to the rope it carries, asked of the ReevingSubsystem without asking the node's
// kind (each kind answers in its own unit, plugin/simbody/src/nodes/): the radius the rope bends
// over (getNodeRadius), the material interval of rope on the node (getNodeMaterialInterval), the
// axis the rope turns about there (getNodeBendAxis) and the rope stored at the node
// (getStoredRope). Checked against hand-worked senses on a rope over every node kind: a drum at
// the origin, a DeviationSheave at (0, 5), a TurningSheave at (2, 0), a TractionSheave at (4, 5),
// an anchor at (6, 0) (the rope zigzags: clockwise, counter-clockwise, clockwise about +z), and a
// second rope from an anchor at (0, 5) to a drum at its end at (3, 0); planar and spatial, point
// and wrapped sheaves.
#include "SimbodyReeving/simbody/ReevingSubsystem.h"
#include "support/ExpectThrowMessage.h"

#include <gtest/gtest.h>

#include <Simbody.h>

#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>
#include <stdexcept>

using namespace SimbodyReeving;
using SimTK::MobilizedBody;
using SimTK::Stage;
using SimTK::State;
using SimTK::Transform;
using SimTK::Vec3;

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

SimTK::Body::Rigid wheel() { return SimTK::Body::Rigid(SimTK::MassProperties(1.0, Vec3(0), SimTK::Inertia(0.01))); }

/// The two ropes on Ground and on Pins about Ground's z (at their default angles, 0): rope 0 from
/// a drum (radius 0.25 m, 30 m stored, payoutSense -1) over A (DeviationSheave, radius 0.2 m,
/// wrapSense -1, axis z), B (TurningSheave, radius 0.2 m, sense -1) and C (TractionSheave, radius
/// 0.2 m, sense +1) to an anchor; rope 1 from an anchor to a drum at its end (radius 0.25 m, 12 m
/// stored, payoutSense +1). Planar (normal z) unless `spatial`.
struct BendScene {
    SimTK::MultibodySystem system;
    SimTK::SimbodyMatterSubsystem matter{system};
    SimTK::GeneralForceSubsystem forces{system};
    MobilizedBody::Pin drum{matter.Ground(), Transform(), wheel(), Transform()};
    MobilizedBody::Pin b{matter.Ground(), Transform(Vec3(2, 0, 0)), wheel(), Transform()};
    MobilizedBody::Pin c{matter.Ground(), Transform(Vec3(4, 5, 0)), wheel(), Transform()};
    MobilizedBody::Pin endDrum{matter.Ground(), Transform(Vec3(3, 0, 0)), wheel(), Transform()};
    ReevingSubsystem reeving{system, Vec3(0, -9.81, 0)};
    State state;

    BendScene(SheaveModel model, bool spatial) {
        const double chord = std::sqrt(29.0);  // A-B, B-C and C-anchor [m]
        RopeSpec r0;
        r0.name = "zigzag";
        r0.start = WinchDrum{drum, 0.25, 30.0, -1};
        DeviationSheave a{matter.Ground(), Vec3(0, 5, 0), 0.2};
        a.wrapSense = -1;
        a.axis = Vec3(0, 0, 1);
        TractionSheave traction{c, 0.2, 0.3, 0.0, 5.0 + 2 * chord, +1};
        r0.sheaves = {a, TurningSheave{b, 0.2, 5.0 + chord, -1}, traction};
        r0.end = RopeAnchor{matter.Ground(), Vec3(6, 0, 0)};
        r0.unstretchedLength = 5.0 + 3 * chord - 0.05;
        RopeSpec r1;
        r1.name = "to a drum";
        r1.start = RopeAnchor{matter.Ground(), Vec3(0, 5, 0)};
        r1.end = WinchDrum{endDrum, 0.25, 12.0, +1};
        r1.unstretchedLength = std::sqrt(34.0) - 0.05;
        for (RopeSpec* r : {&r0, &r1}) {
            r->properties = RopeProperties{1e-3, 1e7, 0.0};
            r->spanDefaults.axialModes = 0;
            r->spanDefaults.transverseModes = 0;
            r->sheaveModel = model;
            if (!spatial) r->planeNormal = Vec3(0, 0, 1);
            reeving.addRope(*r);
        }
        system.realizeTopology();
        state = system.getDefaultState();
        system.realize(state, Stage::Position);
    }
};

const char* modelName(SheaveModel m) { return m == SheaveModel::Wrapped ? "wrapped" : "point"; }

}  // namespace

TEST(NodeBendQueries, RadiusIsTheGroovesAndZeroAtAnAnchor) {
    BendScene scene(SheaveModel::Point, false);
    const double expected[] = {0.25, 0.2, 0.2, 0.2, 0.0};
    for (int k = 0; k < 5; ++k) EXPECT_EQ(scene.reeving.getNodeRadius(0, k), expected[k]) << "node " << k;
    EXPECT_EQ(scene.reeving.getNodeRadius(1, 0), 0.0);
    EXPECT_EQ(scene.reeving.getNodeRadius(1, 1), 0.25);
}

// A sheave holds the rope from where it arrives (the end of span k - 1) to where it leaves (the
// start of span k): one point on a point sheave, the arc R alpha on a wrapped one; a drum holds
// the rope on its side of the tangent point without bound; an anchor holds the rope's end.
TEST(NodeBendQueries, MaterialIntervalIsTheRopeOnTheNode) {
    for (SheaveModel model : {SheaveModel::Point, SheaveModel::Wrapped})
        for (bool spatial : {false, true}) {
            BendScene scene(model, spatial);
            const ReevingSubsystem& rv = scene.reeving;
            const State& s = scene.state;
            const auto start = rv.getNodeMaterialInterval(s, 0, 0);
            EXPECT_EQ(start.first, -kInf);
            EXPECT_EQ(start.second, rv.getSpanMaterialRange(s, 0, 0).first);
            double arcs = 0;
            for (int k = 1; k <= 3; ++k) {
                const auto [lower, upper] = rv.getNodeMaterialInterval(s, 0, k);
                EXPECT_EQ(lower, rv.getSpanMaterialRange(s, 0, k - 1).second) << "node " << k;
                EXPECT_EQ(upper, rv.getSpanMaterialRange(s, 0, k).first) << "node " << k;
                EXPECT_EQ(lower, rv.getMaterialCoordinate(s, 0, k)) << "node " << k;
                EXPECT_EQ(upper - lower, rv.getArcLength(s, 0, k)) << "node " << k;
                if (model == SheaveModel::Point) {
                    EXPECT_EQ(upper, lower) << "node " << k;
                } else {
                    EXPECT_GT(upper - lower, 0.0) << "node " << k;
                }
                arcs += upper - lower;
            }
            const auto end = rv.getNodeMaterialInterval(s, 0, 4);
            EXPECT_EQ(end.first, rv.getMaterialCoordinate(s, 0, 4));
            EXPECT_EQ(end.second, end.first);
            EXPECT_DOUBLE_EQ(end.first, rv.getRopeSpec(0).unstretchedLength);
            const auto anchor = rv.getNodeMaterialInterval(s, 1, 0);
            EXPECT_EQ(anchor.first, 0.0);
            EXPECT_EQ(anchor.second, 0.0);
            const auto drumEnd = rv.getNodeMaterialInterval(s, 1, 1);
            EXPECT_EQ(drumEnd.first, rv.getSpanMaterialRange(s, 1, 0).second);
            EXPECT_EQ(drumEnd.second, kInf);
            std::printf("[ bend ] %s %s: drum (-inf, %.6f] m, sheaves' arcs %.6f m in all, end drum [%.6f, inf) m\n",
                        spatial ? "spatial" : "planar", modelName(model), start.second, arcs, drumEnd.first);
        }
}

// The rope runs from its start to its end; its bend axis at a node is the unit axis it turns
// about there (right hand). Rope 0: the drum, paying out with payoutSense -1, winds the rope
// clockwise about +z; at A the rope turns from up to down-right (clockwise), at B from
// down-right to up-right (counter-clockwise), at C back to down-right (clockwise). Point sheaves:
// the chords' turn; wrapped: A's wrapSense -1 about its axis +z, B's -sense (+1) and C's -sense
// (-1) about their pin axes +z. An end drum with payoutSense +1 winds clockwise as the rope
// arrives. An anchor does not bend the rope: zero.
TEST(NodeBendQueries, BendAxisIsTheTurnOfTheRopeOverTheNode) {
    const Vec3 cw(0, 0, -1), ccw(0, 0, 1);
    for (SheaveModel model : {SheaveModel::Point, SheaveModel::Wrapped})
        for (bool spatial : {false, true}) {
            BendScene scene(model, spatial);
            const ReevingSubsystem& rv = scene.reeving;
            const Vec3 expected[] = {cw, cw, ccw, cw, Vec3(0)};
            double worst = 0;
            for (int k = 0; k < 5; ++k) {
                const Vec3 axis = rv.getNodeBendAxis(scene.state, 0, k);
                worst = std::max(worst, (axis - expected[k]).norm());
                EXPECT_LT((axis - expected[k]).norm(), 1e-12) << "node " << k << ": " << axis;
            }
            EXPECT_EQ(rv.getNodeBendAxis(scene.state, 1, 0), Vec3(0));
            const Vec3 drumEnd = rv.getNodeBendAxis(scene.state, 1, 1);
            EXPECT_LT((drumEnd - cw).norm(), 1e-12) << drumEnd;
            std::printf("[ bend ] %s %s: bend axes off the hand-worked ones by at most %.3g\n",
                        spatial ? "spatial" : "planar", modelName(model), worst);
        }
}

// The rope on a drum: ropeOnDrum + s_0 at a start drum, ropeOnDrum + L - s_N at an end drum (the
// drum's own query, WinchDrumHandle::getRopeOnDrum); no node but a drum stores rope.
TEST(NodeBendQueries, StoredRopeIsTheDrumsAndZeroElsewhere) {
    for (SheaveModel model : {SheaveModel::Point, SheaveModel::Wrapped}) {
        BendScene scene(model, false);
        const ReevingSubsystem& rv = scene.reeving;
        const State& s = scene.state;
        const double start = rv.getStoredRope(s, 0, 0), end = rv.getStoredRope(s, 1, 1);
        EXPECT_EQ(start, rv.getRope(0).getWinchDrum(0).getRopeOnDrum(s));
        EXPECT_DOUBLE_EQ(start, 30.0 + rv.getMaterialCoordinate(s, 0, 0));
        EXPECT_EQ(end, rv.getRope(1).getWinchDrum(1).getRopeOnDrum(s));
        EXPECT_DOUBLE_EQ(end, 12.0 + rv.getRopeSpec(1).unstretchedLength - rv.getMaterialCoordinate(s, 1, 1));
        for (int k = 1; k <= 4; ++k) EXPECT_EQ(rv.getStoredRope(s, 0, k), 0.0) << "node " << k;
        EXPECT_EQ(rv.getStoredRope(s, 1, 0), 0.0);
        std::printf("[ bend ] %s: %.6f m on the start drum, %.6f m on the end drum\n", modelName(model), start, end);
    }
}

TEST(NodeBendQueries, BadIndicesAndStagesAreRejected) {
    BendScene scene(SheaveModel::Point, false);
    const ReevingSubsystem& rv = scene.reeving;
    const State& s = scene.state;
    EXPECT_THROW_MESSAGE(rv.getNodeRadius(2, 0), std::invalid_argument, "rope index = 2 is outside 0..1");
    EXPECT_THROW_MESSAGE(rv.getNodeRadius(0, 5), std::invalid_argument, "node index = 5 is outside 0..4");
    EXPECT_THROW_MESSAGE(rv.getNodeMaterialInterval(s, -1, 0), std::invalid_argument, "rope index = -1 is outside 0..1");
    EXPECT_THROW_MESSAGE(rv.getNodeMaterialInterval(s, 1, 2), std::invalid_argument, "node index = 2 is outside 0..1");
    EXPECT_THROW_MESSAGE(rv.getNodeBendAxis(s, 2, 0), std::invalid_argument, "rope index = 2 is outside 0..1");
    EXPECT_THROW_MESSAGE(rv.getNodeBendAxis(s, 0, -1), std::invalid_argument, "node index = -1 is outside 0..4");
    EXPECT_THROW_MESSAGE(rv.getStoredRope(s, 2, 0), std::invalid_argument, "rope index = 2 is outside 0..1");
    EXPECT_THROW_MESSAGE(rv.getStoredRope(s, 0, 5), std::invalid_argument, "node index = 5 is outside 0..4");
    State fresh = scene.system.getDefaultState();
    scene.system.realize(fresh, Stage::Instance);
    EXPECT_THROW_MESSAGE(rv.getNodeMaterialInterval(fresh, 0, 1), std::logic_error,
                         "getNodeMaterialInterval: realize the state to Stage::Position first");
    EXPECT_THROW_MESSAGE(rv.getNodeBendAxis(fresh, 0, 1), std::logic_error,
                         "getNodeBendAxis: realize the state to Stage::Position first");
    EXPECT_THROW_MESSAGE(rv.getStoredRope(fresh, 0, 0), std::logic_error,
                         "getStoredRope: realize the state to Stage::Position first");
}
