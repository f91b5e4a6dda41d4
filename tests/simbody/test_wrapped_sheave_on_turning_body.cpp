// A wrapped TurningSheave at the tip of a boom that luffs at a prescribed rate (a jib head sheave):
// the rope comes from an anchor at the boom's foot, runs over the tip sheave's groove and falls to
// a load. The sheave turns freely on its pin and grips the rope, so the rope on its groove moves
// with the sheave, whose angle is its pin's plus the boom's: a material point of the rope on the
// groove stays at the same place of the sheave. The rope's length, measured from the geometry (the straight spans' lengths over their
// stretch, the arc between the tangent points), stays the rope's; the energy changes by the drive's
// work.
#include "SimbodyReeving/simbody/MotionWorkMeter.h"
#include "SimbodyReeving/simbody/ReevingSubsystem.h"

#include <gtest/gtest.h>

#include <Simbody.h>

#include <cmath>
#include <cstdio>
#include <memory>

using namespace SimTK;
namespace sr = SimbodyReeving;

namespace {

constexpr double kG = 9.81;
constexpr double kR = 0.3;     // sheave radius [m]
constexpr double kBoom = 6.0;  // [m]
constexpr double kEA = 16.5e6;

struct LuffingBoom {
    MultibodySystem system;
    SimbodyMatterSubsystem matter{system};
    GeneralForceSubsystem forces{system};
    Force::Gravity gravity{forces, matter, -YAxis, kG};
    std::unique_ptr<sr::ReevingSubsystem> reeving;
    std::unique_ptr<sr::MotionWorkMeter> meter;
    MobilizedBody::Pin boom, sheave;
    MobilizedBody::Planar load;
    State state;

    // The boom luffs from 0.6 rad by `turn` [rad] over `time` [s], smoothly from rest to rest:
    // its angle 0.6 + turn / 2 (1 - cos(pi t / time)) (the pin's q = -turn / 2 cos(pi t / time)
    // after an inboard frame turned by 0.6 + turn / 2).
    // spatial: the rope has no plane normal and comes from an anchor 0.4 m off the boom's plane
    // (a fleet angle where it arrives on the tip sheave).
    LuffingBoom(double turn, double time, bool spatial = false) {
        boom = MobilizedBody::Pin(matter.Ground(), Transform(Rotation(0.6 + 0.5 * turn, ZAxis)),
                                  Body::Rigid(MassProperties(800, Vec3(0.5 * kBoom, 0, 0), Inertia(Vec3(1, 7201, 7201)))),
                                  Transform());
        Motion::Sinusoid(boom, Motion::Position, 0.5 * turn, Pi / time, -0.5 * Pi);
        sheave = MobilizedBody::Pin(boom, Transform(Vec3(kBoom, 0, 0)),
                                    Body::Rigid(MassProperties(30, Vec3(0), Inertia(0.5))), Transform());
        load = MobilizedBody::Planar(matter.Ground(), Transform(),
                                     Body::Rigid(MassProperties(500, Vec3(0), Inertia(5))), Transform());
        reeving = std::make_unique<sr::ReevingSubsystem>(system, Vec3(0, -kG, 0));
        meter = std::make_unique<sr::MotionWorkMeter>(system);
        sr::RopeSpec rope;
        rope.sheaveModel = sr::SheaveModel::Wrapped;
        rope.planeNormal = spatial ? Vec3(0) : Vec3(0, 0, 1);
        const Vec3 anchor(0, 0.8, spatial ? 0.4 : 0.0);
        rope.properties = {0.6205, kEA, 0.0};
        rope.spanDefaults.axialModes = 0;  // straight spans of uniform strain: their material is
        rope.spanDefaults.transverseModes = 0;  // their length over their stretch
        rope.start = sr::RopeAnchor{matter.Ground(), anchor};
        sr::TurningSheave tip;
        tip.body = sheave;
        tip.radius = kR;
        tip.sense = 1;  // over the top from the foot, down the far side: clockwise about +z
        rope.end = sr::RopeAnchor{load, Vec3(0)};
        // The tip at 6 (cos 0.6, sin 0.6) = (4.95, 3.39); the load 5 m under its far side.
        const Vec3 tipPoint(kBoom * std::cos(0.6), kBoom * std::sin(0.6), 0);
        rope.unstretchedLength = (tipPoint + Vec3(0, kR, 0) - anchor).norm() + 0.5 * Pi * kR + 5.0;
        // s_ref: the material at the groove's top when the sheave's own angle is 0 (its pin's plus
        // the boom's turn, 0.6 rad at the start): the anchor's span about taut then.
        tip.materialCoordinateAtZeroAngle = (tipPoint + Vec3(0, kR, 0) - anchor).norm() - tip.sense * kR * 0.6;
        rope.sheaves = {tip};
        reeving->addRope(rope);
        system.realizeTopology();
        state = system.getDefaultState();
        boom.setOneQ(state, 0, -0.5 * turn);
        load.setQToFitTranslation(state, tipPoint + Vec3(kR, -5.0, 0));
    }
};

// The material coordinate's place on the groove: the point of the arc that holds material s
// (GrooveArc: from T_in, R per unit of material, about the groove's centre), in the sheave's frame.
Vec3 materialPointOnSheave(const LuffingBoom& b, const State& s, double material) {
    const std::vector<Vec3> arc = b.reeving->sampleArc(s, 0, 1, 2);  // T_in and T_out
    const double sIn = b.reeving->getMaterialCoordinate(s, 0, 1);
    const Vec3 c = b.sheave.getBodyOriginLocation(s);
    const Vec3 d = arc.front() - c;
    const double theta = (material - sIn) / kR;  // clockwise (sigma = -1) about +z
    const Vec3 w = cross(Vec3(0, 0, -1), d);
    const Vec3 p = c + std::cos(theta) * d + std::sin(theta) * w;
    return b.sheave.findStationAtGroundPoint(s, p);
}

// The rope's length from the geometry: each straight span's length over its stretch
// sqrt(1 + 2 eps) (eps = P / EA, Green's strain: uniform without modes), plus the arc R alpha
// with alpha the angle from T_in to T_out about the sheave's centre (clockwise).
double ropeLengthFromGeometry(const LuffingBoom& b, const State& s) {
    double length = 0;
    for (int j = 0; j < 2; ++j) {
        const std::vector<Vec3> ends = b.reeving->sampleSpan(s, 0, j, 2);
        const auto range = b.reeving->getSpanMaterialRange(s, 0, j);
        const double eps = b.reeving->getAxialForce(s, 0, j, 0.5 * (range.first + range.second)) / kEA;
        length += (ends[1] - ends[0]).norm() / std::sqrt(1 + 2 * eps);
    }
    const Vec3 c = b.sheave.getBodyOriginLocation(s);
    const Vec3 in = b.reeving->sampleSpan(s, 0, 0, 2).back() - c, out = b.reeving->sampleSpan(s, 0, 1, 2).front() - c;
    double alpha = -std::atan2(cross(in, out)[2], dot(in, out));  // clockwise
    if (alpha < 0) alpha += 2 * Pi;
    return length + kR * alpha;
}

}  // namespace

