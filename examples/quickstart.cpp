// reeving-quickstart: the first program to read and run. The paper's Table 1 pendulum built from
// Simbody bodies and one SimbodyReeving rope over one deviation sheave: static equilibrium, a 1 m/s
// push, RK-Merson; prints the payload's position, the rope's axial force at the payload and the
// energy drift every second. About a second of wall for the default 20 s.
//
//   reeving-quickstart               prints a table
//   reeving-quickstart --t-end 5     a shorter run
// (The bundled demos, reeving-pendulum, reeving-crane and reeving-elevator, show their runs with
// --visualize.) README.md's smallest complete program is this machine without the command line.
#include "common/Cli.h"

#include <SimbodyReeving/SimbodyReeving.h>

#include <Simbody.h>

#include <cmath>
#include <cstdio>
#include <exception>
#include <string>

namespace {

int run(double tEnd) {
    using namespace SimTK;
    MultibodySystem system;
    SimbodyMatterSubsystem matter(system);
    GeneralForceSubsystem forces(system);                   // every other force subsystem first
    Force::Gravity gravity(forces, matter, Vec3(0, -9.81, 0));
    SimbodyReeving::ReevingSubsystem reeving(system);  // then the ropes (gravity: the system's)

    // A 1000 kg payload on a free mobilizer (quaternions), inertia 36 kg m^2 about its centre.
    const Body::Rigid payloadBody(MassProperties(1000, Vec3(0), Inertia(36)));
    MobilizedBody::Free payload(matter.Ground(), Transform(), payloadBody, Transform());

    SimbodyReeving::RopeSpec rope;
    rope.start = SimbodyReeving::RopeAnchor{matter.Ground(), Vec3(0)};                  // [m]
    rope.sheaves = {SimbodyReeving::DeviationSheave{matter.Ground(), Vec3(3, 0, 0), 0.1}}; // centre, radius [m]
    rope.end = SimbodyReeving::RopeAnchor{payload, Vec3(0, 0.3, 0)};  // 0.3 m above the centre of mass
    rope.properties = {0.6205, 16.5e6, 30.9};   // rhoA [kg/m], EA [N], EI [N m^2]; tension-only
    rope.unstretchedLength = 23;                // [m]: 3 m span + 20 m span
    rope.spanDefaults.axialModes = 3;           // n_a; defaults: n_t = 1, quasi-static axial modes
    rope.planeNormal = Vec3(0, 0, 1);           // a planar rope (optional)
    reeving.addRope(rope);
    system.realizeTopology();

    State state = system.getDefaultState();
    payload.setQToFitTranslation(state, Vec3(3, -20.3, 0));  // near where it hangs: Newton starts here
    reeving.findStaticEquilibrium(state);                    // bodies and rope together
    system.realize(state, Stage::Position);
    const auto span = reeving.getSpanMaterialRange(state, 0, 1);   // rope 0, span 1 (the vertical one)
    std::printf("equilibrium: payload at y = %.4f m, axial force at the payload %.1f N (payload weight %.1f N)\n",
                payload.getBodyOriginLocation(state)[1], reeving.getAxialForce(state, 0, 1, span.second), 1000 * 9.81);

    payload.setUToFitLinearVelocity(state, Vec3(1, 0, 0));   // a 1 m/s push
    system.realize(state, Stage::Velocity);
    const double E0 = reeving.calcMechanicalEnergy(state);   // bodies + rope, kinetic + potential [J]
    const double KE0 = system.calcKineticEnergy(state) + reeving.calcRopeKineticEnergy(state);

    RungeKuttaMersonIntegrator integ(system);               // or any Simbody integrator
    integ.setAccuracy(1e-6);
    SimbodyReeving::InterpolatingTimeStepper stepper(system, integ);  // reports do not end steps
    stepper.initialize(state);
    std::printf("%6s %10s %10s %14s %12s\n", "t [s]", "x [m]", "y [m]", "P payload [N]", "(E-E0)/KE0");
    for (int k = 1; k <= static_cast<int>(std::round(tEnd)); ++k) {  // a report every second
        stepper.stepTo(1.0 * k);
        const State& s = stepper.getState();                 // the report, realized to Velocity
        const Vec3 x = payload.getBodyOriginLocation(s);
        const auto range = reeving.getSpanMaterialRange(s, 0, 1);
        const double P = reeving.getAxialForce(s, 0, 1, range.second);  // axial force EA eps [N]
        std::printf("%6.2f %10.5f %10.5f %14.2f %12.3e\n", s.getTime(), x[0], x[1], P,
                    (reeving.calcMechanicalEnergy(s) - E0) / KE0);
    }
    std::printf("%d integrator steps\n", integ.getNumStepsTaken());
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    double tEnd = 20.0;
    CLI::App app(
        "The paper's Table 1 pendulum built from Simbody bodies and one SimbodyReeving rope: a 1000 kg\n"
        "payload on a rope from a Ground anchor over a deviation sheave 3 m away and 20 m down\n"
        "(n_a = 3 quasi-static axial modes, n_t = 1). From the static equilibrium, a 1 m/s sideways\n"
        "push, RK-Merson at accuracy 1e-6; prints every second the payload position, the rope's axial\n"
        "force at the payload and the energy drift.\n",
        "reeving-quickstart");
    demo_common::applyConventions(app);
    app.footer("Prints a table to stdout.\nExit status: 0 done; 2 bad command line; 1 the simulation failed.");
    app.add_option("--t-end", tEnd, "end time [s], whole seconds (default 20)")
        ->type_name("T")
        ->check(demo_common::positiveNumber());
    if (const int status = demo_common::parseOrExitStatus(app, argc, argv); status >= 0) return status;
    try {
        return run(tEnd);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "reeving-quickstart: simulation failed: %s\n", e.what());
        return 1;
    }
}
