// The README's shorter code blocks, compiled and run inside complete scenes (readme_code_blocks
// checks that each README block appears here, in examples/quickstart.cpp or in the consumer
// project). The lines between "README:" markers are the README's, verbatim.
#include "SimbodyReeving/SimbodyReeving.h"

#include <gtest/gtest.h>

#include <Simbody.h>

#include <cmath>
#include <cstdio>

using namespace SimTK;

namespace {

// The slack log: a 100 kg payload on 2 m of rope, thrown up at 6 m/s, so the rope goes slack and
// snaps taut again.
TEST(ReadmeSnippets, SlackMonitorLogsTransitions) {
    MultibodySystem system;
    SimbodyMatterSubsystem matter(system);
    GeneralForceSubsystem forces(system);
    Force::Gravity gravity(forces, matter, Vec3(0, -9.81, 0));
    SimbodyReeving::ReevingSubsystem reeving(system, Vec3(0, -9.81, 0));
    MobilizedBody::Free payload(matter.Ground(), Transform(),
                                Body::Rigid(MassProperties(100, Vec3(0), Inertia(1))), Transform());
    SimbodyReeving::RopeSpec rope;
    rope.start = SimbodyReeving::RopeAnchor{matter.Ground(), Vec3(0)};
    rope.end = SimbodyReeving::RopeAnchor{payload, Vec3(0)};
    rope.unstretchedLength = 2;
    rope.planeNormal = Vec3(0, 0, 1);
    // README: slack begin
    rope.properties = {0.6205, 16.5e6, 30.9};                     // rhoA, EA, EI; tension-only (default)
    reeving.addRope(rope);
    SimbodyReeving::SlackMonitor slack(system, reeving);          // before realizeTopology
    // README: slack end
    system.realizeTopology();
    State state = system.getDefaultState();
    payload.setQToFitTranslation(state, Vec3(0, -2.0, 0));
    reeving.findStaticEquilibrium(state);
    payload.setUToFitLinearVelocity(state, Vec3(0, 6, 0));
    RungeKuttaMersonIntegrator integ(system);
    integ.setAccuracy(1e-8);
    SimbodyReeving::InterpolatingTimeStepper stepper(system, integ);
    stepper.initialize(state);
    stepper.stepTo(1.6);  // up for 0.61 s, down to the taut length at about 1.22 s
    // README: slack log begin
    for (const auto& t : slack.transitions()) std::printf("%g s: span %d %s\n", t.time, t.span, t.slack ? "slack" : "taut");
    // README: slack log end
    ASSERT_GE(slack.transitions().size(), 2u);
    EXPECT_TRUE(slack.transitions()[0].slack);
    EXPECT_FALSE(slack.transitions()[1].slack);
    // Free flight between the transitions: from the taut length up and back, 2 v / g (v = 6 m/s
    // less what the rope's spring took, so a little shorter). Measured 1.2225 s; bound from physics.
    const double flight = slack.transitions()[1].time - slack.transitions()[0].time;
    EXPECT_GT(flight, 1.0);
    EXPECT_LT(flight, 2 * 6 / 9.81);
}

// A winch drum on a Pin hauls a 500 kg payload in over an idler that turns with the rope; the
// motor's work equals the change of mechanical energy (the README's hoisting snippet). The drum
// starts at full speed, so the payload bounces on the rope (57 rad/s, +-17 kN about its weight): the
// paper's linear law here, so that the bounce does not go slack.
TEST(ReadmeSnippets, DrumAndTurningSheaveHoist) {
    MultibodySystem system;
    SimbodyMatterSubsystem matter(system);
    GeneralForceSubsystem forces(system);
    Force::Gravity gravity(forces, matter, Vec3(0, -9.81, 0));
    SimbodyReeving::ReevingSubsystem reeving(system, Vec3(0, -9.81, 0));
    MobilizedBody& trolley = matter.updGround();  // a trolley body in a crane; Ground here
    const Body::Rigid drumBody(MassProperties(50, Vec3(0), Inertia(2.0)));
    const Body::Rigid idlerBody(MassProperties(100, Vec3(0), Inertia(2.0)));
    MobilizedBody::Pin idler(matter.Ground(), Transform(Vec3(1, 0.5, 0)), idlerBody, Transform());
    MobilizedBody::Free payload(matter.Ground(), Transform(),
                                Body::Rigid(MassProperties(500, Vec3(0), Inertia(10))), Transform());
    SimbodyReeving::RopeSpec rope;
    rope.properties = {0.6205, 16.5e6, 0.0, /*tensionOnly=*/false};
    rope.end = SimbodyReeving::RopeAnchor{payload, Vec3(0)};
    rope.unstretchedLength = 10;  // 1 m drum to idler, 9 m down to the payload
    rope.planeNormal = Vec3(0, 0, 1);
    // README: hoist begin
    MobilizedBody::Pin drum(trolley, Transform(Vec3(0, 0.5, 0)), drumBody, Transform());
    Motion::Steady hoist(drum, -2.0);                             // [rad/s]; or a torque, a brake...
    rope.start = SimbodyReeving::WinchDrum{drum, 0.3, 50.0};      // radius [m], rope on the drum at angle 0 [m]
    rope.sheaves.push_back(SimbodyReeving::TurningSheave{idler, 0.2, 1.0});  // no slip: s = 1 m + R theta
    rope.minimumSpanLength = 0.3;                                 // two-blocking ends the run [m]
    SimbodyReeving::MotionWorkMeter work(system);                 // motor work, integrated with the state
    // README: hoist end
    reeving.addRope(rope);
    system.realizeTopology();
    State state = system.getDefaultState();
    payload.setQToFitTranslation(state, Vec3(1, 0.5 - 9.0, 0));
    hoist.setRate(state, 0.0);  // hold the drum for the equilibrium
    reeving.findStaticEquilibrium(state);
    hoist.setRate(state, -2.0);
    system.prescribe(state);  // the drum's speed into the state's u, as the integrator does
    system.realize(state, Stage::Velocity);
    const double E0 = reeving.calcMechanicalEnergy(state);
    const double y0 = payload.getBodyOriginLocation(state)[1];
    RungeKuttaMersonIntegrator integ(system);
    integ.setAccuracy(1e-8);
    SimbodyReeving::InterpolatingTimeStepper stepper(system, integ);
    stepper.initialize(state);
    stepper.stepTo(0.5);
    const State& s = stepper.getState();
    system.realize(s, Stage::Velocity);
    EXPECT_EQ(reeving.getLimitReached(), "");
    // Hauled in: 0.5 s x 2 rad/s x 0.3 m = 0.3 m of rope, so the payload rose about 0.3 m, give or
    // take the bounce (+-1 cm).
    EXPECT_NEAR(payload.getBodyOriginLocation(s)[1] - y0, 0.3, 0.02);
    EXPECT_NEAR(reeving.getRopeOnDrum(s, 0, 0), 50.0 + 0.3, 1e-12);
    // Energy: work of the prescribed drum motion = change of mechanical energy.
    const double dE = reeving.calcMechanicalEnergy(s) - E0;
    std::printf("steps %d, work %.9e J, dE %.9e J, difference %.3e J\n", integ.getNumStepsTaken(), work.getWork(s),
                dE, work.getWork(s) - dE);
    EXPECT_GT(dE, 500 * 9.81 * 0.25);
    // Measured 3.9e-6 J of 1 851 J (2.1e-9, 7 632 steps): margin 47x.
    EXPECT_NEAR(work.getWork(s), dE, 1e-7 * std::abs(dE));
}

}  // namespace
