// A WinchDrum that spools across its width (WinchDrum::pitch): the rope's exit point walks along the
// drum's axis by one pitch per turn of rope stored, so the fleet angle of its fall changes through a
// lift. The drum's axis is Ground's z, the rope spatial and wrapped; the load hangs under the drum's
// right-hand side (the rope leaving it clockwise about +z).
#include "SimbodyReeving/simbody/ReevingSubsystem.h"

#include "support/ExpectThrowMessage.h"

#include <gtest/gtest.h>

#include <Simbody.h>

#include <cmath>
#include <cstdio>
#include <memory>

using namespace SimTK;
namespace sr = SimbodyReeving;

namespace {

constexpr double kG = 9.81;
constexpr double kR = 0.3;       // drum radius [m]
constexpr double kPitch = 0.02;  // the exit point's advance per turn [m] (a 20 mm rope on a grooved drum)
constexpr double kFall = 12.0;   // the fall's unstretched length at pin angle 0 [m]

struct Options {
    double pitch = kPitch;
    bool heldDrum = true;
    bool planar = false;
    sr::SheaveModel sheaves = sr::SheaveModel::Wrapped;
};

struct Scene {
    MultibodySystem system;
    SimbodyMatterSubsystem matter{system};
    GeneralForceSubsystem forces{system};
    Force::Gravity gravity{forces, matter, -YAxis, kG};
    MobilizedBody::Pin drum;
    MobilizedBody::Translation load;
    std::unique_ptr<sr::ReevingSubsystem> reeving;
    State state;

    explicit Scene(const Options& o) {
        drum = MobilizedBody::Pin(matter.Ground(), Transform(), Body::Rigid(MassProperties(50, Vec3(0), Inertia(2.0))),
                                  Transform());
        if (o.heldDrum) Motion::Steady(drum, 0.0);
        load = MobilizedBody::Translation(matter.Ground(), Transform(),
                                          Body::Rigid(MassProperties(200, Vec3(0), Inertia(1))), Transform());
        reeving = std::make_unique<sr::ReevingSubsystem>(system, Vec3(0, -kG, 0));
        sr::RopeSpec rope;
        rope.sheaveModel = o.sheaves;
        rope.properties = {1.0, 2e7, 0.0};
        rope.spanDefaults.axialModes = 1;
        rope.spanDefaults.transverseModes = 1;
        if (o.planar) rope.planeNormal = Vec3(0, 0, 1);
        sr::WinchDrum d;
        d.body = drum;
        d.radius = kR;
        d.ropeOnDrum = 10.0;
        d.payoutSense = -1;  // a positive pin angle hauls rope in: s_0 = R theta
        d.pitch = o.pitch;
        rope.start = d;
        rope.end = sr::RopeAnchor{load, Vec3(0)};
        rope.unstretchedLength = 0.5 * Pi * kR + kFall;  // a quarter turn from the drum's top to its right side
        reeving->addRope(rope);
        system.realizeTopology();
        state = system.getDefaultState();
        load.setQToFitTranslation(state, Vec3(kR, -kFall, 0));
    }
};

}  // namespace

// The exit point after k turns of rope stored (the drum's pin at 2 pi k, the load hung where the
// fall keeps its length, straight under the drum's right-hand side at z = 0): in closed form the
// groove circle lies k p along the axis, so the tangent point is (R, 0, k p) (the load's
// projection onto the groove's plane lies on the tangent x = R) and the fall leans out of the
// groove's plane by the fleet angle atan(k p / depth), depth the load's distance below the drum's
// centre. Measured: the tangent point to 1.0e-18 m, the fleet angle to 8.7e-19 rad (round-off;
// 0.634 degrees after 3.25 turns); bounds 1e-16 m and 1e-16 rad. Without a pitch the fall stays in
// the plane (fleet angle 0).
TEST(SpoolingDrum, ExitPointWalksOnePitchPerTurnStored) {
    double worstPoint = 0, worstFleet = 0, largestFleet = 0;
    for (double turns : {0.0, 0.5, 1.0, 2.0, 3.25}) {
        Scene sc{Options{}};
        const double depth = kFall - 2 * Pi * kR * turns;
        sc.drum.setOneQ(sc.state, 0, 2 * Pi * turns);
        sc.load.setQToFitTranslation(sc.state, Vec3(kR, -depth, 0));
        sc.system.realize(sc.state, Stage::Position);
        const Vec3 T = sc.reeving->sampleSpan(sc.state, 0, 0, 2).front();
        worstPoint = std::max(worstPoint, (T - Vec3(kR, 0, turns * kPitch)).norm());
        const double fleet = std::abs(sc.reeving->getFleetAngles(sc.state, 0, 0).first);
        worstFleet = std::max(worstFleet, std::abs(fleet - std::atan(turns * kPitch / depth)));
        largestFleet = std::max(largestFleet, fleet);
    }
    Options plain;
    plain.pitch = 0;
    Scene sc(plain);
    sc.drum.setOneQ(sc.state, 0, 2 * Pi * 2.0);
    sc.load.setQToFitTranslation(sc.state, Vec3(kR, -(kFall - 4 * Pi * kR), 0));
    sc.system.realize(sc.state, Stage::Position);
    std::printf("spooling drum: tangent point %.1e m, fleet angle %.1e rad off the closed form; largest %.3f deg\n",
                worstPoint, worstFleet, largestFleet * 180 / Pi);
    EXPECT_LE(worstPoint, 1e-16);
    EXPECT_LE(worstFleet, 1e-16);
    EXPECT_GT(largestFleet, 0.1 * Pi / 180);  // 3.25 turns: 65 mm over 5.9 m
    EXPECT_EQ(sc.reeving->getFleetAngles(sc.state, 0, 0).first, 0.0);
    EXPECT_EQ(sc.reeving->sampleSpan(sc.state, 0, 0, 2).front()[2], 0.0);
}