// Luffing up by 0.3 rad in 6 s, from rest to rest: the material point at the middle of the
// groove's rope stays put on the sheave (measured 1.3e-15 m; bound 1e-13 m; a groove whose grip
// followed the pin angle alone would let the rope slide R times the boom's turn, 0.09 m); the
// rope's length from the geometry equals its unstretched length (both spans stay taut; measured
// 3e-16, bound 1e-14 relative); T + U changes by the drive's work (measured 2e-10 J of 1.2e4 J,
// bound 1e-12 of the work). The same with a spatial rope from an anchor off the boom's plane
// (a fleet angle of several degrees at the tip sheave, whose axis turns about itself as the boom
// luffs).
TEST(WrappedSheaveOnTurningBody, JibHeadSheaveCarriesTheRopeWithTheBoom) {
  for (bool spatial : {false, true}) {
    LuffingBoom b(0.3, 6.0, spatial);
    ASSERT_LE(b.reeving->findStaticEquilibrium(b.state, 1e-12), 1e-12);
    RungeKuttaMersonIntegrator integ(b.system);
    integ.setAccuracy(1e-10);
    TimeStepper ts(b.system, integ);
    ts.initialize(b.state);
    const State& s0 = integ.getState();
    b.system.realize(s0, Stage::Velocity);
    const double e0 = b.reeving->calcMechanicalEnergy(s0), w0 = b.meter->getWork(s0);
    const double sMid = 0.5 * (b.reeving->getMaterialCoordinate(s0, 0, 1) + b.reeving->getSpanMaterialRange(s0, 0, 1).first);
    const Vec3 point0 = materialPointOnSheave(b, s0, sMid);
    const double L = b.reeving->getRopeSpec(0).unstretchedLength;
    double slide = 0, length = 0, energy = 0, work = 0, lift = 0;
    const double y0 = b.load.getBodyOriginLocation(s0)[1];
    for (int i = 1; i <= 60; ++i) {
        ts.stepTo(0.1 * i);
        const State& s = integ.getState();
        b.system.realize(s, Stage::Velocity);
        slide = std::max(slide, (materialPointOnSheave(b, s, sMid) - point0).norm());
        length = std::max(length, std::abs(ropeLengthFromGeometry(b, s) - L) / L);
        work = b.meter->getWork(s) - w0;
        energy = std::max(energy, std::abs(b.reeving->calcMechanicalEnergy(s) - e0 - work));
        lift = b.load.getBodyOriginLocation(s)[1] - y0;
    }
    std::printf("luffing boom (%s rope), jib head sheave: rope point on the groove moved %.2e m; rope length from the "
                "geometry %.2e of L; E - E0 - W %.2e J of W = %.1f J; load lifted %.3f m\n",
                spatial ? "spatial" : "planar", slide, length, energy, work, lift);
    if (spatial) {
        EXPECT_GT(std::abs(b.reeving->getFleetAngles(integ.getState(), 0, 0).second), 3 * Pi / 180);
    }
    EXPECT_GT(lift, 1.0);
    EXPECT_LT(slide, 1e-13);
    EXPECT_LT(length, 1e-14);
    EXPECT_LT(energy, 1e-12 * std::abs(work));
}
}
