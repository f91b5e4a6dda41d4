// A WinchDrum with SheaveModel::Wrapped: the rope leaves the drum at its groove's tangent point
// and rolls on and off the drum as its fall swings. A held drum (Motion::Steady 0: no work) with a
// payload swinging on the rope: the rope's length (the span's material plus the rope stored on the
// drum) is conserved while the tangent point rolls, and so is the energy.
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
constexpr double kR = 0.25;       // drum radius [m]
constexpr double kStored = 5.0;   // rope stored up to the drum's top at pin angle 0 [m]

struct SwingingLoad {
    MultibodySystem system;
    SimbodyMatterSubsystem matter{system};
    GeneralForceSubsystem forces{system};
    Force::Gravity gravity{forces, matter, -YAxis, kG};
    std::unique_ptr<sr::ReevingSubsystem> reeving;
    MobilizedBody::Pin drum;
    MobilizedBody::Planar load;
    State state;

    SwingingLoad() {
        drum = MobilizedBody::Pin(matter.Ground(), Transform(), Body::Rigid(MassProperties(20, Vec3(0), Inertia(0.6))),
                                  Transform());
        Motion::Steady(drum, 0.0);
        load = MobilizedBody::Planar(matter.Ground(), Transform(),
                                     Body::Rigid(MassProperties(150, Vec3(0), Inertia(4))), Transform());
        reeving = std::make_unique<sr::ReevingSubsystem>(system);
        sr::RopeSpec rope;
        rope.sheaveModel = sr::SheaveModel::Wrapped;
        sr::WinchDrum d;
        d.body = drum;
        d.radius = kR;
        d.ropeOnDrum = kStored;
        d.payoutSense = 1;  // sigma = +1: the rope unwinds counter-clockwise off the drum's left side
        rope.start = d;
        rope.end = sr::RopeAnchor{load, Vec3(0)};
        rope.properties = {1.2, 2e7, 0.0, false};
        rope.unstretchedLength = 0.5 * Pi * kR + 4.0;  // a quarter turn to the left tangent point, 4 m down
        rope.spanDefaults.axialModes = 1;
        rope.spanDefaults.transverseModes = 2;
        rope.planeNormal = Vec3(0, 0, 1);
        reeving->addRope(rope);
        system.realizeTopology();
        state = system.getDefaultState();
        // The load 4 m under the drum's left side, pulled 0.8 m out to the left (the rope's chord
        // about its length: taut to within the tangent point's roll), at rest: it swings, and the
        // rope rolls on and off the held drum with its fall.
        load.setQ(state, Vec3(0, -kR - 0.8, -std::sqrt(16.0 - 0.64)));
        system.realize(state, Stage::Velocity);
    }
};

}  // namespace

// Over 2 s of swing (the fall turning by about +-0.2 rad, the tangent point rolling round the
// drum with it): the rope stored plus the span's material equals the rope's length plus
// ropeOnDrum (measured 1.8e-15 m; bound 1e-12 m), the stored rope changes by R times the fall's
// turn (0.10 m at most; the two agree to 8.2e-16 m, bound 1e-9 m), and the energy drifts by
// 4.6e-10 of the largest kinetic energy (RK-Merson 1e-9; bound 1e-8).
TEST(WrappedDrum, HeldDrumAndSwingingLoadKeepLengthAndEnergy) {
    SwingingLoad s;
    const double e0 = s.reeving->calcMechanicalEnergy(s.state);
    RungeKuttaMersonIntegrator integ(s.system);
    integ.setAccuracy(1e-9);
    TimeStepper ts(s.system, integ);
    ts.initialize(s.state);
    double worstLength = 0, worstEnergy = 0, largestKinetic = 0, rolled = 0, worstRoll = 0;
    const double stored0 = s.reeving->getRopeOnDrum(s.state, 0, 0);
    auto lean = [&](const State& st) {  // the fall's angle from vertical
        const std::vector<Vec3> ends = s.reeving->sampleSpan(st, 0, 0, 2);
        const Vec3 d = ends[1] - ends[0];
        return std::atan2(d[0], -d[1]);
    };
    const double lean0 = lean(s.state);
    for (int i = 1; i <= 100; ++i) {
        ts.stepTo(0.02 * i);
        const State& st = integ.getState();
        s.system.realize(st, Stage::Velocity);
        const auto range = s.reeving->getSpanMaterialRange(st, 0, 0);
        const double stored = s.reeving->getRopeOnDrum(st, 0, 0);
        worstLength = std::max(worstLength, std::abs(stored + range.second - range.first -
                                                     (s.reeving->getRopeSpec(0).unstretchedLength + kStored)));
        const double kinetic = s.system.calcKineticEnergy(st) + s.reeving->calcRopeKineticEnergy(st);
        largestKinetic = std::max(largestKinetic, kinetic);
        worstEnergy = std::max(worstEnergy, std::abs(s.reeving->calcMechanicalEnergy(st) - e0));
        rolled = std::max(rolled, std::abs(stored - stored0));
        // The held drum's rope rolls with the fall: |stored - stored0| = R |lean - lean0|.
        worstRoll = std::max(worstRoll, std::abs(std::abs(stored - stored0) - kR * std::abs(lean(st) - lean0)));
    }
    std::printf("wrapped drum: length %.1e m, energy %.1e of KE %.2f J; rope rolled on/off by the swing %.4f m "
                "(R times the fall's turn to %.1e m)\n",
                worstLength, worstEnergy / largestKinetic, largestKinetic, rolled, worstRoll);
    EXPECT_LE(worstLength, 1e-12);
    EXPECT_LE(worstEnergy, 1e-8 * largestKinetic);
    EXPECT_GT(rolled, 0.02);
    EXPECT_LE(worstRoll, 1e-9);
}

// A wrapped drum has no arc and no wrap angle (the rope beyond its tangent point is stored rope):
// getArcLength is 0 there, getWrapAngle and sampleArc say so.
TEST(WrappedDrum, HasNoArcAndNoWrapAngle) {
    SwingingLoad s;
    EXPECT_EQ(s.reeving->getArcLength(s.state, 0, 0), 0.0);
    EXPECT_THROW(s.reeving->getWrapAngle(s.state, 0, 0), std::invalid_argument);
    EXPECT_THROW(s.reeving->sampleArc(s.state, 0, 0, 5), std::invalid_argument);
}
