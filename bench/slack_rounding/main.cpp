// Energy conservation of the quasi-static tension-only rope through slack and snap, against the
// rounding strain eps_s (SpanOptions::quasiStaticSlackTransitionStrain) and the slack
// regularisation delta (quasiStaticSlackStiffness): docs/stability.md, "Slack and snap".
//
// Scene: the Table 1 rope, one 20 m span from a Ground anchor to a 1000 kg payload on a vertical
// Translation, n_a = 2 quasi-static, n_t = 1; static equilibrium, thrown up at 3 m/s; RK-Merson at
// 1e-10 for 1.5 s, the energy checked after every internal step.
//
// Usage: bench-slack-rounding [eps_s delta]...   (no arguments: the table's five rows)
#include <SimbodyReeving/simbody/ReevingSubsystem.h>

#include <Simbody.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <utility>
#include <vector>

namespace {

void run(double transition, double delta) {
    using namespace SimTK;
    using namespace SimbodyReeving;
    const double g = 9.81, M = 1000, L = 20, v0 = 3.0;
    MultibodySystem system;
    SimbodyMatterSubsystem matter(system);
    GeneralForceSubsystem forces(system);
    Force::Gravity gravity(forces, matter, Vec3(0, -g, 0));
    ReevingSubsystem reeving(system, Vec3(0, -g, 0));
    MobilizedBody::Translation payload(matter.Ground(), Transform(Vec3(0, -L, 0)),
                                       Body::Rigid(MassProperties(M, Vec3(0), Inertia(1))), Transform());
    RopeSpec spec;
    spec.start = RopeAnchor{matter.Ground(), Vec3(0)};
    spec.end = RopeAnchor{payload, Vec3(0)};
    spec.properties = {0.6205, 16.5e6, 30.9};  // tension-only (the default)
    spec.unstretchedLength = L;
    spec.spanDefaults.axialModes = 2;
    spec.spanDefaults.transverseModes = 1;
    spec.spanDefaults.axialDynamics = AxialDynamics::QuasiStatic;
    spec.spanDefaults.velocityModel = VelocityModel::Simplified;  // not the default: the setting of the recorded results
    spec.spanDefaults.quasiStaticSlackTransitionStrain = transition;
    spec.spanDefaults.quasiStaticSlackStiffness = delta;
    spec.planeNormal = Vec3(0, 0, 1);
    reeving.addRope(spec);
    system.realizeTopology();
    State s = system.getDefaultState();
    reeving.findStaticEquilibrium(s, 1e-12);
    payload.setUToFitLinearVelocity(s, Vec3(0, v0, 0));
    system.realize(s, Stage::Velocity);
    const double e0 = reeving.calcMechanicalEnergy(s);
    RungeKuttaMersonIntegrator integ(system);
    integ.setAccuracy(1e-10);
    integ.setReturnEveryInternalStep(true);
    integ.initialize(s);
    double worst = 0;
    while (integ.getTime() < 1.5) {
        integ.stepTo(1.5);
        const State& x = integ.getState();
        system.realize(x, Stage::Velocity);
        worst = std::max(worst, std::abs(reeving.calcMechanicalEnergy(x) - e0));
    }
    std::printf("| %.0e | %.0e | %d | %.2e | %d |\n", transition, delta, integ.getNumStepsTaken(), worst,
                reeving.getNumEvaluationFailures());
}

}  // namespace

int main(int argc, char** argv) {
    std::vector<std::pair<double, double>> rows;
    for (int i = 1; i + 1 < argc; i += 2) rows.emplace_back(std::atof(argv[i]), std::atof(argv[i + 1]));
    if (rows.empty()) rows = {{1e-6, 1e-3}, {1e-5, 1e-3}, {1e-4, 1e-3}, {1e-5, 1e-4}, {1e-5, 1e-5}};
    std::printf("payload kinetic energy at the throw %.1f J\n| eps_s | delta | steps | max energy error [J] | evaluation failures (retried) |\n"
                "|---:|---:|---:|---:|---:|\n", 0.5 * 1000 * 9.0);
    for (const auto& [transition, delta] : rows) run(transition, delta);
}
