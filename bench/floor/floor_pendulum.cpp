// bench-floor-pendulum: Simbody's own floor for the Table 1 pendulum. The
// reeving-pendulum demo's scene (SimbodyReeving::PendulumScene) with the rope replaced by one
// massless SimTK::Force::TwoPointLinearSpring, integrated and reported as the demo does; it prints
// the steps, right-hand sides and wall time that Simbody alone spends. bench/cost.sh sets it
// side by side with the demo.
//
// The same as PendulumScene: the payload, a MobilizedBody::Free from Ground (quaternions) of mass M
// and central inertia J; gravity g along -y (Force::Gravity); the initial state: static
// equilibrium, then the payload's velocity (vx0, 0, 0) = (1, 0, 0) m/s. The same as the demo:
// RK-Merson at accuracy 1e-6, reports every 0.01 s through InterpolatingTimeStepper, the reporter
// realizing Stage::Dynamics (the demo's reads the axial forces there) and reading the payload
// position and angle, the spring force and the mechanical energy; 20 s simulated.
//
// The rope: the horizontal span has both ends on Ground and does nothing here, so it has no
// spring. The vertical span becomes one spring from the deviation sheave's point (a, 0, 0) to the
// rope's attachment d above the payload's centre of mass, of the span's axial stiffness
// k = EA / L_v, L_v the vertical span's unstretched length at static equilibrium, and of the
// natural length that makes the spring's static length that of the hanging span: the payload
// starts where the demo's starts (to about 1 mm: the demo's equilibrium also has bending and the
// sheave's wrap), hanging straight below the sheave. L_v and the static length follow from the
// hanging rope of the Table 1 parameters under its own weight and the payload's, the law
// P = EA eps with the stretch sqrt(1 + 2 eps) (the plugin's strain), and a frictionless sheave:
//   tension T(sigma) = M g + rhoA g sigma (sigma: unstretched length below), P = T / stretch;
//   the horizontal span at the sheave's tension: L_h = a / stretch_h; L_v = a + L - L_h;
//   static length l_s = integral over sigma in [0, L_v] of stretch(sigma) (Simpson, 64 panels);
//   natural length l_0 = l_s - M g / k.
//
// usage: bench-floor-pendulum [--t-end T] [--accuracy TOL] [--integrator NAME]
//                             [--report-interval DT] [--out DIR] [--quiet]
#include "FloorRun.h"

#include <SimbodyReeving/scenes/PendulumScene.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>

namespace {

using namespace SimTK;

/// Stretch |dr/ds| = sqrt(1 + 2 eps) of rope at tension T [N] with P = EA eps and T = P stretch.
double stretchAtTension(double T, double EA) {
    double lambda = 1;
    for (int i = 0; i < 50; ++i) lambda = std::sqrt(1.0 + 2.0 * T / (lambda * EA));
    return lambda;
}

struct Spring {
    double stiffness = 0;      ///< k [N/m]
    double naturalLength = 0;  ///< l_0 [m]
    double staticLength = 0;   ///< l_s [m]
    double verticalUnstretched = 0;  ///< L_v [m]
};

Spring verticalSpanSpring(const SimbodyReeving::PendulumParameters& p) {
    Spring s;
    double Lv = p.L;
    for (int i = 0; i < 50; ++i) {
        const double top = p.M * p.g + p.rhoA * p.g * Lv;  // tension at the sheave, both sides
        Lv = p.a + p.L - p.a / stretchAtTension(top, p.EA);
    }
    const int panels = 64;
    double sum = 0;
    for (int i = 0; i <= panels; ++i) {
        const double w = (i == 0 || i == panels) ? 1 : (i % 2 ? 4 : 2);
        sum += w * stretchAtTension(p.M * p.g + p.rhoA * p.g * Lv * i / panels, p.EA);
    }
    s.verticalUnstretched = Lv;
    s.staticLength = sum * Lv / (3.0 * panels);
    s.stiffness = p.EA / Lv;
    s.naturalLength = s.staticLength - p.M * p.g / s.stiffness;
    return s;
}

}  // namespace

