// ReevingSubsystem::sampleArc: the rope on the groove of a wrapped deviation sheave, as drawn with
// the spans (sampleSpan). A rope from a Ground anchor down under the sheave of a displaced and
// turned block (wrap sense +1), up over a Ground sheave (-1) and down to a Ground anchor, in the
// plane z = 0.3, with bent spans: the arc points lie on the groove circle in the rope plane, start
// at the arriving span's end and end at the departing span's start, turn in the wrap sense, and
// their chords add up to getArcLength; the same rope described with the opposite plane normal
// (and so opposite senses) gives the same points.
#include "SimbodyReeving/simbody/ReevingSubsystem.h"

#include "support/ExpectThrowMessage.h"

#include <gtest/gtest.h>

#include <Simbody.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <vector>

using SimbodyReeving::DeviationSheave;
using SimbodyReeving::ReevingSubsystem;
using SimbodyReeving::RopeAnchor;
using SimbodyReeving::RopeProperties;
using SimbodyReeving::RopeSpec;
using SimbodyReeving::SheaveModel;
using SimbodyReeving::SpanOptions;
using SimTK::Inertia;
using SimTK::MassProperties;
using SimTK::MobilizedBody;
using SimTK::Stage;
using SimTK::State;
using SimTK::Transform;
using SimTK::Vec3;

namespace {

constexpr double kR = 0.5;       // both sheaves' radius [m]
constexpr double kZ = 0.3;       // the rope plane z = kZ [m]
const Vec3 kBlockStation(0.1, 0.05, kZ);  // the block's sheave centre, block frame [m]
const Vec3 kGroundSheave(1.5, 0, kZ);     // the Ground sheave's centre [m]

// normalSign +1: plane normal +z, senses +1 (under the block's sheave: counter-clockwise about +z)
// and -1 (over the Ground sheave); normalSign -1: the same rope about -z, senses flipped.
struct TwoSheaves {
    SimTK::MultibodySystem system;
    SimTK::SimbodyMatterSubsystem matter{system};
    SimTK::GeneralForceSubsystem forces{system};
    SimTK::Force::Gravity gravity{forces, matter, Vec3(0, -9.81, 0)};
    ReevingSubsystem reeving{system, Vec3(0, -9.81, 0)};
    MobilizedBody::Planar block{matter.updGround(), Transform(),
                                SimTK::Body::Rigid(MassProperties(500, Vec3(0), Inertia(10))), Transform()};
    State state;

    explicit TwoSheaves(int normalSign, SheaveModel model = SheaveModel::Wrapped) {
        RopeSpec rope;
        rope.name = "two sheaves";
        rope.start = RopeAnchor{matter.Ground(), Vec3(0, 0, kZ)};
        DeviationSheave onBlock{block, kBlockStation, kR}, onGround{matter.Ground(), kGroundSheave, kR};
        onBlock.wrapSense = normalSign;
        onGround.wrapSense = -normalSign;
        rope.sheaves = {onBlock, onGround};
        rope.end = RopeAnchor{matter.Ground(), Vec3(2.2, -6, kZ)};
        rope.properties = RopeProperties{0.6205, 16.5e6, 30.9};
        rope.unstretchedLength = 29.0;
        SpanOptions o;
        o.axialModes = 2;
        o.transverseModes = 2;
        rope.spanDefaults = o;
        rope.planeNormal = Vec3(0, 0, normalSign);
        rope.sheaveModel = model;
        reeving.addRope(rope);
        system.realizeTopology();
        // The block 10 m down, off the symmetric place and turned; the spans bent by their modes.
        state = system.getDefaultState();
        block.setQ(state, Vec3(0.3, 0.6, -10.2));  // angle [rad], x, y [m]
        SimTK::Vector q(reeving.getNumModalCoordinates(0));
        for (int j = 0; j < q.size(); ++j) q[j] = 0.02 * std::sin(1.0 + j);  // [m]
        reeving.setModalCoordinates(state, 0, q);
        system.realize(state, Stage::Position);
    }
    Vec3 centre(int node) const {
        return node == 1 ? block.findStationLocationInGround(state, kBlockStation) : kGroundSheave;
    }
};

// Sum of the chords of a polyline [m].
double chordLength(const std::vector<Vec3>& p) {
    double l = 0;
    for (size_t i = 0; i + 1 < p.size(); ++i) l += (p[i + 1] - p[i]).norm();
    return l;
}

}  // namespace

