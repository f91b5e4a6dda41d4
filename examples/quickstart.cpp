// reeving-quickstart: the README's "Using it from your project" code as a complete program. The
// paper's Table 1 pendulum built from Simbody bodies and one rope over one deviation sheave: static
// equilibrium, a 1 m/s push, 20 s with RK-Merson; prints the payload's position, the rope's axial
// force at the payload and the energy drift every second. Runs in about a second.
//
// The lines between the "README" markers are shown verbatim in README.md; a test
// (readme_code_blocks) checks that every C++ block of the README appears in a compiled source.

#include <SimbodyReeving/SimbodyReeving.h>

#include <Simbody.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <exception>

namespace {

constexpr const char* kUsage =
    "Usage: reeving-quickstart [--help]\n"
    "\n"
    "The paper's Table 1 pendulum (1000 kg payload on a 20 m rope over a deviation sheave 3 m from\n"
    "the anchor) built from Simbody bodies and one SimbodyReeving rope: static equilibrium, a 1 m/s\n"
    "horizontal push, 20 s with RK-Merson at accuracy 1e-6. Prints every second: time [s], payload\n"
    "position x, y [m], axial force at the payload end [N], (E - E0) / KE0. Exit 0 on success,\n"
    "1 if the simulation fails, 2 for an unknown option.\n";

int run() {
    // README: quickstart begin
    using namespace SimTK;
    MultibodySystem system;
    SimbodyMatterSubsystem matter(system);
    GeneralForceSubsystem forces(system);                   // every other force subsystem first
    Force::Gravity gravity(forces, matter, Vec3(0, -9.81, 0));
    SimbodyReeving::ReevingSubsystem reeving(system, Vec3(0, -9.81, 0));  // then the ropes

    // A 1000 kg payload on a free mobilizer (quaternions), inertia 36 kg m^2 about its centre.
    const Body::Rigid payloadBody(MassProperties(1000, Vec3(0), Inertia(36)));
    MobilizedBody::Free payload(matter.Ground(), Transform(), payloadBody, Transform());

    SimbodyReeving::RopeSpec rope;
    rope.start = SimbodyReeving::RopeAnchor{matter.Ground(), Vec3(0)};                  // [m]
    rope.sheaves = {SimbodyReeving::DeviationSheave{matter.Ground(), Vec3(3, 0, 0), 0.1}}; // centre, radius [m]
    rope.end = SimbodyReeving::RopeAnchor{payload, Vec3(0, 0.3, 0)};  // 0.3 m above the centre of mass
    rope.properties = {0.6205, 16.5e6, 30.9};   // rhoA [kg/m], EA [N], EI [N m^2]; tension-only
    rope.unstretchedLength = 23;                // [m]: 3 m span + 20 m span
    rope.spanDefaults.axialModes = 3;           // n_a (transverseModes: n_t = 1)
    rope.spanDefaults.axialDynamics = SimbodyReeving::AxialDynamics::QuasiStatic;   // no axial waves
    rope.spanDefaults.velocityModel = SimbodyReeving::VelocityModel::Complete;
    rope.planeNormal = Vec3(0, 0, 1);           // a planar rope (optional)
    reeving.addRope(rope);
    system.realizeTopology();

    State state = system.getDefaultState();
    payload.setQToFitTranslation(state, Vec3(3, -20.3, 0));  // near where it hangs: Newton starts here
    reeving.findStaticEquilibrium(state);                    // bodies and rope together
    payload.setUToFitLinearVelocity(state, Vec3(1, 0, 0));   // a 1 m/s push
    system.realize(state, Stage::Velocity);
    const double E0 = reeving.calcMechanicalEnergy(state);
    const double KE0 = system.calcKineticEnergy(state) + reeving.calcRopeKineticEnergy(state);

    RungeKuttaMersonIntegrator integ(system);               // or any Simbody integrator
    integ.setAccuracy(1e-6);
    SimbodyReeving::InterpolatingTimeStepper stepper(system, integ);  // reports do not end steps
    stepper.initialize(state);
    for (int k = 1; k <= 20; ++k) {
        stepper.stepTo(1.0 * k);
        const State& s = stepper.getState();                 // the report, realized to Velocity
        const Vec3 x = payload.getBodyOriginLocation(s);
        const auto span = reeving.getSpanMaterialRange(s, 0, 1);   // rope 0, span 1 (vertical)
        const double P = reeving.getAxialForce(s, 0, 1, span.second);  // at the payload end [N]
        std::printf("%4.1f %9.5f %9.5f %9.2f %10.3e\n", s.getTime(), x[0], x[1], P,
                    (reeving.calcMechanicalEnergy(s) - E0) / KE0);
    }
    // README: quickstart end
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    for (int i = 1; i < argc; ++i) {
        if (std::strcmp(argv[i], "--help") == 0 || std::strcmp(argv[i], "-h") == 0) {
            std::fputs(kUsage, stdout);
            return 0;
        }
        std::fprintf(stderr, "reeving-quickstart: unknown option '%s' (see --help)\n", argv[i]);
        return 2;
    }
    try {
        return run();
    } catch (const std::exception& e) {
        std::fprintf(stderr, "reeving-quickstart: %s\n", e.what());
        return 1;
    }
}