// A free drum (2 kg m^2) unwound by a 200 kg load released from rest 0.3 m out of the groove's
// plane: the load falls and swings across the drum's axis while the exit point walks along it
// (against the lay: 0.10 m as 9.6 m of rope pay out), the fleet angle moving between 1.0 and 1.4
// degrees. The system is conservative: T + U stays at its start within 1.6e-9 of the largest
// kinetic energy (20 kJ) over 1.5 s with RK-Merson at 1e-11 (4.2e-9 at 1e-10, 1.0e-10 at 1e-12:
// the integrator's; 7.9e-9 at 1e-10 without a pitch); bound 3e-8. Without the lay's column in the
// station map's Jacobian it drifts by 2.9e-5. The exit point stays at p theta / (2 pi) along the
// axis from the drum's pin angle theta: measured 1.4e-17 m; bound 1e-15 m.
TEST(SpoolingDrum, FreeDrumUnwoundByAFallingLoadConservesEnergy) {
    Options o;
    o.heldDrum = false;
    Scene sc(o);
    // The fall 0.3 m out of the plane, stretched by about the load's weight (1e-4).
    const double stretched = kFall * (1 + 1e-4);
    sc.load.setQToFitTranslation(sc.state, Vec3(kR, -std::sqrt(stretched * stretched - 0.09), 0.3));
    sc.system.realize(sc.state, Stage::Velocity);
    const double e0 = sc.reeving->calcMechanicalEnergy(sc.state);
    const double theta0 = sc.drum.getOneQ(sc.state, 0);
    RungeKuttaMersonIntegrator integ(sc.system);
    integ.setAccuracy(1e-11);
    TimeStepper ts(sc.system, integ);
    ts.initialize(sc.state);
    double drift = 0, largestKinetic = 0, worstWalk = 0, walked = 0, fleetLow = 1e9, fleetHigh = -1e9;
    for (int i = 1; i <= 75; ++i) {
        ts.stepTo(0.02 * i);
        const State& s = integ.getState();
        sc.system.realize(s, Stage::Velocity);
        drift = std::max(drift, std::abs(sc.reeving->calcMechanicalEnergy(s) - e0));
        largestKinetic = std::max(largestKinetic, sc.system.calcKineticEnergy(s) + sc.reeving->calcRopeKineticEnergy(s));
        const double theta = sc.drum.getOneQ(s, 0);
        const double z = sc.reeving->sampleSpan(s, 0, 0, 2).front()[2];
        worstWalk = std::max(worstWalk, std::abs(z - kPitch * theta / (2 * Pi)));
        walked = std::min(walked, kPitch * (theta - theta0) / (2 * Pi));
        const double fleet = sc.reeving->getFleetAngles(s, 0, 0).first;
        fleetLow = std::min(fleetLow, fleet);
        fleetHigh = std::max(fleetHigh, fleet);
    }
    std::printf("spooling drum, free: drift %.2e of the largest KE %.0f J (%d steps); exit point walked %.4f m, off p "
                "theta / 2 pi by %.1e m; fleet angle %.2f .. %.2f deg\n",
                drift / largestKinetic, largestKinetic, integ.getNumStepsTaken(), walked, worstWalk, fleetLow * 180 / Pi,
                fleetHigh * 180 / Pi);
    EXPECT_LT(walked, -0.01);  // the drum paid out over half a turn
    EXPECT_LE(worstWalk, 1e-15);
    EXPECT_LE(drift, 3e-8 * largestKinetic);
}

// Bad input, one clear error at addRope: a pitch that is not finite or not below a turn's
// circumference, a pitch on a planar rope or with point sheaves.
TEST(SpoolingDrum, RejectsBadPitches) {
    for (double pitch : {std::nan(""), 2 * Pi * kR, -7.0}) {
        Options o;
        o.pitch = pitch;
        EXPECT_THROW_MESSAGE(Scene{o}, std::invalid_argument, "must be finite and |pitch| < 2 pi radius");
    }
    Options planar;
    planar.planar = true;
    EXPECT_THROW_MESSAGE(Scene{planar}, std::invalid_argument, "a drum that spools across its width needs a spatial rope");
    Options point;
    point.sheaves = sr::SheaveModel::Point;
    EXPECT_THROW_MESSAGE(Scene{point}, std::invalid_argument, "a drum that spools across its width needs a spatial rope");
}
