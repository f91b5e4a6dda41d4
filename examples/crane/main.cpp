// reeving-crane: an overhead (gantry) crane's lift-traverse-lower cycle (issue 13) from one
// command: a trolley with a prescribed traverse, a winch drum with a prescribed hoist profile, n
// falls of wire rope between trolley and hook block, a payload on a sling. See --help and README.md.
#include "CraneCli.h"
#include "CraneFigures.h"
#include "common/DemoOutput.h"
#include "common/Interrupt.h"

#include <SimbodyReeving/CraneScene.h>
#include <SimbodyReeving/Integrators.h>
#include <SimbodyReeving/InterpolatingTimeStepper.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <sstream>

namespace fs = std::filesystem;
using SimTK::Stage;
using SimTK::State;
using namespace crane_demo;
using namespace SimbodyReeving;
using demo_common::OutputFile;

namespace {

struct Interrupted : std::runtime_error {
    explicit Interrupted(double t) : std::runtime_error("interrupted"), time(t) {}
    double time;
};

/// One report: the columns of timeseries.csv.
struct Row {
    double t, trolleyX, hookX, hookY, sway, payloadAngle;
    std::vector<double> falls;
    double drumSpeed, motorTorque, motorPower, ropeOnDrum, trolleyForce, trolleyPower, work, residual;
};

struct RunResult {
    std::vector<Row> rows;
    std::vector<Snapshot> snapshots;
    std::vector<double> staticFallForce;  // top of each fall at t = 0 [N]
    long steps = 0, rhsEvaluations = 0;
    double wallSeconds = 0, energy0 = 0;
    std::string limit;  // "" or the rope limit that ended the run
};

Row observe(const CraneScene& scene, const State& s, double energy0) {
    // Stage::Acceleration: the drives' generalized forces (and the QuasiStatic force correction).
    scene.system().realize(s, Stage::Acceleration);
    Row r;
    r.t = s.getTime();
    r.trolleyX = scene.trolleyX(s);
    const SimTK::Vec3 hook = scene.hookPosition(s);
    r.hookX = hook[0];
    r.hookY = hook[1];
    r.sway = scene.swayAngle(s);
    r.payloadAngle = scene.payloadAngle(s);
    for (int k = 0; k < scene.falls(); ++k) r.falls.push_back(scene.fallTopForce(s, k));
    r.drumSpeed = scene.drumSpeed(s);
    r.motorTorque = scene.motorTorque(s);
    r.motorPower = r.motorTorque * r.drumSpeed;
    r.ropeOnDrum = scene.ropeOnDrum(s);
    r.trolleyForce = scene.trolleyForce(s);
    r.trolleyPower = r.trolleyForce * scene.trolley().getOneU(s, 0);
    r.work = scene.workMeter().getWork(s);
    r.residual = scene.reeving().calcMechanicalEnergy(s) - energy0 - r.work;
    return r;
}

RunResult run(const Options& o, const CraneScene& scene) {
    RunResult r;
    State s0 = scene.makeInitialState();
    scene.system().realize(s0, Stage::Acceleration);
    for (int k = 0; k < scene.falls(); ++k) r.staticFallForce.push_back(scene.fallTopForce(s0, k));
    r.energy0 = scene.reeving().calcMechanicalEnergy(s0);

    auto integ = makeIntegrator(o.integrator, scene.system());
    integ->setAccuracy(o.accuracy);
    if (o.step > 0) integ->setFixedStepSize(o.step);
    InterpolatingTimeStepper ts(scene.system(), *integ);
    ts.initialize(s0);
    const int reports = static_cast<int>(std::floor(o.tEnd / o.reportInterval + 1e-9));
    // Snapshots at the reports nearest to evenly spaced times over [0, reports * interval].
    std::vector<int> snapshotReports;
    for (int i = 0; i < o.snapshots; ++i)
        snapshotReports.push_back(o.snapshots == 1 ? 0 : static_cast<int>(std::lround(double(reports) * i / (o.snapshots - 1))));
    auto snap = [&](const State& s, const std::string& phase) {
        r.snapshots.push_back({s.getTime(), phase, drawCrane(scene, s)});
    };
    const auto start = std::chrono::steady_clock::now();
    auto lastPrint = start;
    bool printed = false;
    r.rows.push_back(observe(scene, ts.getState(), r.energy0));
    if (std::count(snapshotReports.begin(), snapshotReports.end(), 0)) snap(ts.getState(), phaseAt(scene.cycle(), 0));
    for (int n = 1; n <= reports; ++n) {
        if (demo_common::interrupted()) throw Interrupted(ts.getState().getTime());
        const double target = n * o.reportInterval;
        try {
            ts.stepTo(target);
        } catch (const std::exception& e) {
            // Simbody's integrators drop the cause of a failed step; the rope keeps the last one.
            const std::string& cause = scene.reeving().getLastEvaluationFailure();
            const std::string what = e.what();
            throw std::runtime_error(what + (cause.empty() || what.find(cause) != std::string::npos
                                                 ? ""
                                                 : "\n  last rope evaluation failure: " + cause));
        }
        const State& st = ts.getState();
        r.rows.push_back(observe(scene, st, r.energy0));
        if (!scene.reeving().getLimitReached().empty() || integ->isSimulationOver()) {
            // A rope limit (two-blocking, empty drum) requested termination: the run ends here.
            r.limit = scene.reeving().getLimitReached();
            if (r.limit.empty()) r.limit = "the integrator ended the simulation at t = " + std::to_string(st.getTime()) + " s";
            snap(st, "limit reached");
            break;
        }
        if (std::count(snapshotReports.begin(), snapshotReports.end(), n)) snap(st, phaseAt(scene.cycle(), st.getTime()));
        const auto now = std::chrono::steady_clock::now();
        if (!o.quiet && std::chrono::duration<double>(now - start).count() > 2.0 &&
            std::chrono::duration<double>(now - lastPrint).count() > 1.0) {
            std::fprintf(stderr, "\rreeving-crane: t = %.1f of %.1f s, wall %.1f s", st.getTime(), o.tEnd,
                         std::chrono::duration<double>(now - start).count());
            lastPrint = now;
            printed = true;
        }
    }
    if (printed) std::fprintf(stderr, "\n");
    r.wallSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    r.steps = integ->getNumStepsTaken();
    r.rhsEvaluations = ts.getNumRealizations();
    return r;
}

std::string jsonNumber(double v) {
    if (!std::isfinite(v)) return "null";
    std::ostringstream o;
    o << std::setprecision(12) << v;
    return o.str();
}

std::string jsonString(const std::string& s) {
    std::string r = "\"";
    for (const char c : s) {
        if (c == '"' || c == '\\') r += '\\';
        if (c == '\n') {
            r += "\\n";
            continue;
        }
        r += c;
    }
    return r + "\"";
}

std::string jsonArray(const std::vector<double>& v) {
    std::string r = "[";
    for (size_t i = 0; i < v.size(); ++i) r += (i ? ", " : "") + jsonNumber(v[i]);
    return r + "]";
}

struct Figures {
    std::vector<double> maxFall;
    double maxSway = 0, maxPayloadAngle = 0, maxTorque = 0, maxPower = 0, maxTrolleyForce = 0;
    double maxResidual = 0, maxWork = 0;
};

Figures summarize(const RunResult& r, int falls) {
    Figures f;
    f.maxFall.assign(falls, 0.0);
    for (const Row& w : r.rows) {
        for (int k = 0; k < falls; ++k) f.maxFall[k] = std::max(f.maxFall[k], w.falls[k]);
        f.maxSway = std::max(f.maxSway, std::abs(w.sway));
        f.maxPayloadAngle = std::max(f.maxPayloadAngle, std::abs(w.payloadAngle));
        f.maxTorque = std::max(f.maxTorque, std::abs(w.motorTorque));
        f.maxPower = std::max(f.maxPower, std::abs(w.motorPower));
        f.maxTrolleyForce = std::max(f.maxTrolleyForce, std::abs(w.trolleyForce));
        f.maxResidual = std::max(f.maxResidual, std::abs(w.residual));
        f.maxWork = std::max(f.maxWork, std::abs(w.work));
    }
    return f;
}

void writeOutputs(const fs::path& dir, const Options& o, const CraneScene& scene, const RunResult& r, const Figures& f) {
    const int n = scene.falls();
    OutputFile tsFile(dir / "timeseries.csv"), snFile(dir / "snapshots.dat"), jsFile(dir / "summary.json");
    std::ofstream& ts = tsFile.stream();
    ts << "t,trolley_x,hook_x,hook_height,sway,payload_angle";
    for (int k = 1; k <= n; ++k) ts << ",fall_" << k;
    ts << ",drum_speed,motor_torque,motor_power,rope_on_drum,trolley_force,trolley_power,motion_work,energy_residual\n"
       << std::setprecision(12);
    for (const Row& w : r.rows) {
        ts << w.t << ',' << w.trolleyX << ',' << w.hookX << ',' << w.hookY << ',' << w.sway << ',' << w.payloadAngle;
        for (double x : w.falls) ts << ',' << x;
        ts << ',' << w.drumSpeed << ',' << w.motorTorque << ',' << w.motorPower << ',' << w.ropeOnDrum << ','
           << w.trolleyForce << ',' << w.trolleyPower << ',' << w.work << ',' << w.residual << '\n';
    }
    writeSnapshots(snFile.stream(), r.snapshots);

    const auto& p = scene.parameters();
    const Row& last = r.rows.back();
    std::vector<double> snapshotTimes;
    for (const Snapshot& s : r.snapshots) snapshotTimes.push_back(s.t);
    std::ofstream& js = jsFile.stream();
    js << "{\n"
       << "  \"program\": \"reeving-crane\",\n"
       << "  \"falls\": " << n << ",\n"
       << "  \"axial_modes\": " << o.axialModes << ",\n"
       << "  \"transverse_modes\": " << o.transverseModes << ",\n"
       << "  \"axial_dynamics\": \"" << axialDynamicsName(o.axialDynamics) << "\",\n"
       << "  \"axial_law\": \"" << (o.parameters.tensionOnly ? "tension-only" : "linear") << "\",\n"
       << "  \"integrator\": \"" << o.integrator << "\",\n"
       << "  \"accuracy\": " << jsonNumber(o.accuracy) << ",\n"
       << "  \"fixed_step\": " << jsonNumber(o.step) << ",\n"
       << "  \"report_interval\": " << jsonNumber(o.reportInterval) << ",\n"
       << "  \"lift_m\": " << jsonNumber(o.lift) << ",\n"
       << "  \"traverse_m\": " << jsonNumber(o.traverse) << ",\n"
       << "  \"t_end\": " << jsonNumber(o.tEnd) << ",\n"
       << "  \"t_reached\": " << jsonNumber(last.t) << ",\n"
       << "  \"termination\": \"" << (r.limit.empty() ? "completed" : "limit_reached") << "\",\n"
       << "  \"limit\": " << jsonString(r.limit) << ",\n"
       << "  \"static_fall_tension_N\": " << jsonArray(r.staticFallForce) << ",\n"
       << "  \"static_reference_tension_N\": " << jsonNumber((p.payloadMass + p.hookMass) * p.g / n) << ",\n"
       << "  \"max_fall_tension_N\": " << jsonArray(f.maxFall) << ",\n"
       << "  \"max_abs_sway_rad\": " << jsonNumber(f.maxSway) << ",\n"
       << "  \"max_abs_payload_angle_rad\": " << jsonNumber(f.maxPayloadAngle) << ",\n"
       << "  \"initial_hook_height_m\": " << jsonNumber(r.rows.front().hookY) << ",\n"
       << "  \"final_hook_height_m\": " << jsonNumber(last.hookY) << ",\n"
       << "  \"final_rope_on_drum_m\": " << jsonNumber(last.ropeOnDrum) << ",\n"
       << "  \"max_abs_motor_torque_Nm\": " << jsonNumber(f.maxTorque) << ",\n"
       << "  \"max_abs_motor_power_W\": " << jsonNumber(f.maxPower) << ",\n"
       << "  \"max_abs_trolley_force_N\": " << jsonNumber(f.maxTrolleyForce) << ",\n"
       << "  \"final_motion_work_J\": " << jsonNumber(last.work) << ",\n"
       << "  \"max_abs_motion_work_J\": " << jsonNumber(f.maxWork) << ",\n"
       << "  \"max_abs_energy_residual_J\": " << jsonNumber(f.maxResidual) << ",\n"
       << "  \"energy_residual_relative\": " << jsonNumber(f.maxWork > 0 ? f.maxResidual / f.maxWork : 0.0) << ",\n"
       << "  \"steps\": " << r.steps << ",\n"
       << "  \"rhs_evaluations\": " << r.rhsEvaluations << ",\n"
       << "  \"wall_seconds\": " << jsonNumber(r.wallSeconds) << ",\n"
       << "  \"real_time_factor\": " << jsonNumber(r.wallSeconds > 0 ? last.t / r.wallSeconds : 0.0) << ",\n"
       << "  \"snapshot_times\": " << jsonArray(snapshotTimes) << ",\n"
       << "  \"parameters\": {\"g\": " << jsonNumber(p.g) << ", \"railHeight\": " << jsonNumber(p.railHeight)
       << ", \"trolleyX0\": " << jsonNumber(p.trolleyX0) << ", \"trolleyMass\": " << jsonNumber(p.trolleyMass)
       << ", \"sheavePitch\": " << jsonNumber(p.sheavePitch) << ", \"sheaveRadius\": " << jsonNumber(p.sheaveRadius)
       << ", \"drumRadius\": " << jsonNumber(p.drumRadius) << ", \"drumHeight\": " << jsonNumber(p.drumHeight)
       << ", \"drumMass\": " << jsonNumber(p.drumMass) << ", \"drumInertia\": " << jsonNumber(p.drumInertia)
       << ", \"ropeOnDrum\": " << jsonNumber(p.ropeOnDrum) << ", \"hookMass\": " << jsonNumber(p.hookMass)
       << ", \"hookInertia\": " << jsonNumber(p.hookInertia) << ", \"hookComBelow\": " << jsonNumber(p.hookComBelow)
       << ", \"hookPinBelow\": " << jsonNumber(p.hookPinBelow)
       << ", \"initialHookDepth\": " << jsonNumber(p.initialHookDepth)
       << ", \"payloadMass\": " << jsonNumber(p.payloadMass) << ", \"payloadInertia\": " << jsonNumber(p.payloadInertia)
       << ", \"slingLength\": " << jsonNumber(p.slingLength) << ", \"payloadWidth\": " << jsonNumber(p.payloadWidth)
       << ", \"payloadHeight\": " << jsonNumber(p.payloadHeight) << ", \"rhoA\": " << jsonNumber(p.rhoA)
       << ", \"EA\": " << jsonNumber(p.EA) << ", \"EI\": " << jsonNumber(p.EI)
       << ", \"minimumSpanLength\": " << jsonNumber(p.minimumSpanLength) << "}\n"
       << "}\n";
    tsFile.commit();
    snFile.commit();
    jsFile.commit();  // last: a summary.json means the outputs are complete
}

}  // namespace