// On the groove circle (|p - c| = R, in the rope plane), from the arriving span's end to the
// departing span's start, every step turning in the wrap sense: under the block's sheave and over
// the Ground one.
TEST(WrappedSheaveDrawing, ArcLiesOnTheGrooveBetweenTheSpans) {
    const TwoSheaves scene(1);
    const ReevingSubsystem& rv = scene.reeving;
    for (int node : {1, 2}) {
        const std::vector<Vec3> arc = rv.sampleArc(scene.state, 0, node, 50);
        ASSERT_EQ(arc.size(), 50u);
        const Vec3 c = scene.centre(node);
        double radius = 0, plane = 0, turn = 1e9;
        for (size_t i = 0; i < arc.size(); ++i) {
            radius = std::max(radius, std::abs((arc[i] - c).norm() - kR));
            plane = std::max(plane, std::abs(arc[i][2] - kZ));
            if (i + 1 < arc.size())  // sense about +z of each step: +1 on the block, -1 on Ground
                turn = std::min(turn, (node == 1 ? 1 : -1) * SimTK::cross(arc[i] - c, arc[i + 1] - c)[2]);
        }
        const Vec3 arrival = rv.sampleSpan(scene.state, 0, node - 1, 2).back();
        const Vec3 departure = rv.sampleSpan(scene.state, 0, node, 2).front();
        const double first = (arc.front() - arrival).norm(), last = (arc.back() - departure).norm();
        const double alpha = rv.getWrapAngle(scene.state, 0, node);
        std::printf("[ node %d ] wrap angle %.6f rad, |p - c| - R up to %.2e m, off the plane %.2e m, "
                    "first point %.2e m, last point %.2e m from the spans' ends\n",
                    node, alpha, radius, plane, first, last);
        EXPECT_LT(radius, 1e-13);  // measured 1.2e-15 (node 1), 2.2e-16 (node 2): round-off
        EXPECT_LT(plane, 1e-13);   // measured 0: the centre projected onto the plane of the spans
        EXPECT_LT(first, 1e-13);   // measured 0: the arc starts at the arriving span's end
        EXPECT_LT(last, 1e-13);    // measured 0, 1.4e-15: l = R alpha and the tangent points agree
        EXPECT_GT(turn, 0.0);      // every step turns in the wrap sense
        // The rope goes under the block's sheave and over the Ground one.
        const Vec3 lowest = *std::min_element(arc.begin(), arc.end(), [](auto& a, auto& b) { return a[1] < b[1]; });
        const Vec3 highest = *std::max_element(arc.begin(), arc.end(), [](auto& a, auto& b) { return a[1] < b[1]; });
        const double extreme = (node == 1 ? lowest[1] : highest[1]) - c[1] - (node == 1 ? -kR : kR);
        std::printf("[ node %d ] lowest / highest point - (c_y -/+ R) = %.2e m\n", node, extreme);
        // Measured 5.0e-5, 1.0e-5: the sampling (R (1 - cos 1.8 deg) = 2.6e-4 at most).
        EXPECT_LT(std::abs(extreme), 1e-3);
    }
}