int main(int argc, char** argv) {
    const std::string program = "bench-floor-pendulum";
    bench_floor::Options o;
    o.tEnd = 20.0;
    o.reportInterval = 0.01;
    CLI::App app("Simbody's own floor for the Table 1 pendulum: the reeving-pendulum scene with the rope\n"
                 "replaced by one massless Force::TwoPointLinearSpring (see the source's header).",
                 program);
    bench_floor::defineOptions(app, o);
    if (const int status = demo_common::parseOrExitStatus(app, argc, argv); status >= 0) return status;
    if (!o.outDir.empty() && !demo_common::prepareOutputFolder(program, o.outDir)) return demo_common::kUsageExitStatus;

    const SimbodyReeving::PendulumParameters p;  // Table 1
    const double vx0 = 1.0;                      // the demo's default [m/s]
    const Spring spring = verticalSpanSpring(p);

    MultibodySystem system;
    SimbodyMatterSubsystem matter(system);
    GeneralForceSubsystem forces(system);
    Force::Gravity gravity(forces, matter, Vec3(0, -p.g, 0));
    const Body::Rigid body(MassProperties(p.M, Vec3(0), Inertia(p.J)));
    MobilizedBody::Free payload(matter.updGround(), Transform(), body, Transform());
    const Vec3 sheave(p.a, 0, 0), attachment(0, p.d, 0);
    Force::TwoPointLinearSpring rope(forces, matter.Ground(), sheave, payload, attachment, spring.stiffness,
                                     spring.naturalLength);
    system.realizeTopology();

    State s = system.getDefaultState();
    payload.setQToFitTranslation(s, Vec3(p.a, -spring.staticLength, 0) - attachment);
    payload.setUToFitLinearVelocity(s, Vec3(vx0, 0, 0));
    system.realize(s, Stage::Velocity);

    auto report = [&](const State& st) {
        system.realize(st, Stage::Dynamics);
        const Vec3 r = payload.getBodyOriginLocation(st);
        const Vec3 x = payload.getBodyRotation(st).x();
        const double length = (payload.findStationLocationInGround(st, attachment) - sheave).norm();
        return std::vector<double>{st.getTime(), r[0], r[1], std::atan2(x[1], x[0]),
                                   spring.stiffness * (length - spring.naturalLength), system.calcEnergy(st)};
    };
    bench_floor::Result result;
    try {
        result = bench_floor::run(system, s, o, report);
    } catch (const std::exception& e) {
        std::cerr << program << ": simulation failed: " << e.what() << "\n";
        return 1;
    }
    double drift = 0;
    for (const auto& row : result.rows) drift = std::max(drift, std::abs(row[5] - result.rows.front()[5]));
    if (!o.outDir.empty()) {
        using demo_common::jsonNumber;
        demo_common::Json extra;
        extra["vx0"] = jsonNumber(vx0);
        extra["spring_stiffness_N_per_m"] = jsonNumber(spring.stiffness);
        extra["spring_natural_length_m"] = jsonNumber(spring.naturalLength);
        extra["spring_static_length_m"] = jsonNumber(spring.staticLength);
        extra["vertical_span_unstretched_m"] = jsonNumber(spring.verticalUnstretched);
        extra["max_energy_drift_J"] = jsonNumber(drift);
        try {
            bench_floor::writeOutputs(program, o, result, {"t", "x", "y", "theta", "spring_force", "energy"}, extra);
        } catch (const std::exception& e) {
            std::cerr << program << ": writing the outputs failed: " << e.what() << "\n";
            return 1;
        }
    }
    bench_floor::printSummary(program, o, result);
    if (!o.quiet) std::printf("%s: max energy drift %.3e J\n", program.c_str(), drift);
    return 0;
}