int main(int argc, char** argv) {
    Options o;
    try {
        o = parseCommandLine(argc, argv);
    } catch (const UsageError& e) {
        std::cerr << "reeving-crane: " << e.what() << "\nTry 'reeving-crane --help'.\n";
        return 2;
    }
    if (o.help) {
        std::cout << usage();
        return 0;
    }
    // The output folder must exist or be creatable, and be writable, before anything is simulated.
    if (!demo_common::prepareOutputFolder("reeving-crane", o.outDir)) return 2;
    demo_common::installInterruptHandlers();
    const auto start = std::chrono::steady_clock::now();

    SpanOptions spans;
    spans.axialModes = o.axialModes;
    spans.transverseModes = o.transverseModes;
    spans.axialDynamics = o.axialDynamics;
    spans.velocityModel = VelocityModel::Simplified;  // the library default before issue 19: the README's figures
    std::unique_ptr<CraneScene> scene;
    RunResult result;
    try {
        scene = std::make_unique<CraneScene>(o.parameters, CraneCycle::liftTraverseLower(o.lift, o.traverse), spans);
        result = run(o, *scene);
    } catch (const Interrupted& e) {
        std::cerr << "\nreeving-crane: interrupted at t = " << e.time << " s; no outputs written\n";
        return demo_common::kInterruptedExitStatus;
    } catch (const std::exception& e) {
        std::cerr << "reeving-crane: simulation failed: " << e.what() << "\n";
        return 1;
    }
    if (demo_common::interrupted()) {
        std::cerr << "reeving-crane: interrupted after the simulation; no outputs written\n";
        return demo_common::kInterruptedExitStatus;
    }

    const fs::path out(o.outDir);
    const Figures figures = summarize(result, scene->falls());
    try {
        writeOutputs(out, o, *scene, result, figures);
    } catch (const std::exception& e) {
        std::cerr << "reeving-crane: writing the outputs failed: " << e.what() << "\n";
        return 1;
    }
    const auto& p = scene->parameters();
    if (o.plots) makePlots(out, *scene, result.snapshots, (p.payloadMass + p.hookMass) * p.g / scene->falls());

    const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    const Row& last = result.rows.back();
    std::printf("reeving-crane: %d falls, n_a = %d, %.2f s simulated in %.2f s (%.0fx real time, %ld steps), "
                "max energy residual %.2e of the motion work, outputs in %s\n",
                scene->falls(), o.axialModes, last.t, wall, result.wallSeconds > 0 ? last.t / result.wallSeconds : 0.0,
                result.steps, figures.maxWork > 0 ? figures.maxResidual / figures.maxWork : 0.0, out.string().c_str());
    if (!result.limit.empty()) {
        std::string line = result.limit;
        std::replace(line.begin(), line.end(), '\n', ' ');
        std::cerr << "reeving-crane: rope limit reached at t = " << last.t << " s: " << line << "\n";
        return kLimitReachedExitStatus;
    }
    return 0;
}
