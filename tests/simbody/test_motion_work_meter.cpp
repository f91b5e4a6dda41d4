// MotionWorkMeter: the integrated power of prescribed motions equals the change of mechanical
// energy of an otherwise conservative system.
#include "SimbodyReeving/simbody/MotionWorkMeter.h"

#include <gtest/gtest.h>

#include <Simbody.h>

#include <cmath>

using namespace SimTK;

// A rod pendulum driven at constant speed (Motion::Steady) plus a free pendulum hanging from it on a
// pin: the motor's work over a revolution equals the change of T + U of both.
TEST(MotionWorkMeter, WorkEqualsChangeOfMechanicalEnergy) {
    MultibodySystem system;
    SimbodyMatterSubsystem matter(system);
    GeneralForceSubsystem forces(system);
    Force::Gravity gravity(forces, matter, Vec3(0, -9.81, 0));
    const Body::Rigid rod(MassProperties(2.0, Vec3(0.5, 0, 0), Inertia(0.01, 0.6, 0.6)));  // about the origin
    MobilizedBody::Pin driven(matter.Ground(), Transform(), rod, Transform());
    Motion::Steady(driven, 1.5);
    MobilizedBody::Pin swinging(driven, Transform(Vec3(1, 0, 0)), rod, Transform());
    SimbodyReeving::MotionWorkMeter meter(system);
    system.realizeTopology();
    State s = system.getDefaultState();
    swinging.setAngle(s, 0.3);
    system.realize(s, Stage::Position);
    system.prescribeU(s);  // the driven rod's speed: E0 must include its kinetic energy
    system.realize(s, Stage::Velocity);
    EXPECT_EQ(meter.getWork(s), 0.0);
    const double E0 = system.calcEnergy(s);

    RungeKuttaMersonIntegrator integ(system);
    integ.setAccuracy(1e-10);
    TimeStepper ts(system, integ);
    ts.initialize(s);
    double worst = 0, largest = 0;
    for (double t = 0.1; t <= 4.0 + 1e-12; t += 0.1) {
        ts.stepTo(t);
        const State& st = integ.getState();
        system.realize(st, Stage::Acceleration);
        const double W = meter.getWork(st);
        worst = std::max(worst, std::abs(system.calcEnergy(st) - E0 - W));
        largest = std::max(largest, std::abs(W));
    }
    std::printf("[ work ] max |E - E0 - W| = %.3e J, max |W| = %.3f J\n", worst, largest);
    EXPECT_GT(largest, 1.0);  // the motor does real work
    EXPECT_LE(worst, 2e-9 * largest);  // measured 1.4e-9 J of 35 J (4.0e-11), margin 50x
}