// The chords of m equal steps add up to 2 m R sin(alpha / (2 m)) = l (1 - alpha^2 / (24 m^2) + ...),
// alpha = l / R, l = getArcLength: they converge to it at second order.
TEST(WrappedSheaveDrawing, ChordsConvergeToTheArcLength) {
    const TwoSheaves scene(1);
    const ReevingSubsystem& rv = scene.reeving;
    for (int node : {1, 2}) {
        const double l = rv.getArcLength(scene.state, 0, node), alpha = l / kR;
        const double e100 = l - chordLength(rv.sampleArc(scene.state, 0, node, 101));
        const double e200 = l - chordLength(rv.sampleArc(scene.state, 0, node, 201));
        const double e2000 = l - chordLength(rv.sampleArc(scene.state, 0, node, 2001));
        // l - 2 m R sin(alpha / (2 m)) to fourth order in alpha / m, m = 100.
        const double a2 = alpha * alpha / 1e4, leading = l * (a2 / 24 - a2 * a2 / 1920);
        std::printf("[ node %d ] l = %.9f m; l - chords = %.3e (100 steps), %.3e (200), %.3e (2000) m; "
                    "ratio 100/200 %.6f; minus its series to alpha^4: %.2e m\n",
                    node, l, e100, e200, e2000, e100 / e200, e100 - leading);
        EXPECT_GT(l, 1.0);  // about a half turn on each sheave (measured 1.5708 and 1.5631 m)
        EXPECT_NEAR(e100 / e200, 4.0, 1e-3);      // measured 3.99996 (second order)
        EXPECT_NEAR(e100, leading, 1e-13);        // measured 4.5e-15, 3.8e-15 (round-off of the sums)
        EXPECT_LT(std::abs(e2000), 1e-5);         // measured 1.6e-7 (both nodes)
        // Two points: the chord between the tangent points.
        const std::vector<Vec3> ends = rv.sampleArc(scene.state, 0, node, 2);
        const double chord = (ends[1] - ends[0]).norm() - 2 * kR * std::sin(0.5 * alpha);
        std::printf("[ node %d ] two points: chord - 2 R sin(alpha / 2) = %.2e m\n", node, chord);
        EXPECT_LT(std::abs(chord), 1e-14);  // measured 2.2e-16
    }
}

// The same rope described about -z with both senses flipped: the same points.
TEST(WrappedSheaveDrawing, OppositePlaneNormalGivesTheSameArc) {
    const TwoSheaves plus(1), minus(-1);
    double worst = 0;
    for (int node : {1, 2}) {
        const std::vector<Vec3> a = plus.reeving.sampleArc(plus.state, 0, node, 30);
        const std::vector<Vec3> b = minus.reeving.sampleArc(minus.state, 0, node, 30);
        for (size_t i = 0; i < a.size(); ++i) worst = std::max(worst, (a[i] - b[i]).norm());
    }
    std::printf("largest distance between the arcs about +z and -z: %.2e m\n", worst);
    EXPECT_LT(worst, 1e-12);  // measured 0
}

TEST(WrappedSheaveDrawing, BadInputIsRejected) {
    const TwoSheaves scene(1);
    const ReevingSubsystem& rv = scene.reeving;
    const State& s = scene.state;
    EXPECT_THROW_MESSAGE(rv.sampleArc(s, 1, 1, 10), std::invalid_argument,
                         "ReevingSubsystem: rope index = 1 is outside 0..0");
    EXPECT_THROW_MESSAGE(rv.sampleArc(s, -1, 1, 10), std::invalid_argument,
                         "ReevingSubsystem: rope index = -1 is outside 0..0");
    EXPECT_THROW_MESSAGE(rv.sampleArc(s, 0, 4, 10), std::invalid_argument,
                         "ReevingSubsystem: node index = 4 is outside 0..3");
    EXPECT_THROW_MESSAGE(rv.sampleArc(s, 0, -1, 10), std::invalid_argument,
                         "ReevingSubsystem: node index = -1 is outside 0..3");
    for (int anchor : {0, 3})
        EXPECT_THROW_MESSAGE(rv.sampleArc(s, 0, anchor, 10), std::invalid_argument,
                             "ReevingSubsystem: sampleArc: rope 'two sheaves' node " + std::to_string(anchor) +
                                 " is not a wrapped sheave (SheaveModel::Wrapped): it has no arc");
    for (int n : {1, 0, -3})
        EXPECT_THROW_MESSAGE(rv.sampleArc(s, 0, 1, n), std::invalid_argument,
                             "ReevingSubsystem: sampleArc: numPoints = " + std::to_string(n) + " must be >= 2");
    // The same rope on point sheaves: no arcs (and no length on the grooves).
    const TwoSheaves point(1, SheaveModel::Point);
    EXPECT_EQ(point.reeving.getArcLength(point.state, 0, 1), 0.0);
    EXPECT_THROW_MESSAGE(point.reeving.sampleArc(point.state, 0, 1, 10), std::invalid_argument,
                         "ReevingSubsystem: sampleArc: rope 'two sheaves' node 1 is not a wrapped sheave");
}
