// Hoist over a sheave: a 1000 kg payload hangs from a wire rope that runs from a Ground anchor over
// a Ground deviation sheave and 20 m down. The rope is a ReevingSubsystem (ALE spans) inside an
// ordinary Simbody MultibodySystem: find the static equilibrium, push the payload sideways and
// integrate 5 s, printing the swing, the rope tension at the payload and the energy drift.
//
//   hoist-over-sheave               headless, prints a table
//   hoist-over-sheave --visualize   also shows it in the Simbody visualizer (if one can start)
#include "common/DemoVisualizer.h"

#include <SimbodyReeving/ReevingSubsystem.h>

#include <Simbody.h>

#include <cstdio>
#include <cstring>
#include <memory>
#include <string>

// Not `using namespace SimTK;`: the rope headers bring in Eigen, which SimTK's generic operators upset.
using SimTK::Body;
using SimTK::Inertia;
using SimTK::MassProperties;
using SimTK::MobilizedBody;
using SimTK::Stage;
using SimTK::State;
using SimTK::Transform;
using SimTK::Vec3;
using namespace SimbodyReeving;

int main(int argc, char** argv) {
    const bool visualize = argc > 1 && std::strcmp(argv[1], "--visualize") == 0;
    const Vec3 g(0, -9.81, 0);  // gravity [m/s^2], y up

    // The system: matter, ordinary forces (gravity), then the ropes, always the last force subsystem.
    SimTK::MultibodySystem system;
    SimTK::SimbodyMatterSubsystem matter(system);
    SimTK::GeneralForceSubsystem forces(system);
    SimTK::Force::Gravity gravity(forces, matter, g);
    ReevingSubsystem reeving(system, g);  // the same gravity acts on the rope

    // The payload: a free rigid body, 1000 kg, 36 kg m^2 about every axis through its centre of mass.
    MobilizedBody::Free payload(matter.updGround(), Transform(),
                                Body::Rigid(MassProperties(1000, Vec3(0), Inertia(36))), Transform());
    payload.addBodyDecoration(Transform(), SimTK::DecorativeBrick(Vec3(0.4, 0.3, 0.4)).setColor(SimTK::Blue));

    RopeSpec rope;
    rope.name = "hoist rope";
    rope.start = RopeAnchor{matter.Ground(), Vec3(0, 0, 0)};           // anchored on Ground at the origin [m]
    rope.sheaves = {DeviationSheave{matter.Ground(), Vec3(3, 0, 0), 0.1}};  // sheave on Ground: centre [m], radius [m]
    rope.end = RopeAnchor{payload, Vec3(0, 0.3, 0)};                   // on the payload, 0.3 m above its centre [m]
    rope.properties.massPerLength = 0.6205;                  // rhoA [kg/m]
    rope.properties.axialStiffness = 16.5e6;                 // EA [N]
    rope.properties.bendingStiffness = 30.9;                 // EI [N m^2]
    rope.unstretchedLength = 3 + 20;                         // 3 m across to the sheave, 20 m down [m]
    rope.spanDefaults.axialModes = 1;                        // sine modes per span along the rope...
    rope.spanDefaults.transverseModes = 2;                   // ...and across it
    rope.planeNormal = Vec3(0, 0, 1);                        // planar rope, in the x-y plane
    reeving.addRope(rope);

    // Optional visualizer (real time; closing its window does not stop the run); the rope, sheave and
    // anchor are drawn by the ReevingSubsystem's own decorations.
    demo_common::DemoVisualizer viz(system, reeving, "hoist-over-sheave", visualize);
    viz.lookAt(Vec3(1.5, -10.2, 27), Vec3(1.5, -10.2, 0));  // looking at the x-y plane
    if (viz.showing()) system.addEventReporter(new demo_common::DemoVisualizerReporter(viz, 1.0 / 30));
    system.realizeTopology();

    // Static equilibrium of payload and rope together, from a straight hanging guess.
    State s = system.getDefaultState();
    payload.setQToFitTranslation(s, Vec3(3, -20.3, 0));
    reeving.findStaticEquilibrium(s);
    system.realize(s, Stage::Position);
    // Tension in span 1 (sheave -> payload) at its payload end. It is a pointwise value of the modal strain
    // field, so it differs from the payload weight by a fraction of the rope weight; more axial modes close the gap.
    auto tensionAtPayload = [&](const State& st) {
        return reeving.getTension(st, 0, 1, reeving.getSpanMaterialRange(st, 0, 1).second);
    };
    std::printf("equilibrium: payload at y = %.4f m, tension at the payload %.1f N (payload weight %.1f N)\n",
                payload.getBodyOriginLocation(s)[1], tensionAtPayload(s), 1000 * 9.81);

    // A push: 1 m/s sideways. Then integrate with an ordinary Simbody integrator.
    payload.setUToFitLinearVelocity(s, Vec3(1, 0, 0));
    system.realize(s, Stage::Velocity);
    const double E0 = reeving.calcMechanicalEnergy(s);  // bodies + ropes, kinetic + potential [J]

    SimTK::RungeKuttaMersonIntegrator integ(system);
    integ.setAccuracy(1e-8);
    SimTK::TimeStepper stepper(system, integ);
    stepper.initialize(s);
    std::printf("%6s %10s %10s %12s %12s\n", "t [s]", "x [m]", "y [m]", "tension [N]", "E - E0 [J]");
    for (int k = 0; k <= 10; ++k) {
        if (k > 0) stepper.stepTo(0.5 * k);
        const State& st = integ.getState();
        system.realize(st, Stage::Velocity);
        const Vec3 p = payload.getBodyOriginLocation(st);
        std::printf("%6.2f %10.4f %10.4f %12.2f %12.2e\n", st.getTime(), p[0], p[1], tensionAtPayload(st),
                    reeving.calcMechanicalEnergy(st) - E0);
    }
    std::printf("%d integrator steps\n", integ.getNumStepsTaken());
    viz.close();  // the window closes and its process ends with the run
    return 0;
}
