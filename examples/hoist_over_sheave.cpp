// Hoist over a sheave: a 1000 kg payload hangs from a wire rope that runs from a Ground anchor over
// a Ground deviation sheave and 20 m down. The rope is a ReevingSubsystem (ALE spans) inside an
// ordinary Simbody MultibodySystem: find the static equilibrium, push the payload sideways and
// integrate 5 s, printing the swing, the rope tension at the payload and the energy drift.
//
//   hoist-over-sheave               headless, prints a table
//   hoist-over-sheave --visualize   also shows it in the Simbody visualizer (if one can start)
//   hoist-over-sheave --t-end 2     a shorter run
#include "common/Cli.h"

#include <SimbodyReeving/ReevingSubsystem.h>
#include <SimbodyReeving/Visualization.h>

#include <Simbody.h>

#include <cmath>
#include <cstdio>
#include <exception>
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
using SimTK::Visualizer;
using namespace SimbodyReeving;

namespace {

int simulate(double tEnd, bool visualize) {
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

    // Optional visualizer; the rope is drawn by the ReevingSubsystem's own decorations.
    std::unique_ptr<Visualizer> viz;
    if (visualize) {
        std::string whyNot;
        viz = tryStartVisualizer(system, whyNot);
        if (viz) {
            viz->setShowSimTime(true);
            viz->setMode(Visualizer::RealTime);
            viz->setBackgroundType(Visualizer::SolidColor);          // no ground plane at y = 0
            viz->setCameraTransform(Transform(Vec3(1.5, -10, 45)));  // looking at the x-y plane
            system.addEventReporter(new Visualizer::Reporter(*viz, 1.0 / 30));
        } else {
            std::fprintf(stderr, "hoist-over-sheave: --visualize: %s; running headless\n", whyNot.c_str());
        }
    }
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
    const int reports = static_cast<int>(std::ceil(tEnd / 0.5 - 1e-9));  // every 0.5 s, and at tEnd
    for (int k = 0; k <= reports; ++k) {
        if (k > 0) stepper.stepTo(std::min(0.5 * k, tEnd));
        const State& st = integ.getState();
        system.realize(st, Stage::Velocity);
        const Vec3 p = payload.getBodyOriginLocation(st);
        std::printf("%6.2f %10.4f %10.4f %12.2f %12.2e\n", st.getTime(), p[0], p[1], tensionAtPayload(st),
                    reeving.calcMechanicalEnergy(st) - E0);
    }
    std::printf("%d integrator steps\n", integ.getNumStepsTaken());
    if (viz) stopVisualizer(*viz);  // before the system is destroyed
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    double tEnd = 5.0;
    bool visualize = false;
    CLI::App app(
        "A 1000 kg payload hangs from a wire rope that runs from a Ground anchor over a deviation sheave\n"
        "and 20 m down (a ReevingSubsystem in an ordinary Simbody MultibodySystem). From the static\n"
        "equilibrium, a 1 m/s sideways push; prints the payload position, the rope tension at the payload\n"
        "and the energy drift every 0.5 s.\n",
        "hoist-over-sheave");
    demo_common::applyConventions(app);
    app.footer("Prints a table to stdout.\nExit status: 0 done; 2 bad command line; 1 the simulation failed.");
    app.add_option("--t-end", tEnd, "end time [s] (default 5)")->type_name("T")->check(demo_common::positiveNumber());
    app.add_flag("--visualize", visualize, "show the run in Simbody's Visualizer (runs headless without a display)");
    if (const int status = demo_common::parseOrExitStatus(app, argc, argv); status >= 0) return status;
    try {
        return simulate(tEnd, visualize);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "hoist-over-sheave: simulation failed: %s\n", e.what());
        return 1;
    }
}
