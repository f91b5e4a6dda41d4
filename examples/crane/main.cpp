// reeving-crane: an overhead (gantry) crane's lift-traverse-lower cycle from one
// command: a trolley with a prescribed traverse, a winch drum with a prescribed hoist profile, n
// falls of wire rope between trolley and hook block, a payload on a sling. Or (--scenario lift-off)
// the lift-off of a payload resting on the floor and its dynamic factor. See --help and README.md.
#include "CraneCli.h"
#include "CraneFigures.h"
#include "common/DemoOutput.h"
#include "common/DemoVisualizer.h"
#include "common/Interrupt.h"
#include "common/RopeLifeOutput.h"

#include <SimbodyReeving/scenes/CraneScene.h>
#include <SimbodyReeving/simbody/Integrators.h>
#include <SimbodyReeving/simbody/InterpolatingTimeStepper.h>
#include <SimbodyReeving/simbody/RopeLifeMonitor.h>
#include <SimbodyReeving/simbody/Visualization.h>

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

/// --max-steps reached: what() says when.
struct StepLimitReached : std::runtime_error {
    using std::runtime_error::runtime_error;
};

/// One report: the columns of timeseries.csv.
struct Row {
    double t, trolleyX, hookX, hookY, sway, payloadAngle;
    std::vector<double> falls;
    double drumSpeed, motorTorque, motorPower, ropeOnDrum, trolleyForce, trolleyPower, work, residual;
    double ropeForce;  // sum of the falls' top forces [N]
    double largestLean;               // largest angle of a fall's chord from the vertical [rad]
    std::vector<double> wrapAngles;   // per sheave 1..n-1 [rad] (0 with point sheaves)
    double ropeLengthError;           // spans + arcs + rope on the drum - (rope length + ropeOnDrum) [m]
    double floorForce = 0, slingForce = 0, contactDissipation = 0;  // lift-off
};

struct RunResult {
    std::vector<Row> rows;
    std::vector<Snapshot> snapshots;
    std::vector<double> staticFallForce;  // top of each fall at t = 0 [N]
    long steps = 0, rhsEvaluations = 0;
    double wallSeconds = 0, energy0 = 0;
    std::string limit;  // "" or the rope limit that ended the run
    std::vector<demo_common::RopePathPoint> ropeAtStart;  // the rope drawn at t = 0, for rope_bending.png
    std::vector<double> nodesAtStart;                    // its nodes' material coordinates at t = 0
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
    r.ropeForce = 0;
    for (double f : r.falls) r.ropeForce += f;
    r.largestLean = scene.largestFallLean(s);
    for (int k = 1; k < scene.falls(); ++k) r.wrapAngles.push_back(scene.sheaveWrapAngle(s, k));
    r.ropeLengthError = scene.ropeLengthError(s);
    if (scene.parameters().scenario == CraneScenario::LiftOff) {
        r.floorForce = scene.floorForce(s);
        r.slingForce = scene.slingForce(s);
        r.contactDissipation = scene.contactDissipation(s);
        r.residual += r.contactDissipation;  // E - E0 + W_contact - W_motion
    }
    return r;
}

// What the lift-off is doing: the sling slack, the load on the floor or lifted.
std::string liftOffPhase(const CraneScene& scene, const State& s) {
    if (scene.slingForce(s) <= 0) return "sling slack";
    return scene.floorForce(s) > 0 ? "load on the floor" : "load lifted";
}

RunResult run(const Options& o, CraneScene& scene, RopeLifeMonitor& life) {
    RunResult r;
    State s0 = scene.makeInitialState();
    scene.system().realize(s0, Stage::Acceleration);
    for (int k = 0; k < scene.falls(); ++k) r.staticFallForce.push_back(scene.fallTopForce(s0, k));
    r.energy0 = scene.reeving().calcMechanicalEnergy(s0);
    demo_common::DemoVisualizer viz(scene.system(), scene.reeving(), "reeving-crane", o.visualize);
    const SimTK::Vec3 centre(scene.parameters().trolleyX0 + (o.liftOff() ? 0.0 : 0.5 * o.traverse),
                             0.55 * scene.parameters().railHeight, 0);
    viz.lookAt(centre + SimTK::Vec3(-11, 2, 21), centre);  // oblique: the drum's stored rope shows
    viz.report(s0);

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
    const bool liftOff = scene.parameters().scenario == CraneScenario::LiftOff;
    auto phase = [&](const State& s) { return liftOff ? liftOffPhase(scene, s) : phaseAt(scene.cycle(), s.getTime()); };
    const auto start = std::chrono::steady_clock::now();
    auto lastPrint = start;
    bool printed = false;
    r.rows.push_back(observe(scene, ts.getState(), r.energy0));
    life.record(ts.getState());
    r.ropeAtStart = demo_common::sampleRopePath(scene.reeving(), ts.getState(), 0, 41);
    r.nodesAtStart = demo_common::nodeMaterialCoordinates(scene.reeving(), ts.getState(), 0);
    if (std::count(snapshotReports.begin(), snapshotReports.end(), 0)) snap(ts.getState(), phase(ts.getState()));
    for (int n = 1; n <= reports; ++n) {
        if (demo_common::interrupted()) throw Interrupted(ts.getState().getTime());
        const double target = n * o.reportInterval;
        try {
            // --max-steps: the stepper returns once the integrator has taken the steps left.
            for (;;) {
                if (o.maxSteps > 0) {
                    const long left = o.maxSteps - integ->getNumStepsTaken();
                    if (left <= 0)
                        throw StepLimitReached("the integrator took --max-steps " + std::to_string(o.maxSteps) +
                                               " steps at t = " + demo_common::numberText(ts.getState().getTime()) +
                                               " s, before the end (" + demo_common::numberText(o.tEnd) + " s)");
                    ts.setStepLimit(static_cast<int>(std::min<long>(left, 1000000000L)));
                }
                if (ts.stepTo(target) != SimTK::Integrator::ReachedStepLimit) break;
            }
        } catch (const StepLimitReached&) {
            throw;
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
        life.record(st);
        viz.report(st);
        if (!scene.reeving().getLimitReached().empty() || integ->isSimulationOver()) {
            // A rope limit (two-blocking, empty drum) requested termination: the run ends here.
            r.limit = scene.reeving().getLimitReached();
            if (r.limit.empty()) r.limit = "the integrator ended the simulation at t = " + std::to_string(st.getTime()) + " s";
            snap(st, "limit reached");
            break;
        }
        if (std::count(snapshotReports.begin(), snapshotReports.end(), n)) snap(st, phase(st));
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
    viz.close();  // the window closes and its process ends with the run
    r.wallSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    r.steps = integ->getNumStepsTaken();
    r.rhsEvaluations = ts.getNumRealizations();
    return r;
}

struct Figures {
    std::vector<double> maxFall;
    double maxLean = 0, maxRopeLengthError = 0;
    std::vector<double> minWrap, maxWrap;  // per sheave 1..n-1 [rad]
    double maxSway = 0, maxPayloadAngle = 0, maxTorque = 0, maxPower = 0, maxTrolleyForce = 0;
    double maxResidual = 0, maxWork = 0;
    double peakRopeForce = 0, peakRopeForceTime = 0;
    double liftOffTime = SimTK::NaN;  // lift-off: see summarize
};

Figures summarize(const RunResult& r, int falls) {
    Figures f;
    f.maxFall.assign(falls, 0.0);
    for (const Row& w : r.rows) {
        for (int k = 0; k < falls; ++k) f.maxFall[k] = std::max(f.maxFall[k], w.falls[k]);
        f.maxSway = std::max(f.maxSway, std::abs(w.sway));
        f.maxLean = std::max(f.maxLean, w.largestLean);
        f.maxRopeLengthError = std::max(f.maxRopeLengthError, std::abs(w.ropeLengthError));
        if (f.minWrap.empty()) f.minWrap = f.maxWrap = w.wrapAngles;
        for (size_t k = 0; k < w.wrapAngles.size(); ++k) {
            f.minWrap[k] = std::min(f.minWrap[k], w.wrapAngles[k]);
            f.maxWrap[k] = std::max(f.maxWrap[k], w.wrapAngles[k]);
        }
        f.maxPayloadAngle = std::max(f.maxPayloadAngle, std::abs(w.payloadAngle));
        f.maxTorque = std::max(f.maxTorque, std::abs(w.motorTorque));
        f.maxPower = std::max(f.maxPower, std::abs(w.motorPower));
        f.maxTrolleyForce = std::max(f.maxTrolleyForce, std::abs(w.trolleyForce));
        f.maxResidual = std::max(f.maxResidual, std::abs(w.residual));
        f.maxWork = std::max(f.maxWork, std::abs(w.work));
        if (w.ropeForce > f.peakRopeForce) {
            f.peakRopeForce = w.ropeForce;
            f.peakRopeForceTime = w.t;
        }
    }
    // Lift-off: the last time before the peak rope force that the floor's force fell to zero (the
    // payload may bounce on the floor as the sling jerks taut): where the floor force's trend over
    // the two reports before reaches zero, within the report interval (the force is clamped at 0).
    for (size_t i = 1; i < r.rows.size() && r.rows[i].t <= f.peakRopeForceTime; ++i) {
        const Row &a = r.rows[i - 1], &b = r.rows[i];
        if (!(a.floorForce > 0 && b.floorForce <= 0)) continue;
        f.liftOffTime = b.t;
        if (i >= 2 && r.rows[i - 2].floorForce > a.floorForce) {
            const Row& before = r.rows[i - 2];
            f.liftOffTime = std::min(b.t, a.t + a.floorForce * (a.t - before.t) / (before.floorForce - a.floorForce));
        }
    }
    return f;
}

void writeOutputs(const fs::path& dir, const Options& o, const CraneScene& scene, const RunResult& r, const Figures& f,
                  const RopeLifeMonitor& life) {
    const int n = scene.falls();
    OutputFile tsFile(dir / "timeseries.csv"), snFile(dir / "snapshots.dat"), jsFile(dir / "summary.json"),
        bendFile(dir / "rope_bending.csv"), bendFigureFile(dir / "rope_bending.dat");
    std::ofstream& ts = tsFile.stream();
    ts << "t,trolley_x,hook_x,hook_height,sway,payload_angle";
    for (int k = 1; k <= n; ++k) ts << ",fall_" << k;
    const bool liftOff = scene.parameters().scenario == CraneScenario::LiftOff;
    ts << ",drum_speed,motor_torque,motor_power,rope_on_drum,trolley_force,trolley_power,motion_work,energy_residual"
       << (liftOff ? ",rope_force,floor_force,sling_force,contact_dissipation" : "") << "\n"
       << std::setprecision(12);
    for (const Row& w : r.rows) {
        ts << w.t << ',' << w.trolleyX << ',' << w.hookX << ',' << w.hookY << ',' << w.sway << ',' << w.payloadAngle;
        for (double x : w.falls) ts << ',' << x;
        ts << ',' << w.drumSpeed << ',' << w.motorTorque << ',' << w.motorPower << ',' << w.ropeOnDrum << ','
           << w.trolleyForce << ',' << w.trolleyPower << ',' << w.work << ',' << w.residual;
        if (liftOff) ts << ',' << w.ropeForce << ',' << w.floorForce << ',' << w.slingForce << ',' << w.contactDissipation;
        ts << '\n';
    }
    writeSnapshots(snFile.stream(), r.snapshots);
    demo_common::writeRopeBendingCsv(bendFile.stream(), life);
    demo_common::writeRopeBendingFigureData(bendFigureFile.stream(), r.ropeAtStart, r.nodesAtStart, life);

    const auto& p = scene.parameters();
    const Row& last = r.rows.back();
    std::vector<double> snapshotTimes;
    for (const Snapshot& s : r.snapshots) snapshotTimes.push_back(s.t);
    using demo_common::jsonNumber;
    auto jsonArray = [](const std::vector<double>& v) {
        demo_common::Json a = demo_common::Json::array();
        for (double x : v) a.push_back(jsonNumber(x));
        return a;
    };
    // The fall forces are axial forces P = EA eps at the top of each fall (CraneScene::fallTopForce),
    // not tensions T = P |dr/ds|; the reference is the static share of the hook load, (M + m_hook) g / n.
    demo_common::Json js;
    js["program"] = "reeving-crane";
    js["scenario"] = toString(p.scenario);
    js["falls"] = n;
    js["sheaves"] = p.sheaveModel == SimbodyReeving::SheaveModel::Wrapped ? "wrapped" : "point";
    js["axial_modes"] = o.axialModes;
    js["transverse_modes"] = o.transverseModes;
    js["axial_dynamics"] = axialDynamicsName(o.axialDynamics);
    js["axial_law"] = o.parameters.tensionOnly ? "tension-only" : "linear";
    js["integrator"] = o.integrator;
    js["accuracy"] = jsonNumber(o.accuracy);
    js["fixed_step"] = jsonNumber(o.step);
    js["report_interval"] = jsonNumber(o.reportInterval);
    js["lift_m"] = jsonNumber(o.lift);  // the cycle's (unused in lift-off)
    js["traverse_m"] = jsonNumber(o.traverse);
    js["t_end"] = jsonNumber(o.tEnd);
    js["t_reached"] = jsonNumber(last.t);
    js["termination"] = r.limit.empty() ? "completed" : "limit_reached";
    js["limit"] = r.limit;
    js["static_fall_axial_force_N"] = jsonArray(r.staticFallForce);
    js["static_reference_axial_force_N"] = jsonNumber((p.payloadMass + p.hookMass) * p.g / n);
    js["max_fall_axial_force_N"] = jsonArray(f.maxFall);
    // The hoist rope's force on the trolley, all falls at their tops [N] (CraneScene::ropeForce):
    // its static value with the load hanging at rest, (M + m_hook) g + rhoA g (the falls' length),
    // its largest value at the reports and their ratio, the dynamic factor.
    js["static_rope_force"] = jsonNumber(scene.staticRopeForce());
    js["peak_rope_force"] = jsonNumber(f.peakRopeForce);
    js["peak_rope_force_time"] = jsonNumber(f.peakRopeForceTime);
    js["dynamic_factor"] = jsonNumber(f.peakRopeForce / scene.staticRopeForce());
    if (liftOff) {
        js["hoist_speed"] = jsonNumber(p.hoistSpeed);
        js["lift_off_time"] = jsonNumber(f.liftOffTime);
        js["hook_stiffness_N_per_m"] = jsonNumber(scene.hookStiffness());
        js["spring_mass_dynamic_factor"] = jsonNumber(scene.springMassDynamicFactor());
        js["rope_slack_m"] = jsonNumber(scene.ropeSlack());
        js["floor_height_m"] = jsonNumber(scene.floorHeight());
        js["final_contact_dissipation_J"] = jsonNumber(last.contactDissipation);
    }
    js["max_abs_sway_rad"] = jsonNumber(f.maxSway);
    // Falls' lean: the largest angle of a fall's chord from the vertical, at rest (t = 0) and over
    // the reports [deg]. Wrap angles: per sheave 1..n-1, their range over the reports [rad] (0 with
    // point sheaves); fleet angles are 0 (planar rope). Rope length: the largest |spans + arcs +
    // rope on the drum - their initial sum| over the reports [m].
    js["initial_largest_fall_lean_deg"] = jsonNumber(r.rows.front().largestLean * 180.0 / SimTK::Pi);
    js["max_largest_fall_lean_deg"] = jsonNumber(f.maxLean * 180.0 / SimTK::Pi);
    {
        demo_common::Json w = demo_common::Json::array();
        for (size_t k = 0; k < f.minWrap.size(); ++k)
            w.push_back({{"sheave", k + 1}, {"min_rad", jsonNumber(f.minWrap[k])}, {"max_rad", jsonNumber(f.maxWrap[k])}});
        js["sheave_wrap_angles"] = w;
    }
    js["max_fleet_angle_rad"] = jsonNumber(0.0);
    js["max_abs_rope_length_error_m"] = jsonNumber(f.maxRopeLengthError);
    js["max_abs_payload_angle_rad"] = jsonNumber(f.maxPayloadAngle);
    js["initial_hook_height_m"] = jsonNumber(r.rows.front().hookY);
    js["final_hook_height_m"] = jsonNumber(last.hookY);
    js["final_rope_on_drum_m"] = jsonNumber(last.ropeOnDrum);
    js["max_abs_motor_torque_Nm"] = jsonNumber(f.maxTorque);
    js["max_abs_motor_power_W"] = jsonNumber(f.maxPower);
    js["max_abs_trolley_force_N"] = jsonNumber(f.maxTrolleyForce);
    js["final_motion_work_J"] = jsonNumber(last.work);
    js["max_abs_motion_work_J"] = jsonNumber(f.maxWork);
    js["max_abs_energy_residual_J"] = jsonNumber(f.maxResidual);
    js["energy_residual_relative"] = jsonNumber(f.maxWork > 0 ? f.maxResidual / f.maxWork : 0.0);
    // The most bent rope section over the run (no life law: the demo has no rope constants).
    js["rope_life"] = demo_common::ropeLifeSummary(life, o.ropeLife);
    js["steps"] = r.steps;
    js["rhs_evaluations"] = r.rhsEvaluations;
    js["wall_seconds"] = jsonNumber(r.wallSeconds);
    js["real_time_factor"] = jsonNumber(r.wallSeconds > 0 ? last.t / r.wallSeconds : 0.0);
    js["snapshot_times"] = jsonArray(snapshotTimes);
    demo_common::Json& params = js["parameters"];
    params["g"] = jsonNumber(p.g);
    params["railHeight"] = jsonNumber(p.railHeight);
    params["trolleyX0"] = jsonNumber(p.trolleyX0);
    params["trolleyMass"] = jsonNumber(p.trolleyMass);
    params["sheavePitch"] = jsonNumber(p.sheavePitch);
    params["sheaveRadius"] = jsonNumber(p.sheaveRadius);
    params["drumRadius"] = jsonNumber(p.drumRadius);
    params["drumHeight"] = jsonNumber(p.drumHeight);
    params["drumMass"] = jsonNumber(p.drumMass);
    params["drumInertia"] = jsonNumber(p.drumInertia);
    params["ropeOnDrum"] = jsonNumber(p.ropeOnDrum);
    params["hookMass"] = jsonNumber(p.hookMass);
    params["hookInertia"] = jsonNumber(p.hookInertia);
    params["hookComBelow"] = jsonNumber(p.hookComBelow);
    params["hookPinBelow"] = jsonNumber(p.hookPinBelow);
    params["initialHookDepth"] = jsonNumber(p.initialHookDepth);
    params["payloadMass"] = jsonNumber(p.payloadMass);
    params["payloadInertia"] = jsonNumber(p.payloadInertia);
    params["slingLength"] = jsonNumber(p.slingLength);
    params["payloadWidth"] = jsonNumber(p.payloadWidth);
    params["payloadHeight"] = jsonNumber(p.payloadHeight);
    params["rhoA"] = jsonNumber(p.rhoA);
    params["EA"] = jsonNumber(p.EA);
    params["EI"] = jsonNumber(p.EI);
    params["minimumSpanLength"] = jsonNumber(p.minimumSpanLength);
    if (liftOff) {
        params["hoistSpeed"] = jsonNumber(p.hoistSpeed);
        params["hoistRamp"] = jsonNumber(p.hoistRamp);
        params["slackTime"] = jsonNumber(p.slackTime);
        params["afterLiftOff"] = jsonNumber(p.afterLiftOff);
        params["floorStiffness"] = jsonNumber(p.floorStiffness);
        params["floorDampingRatio"] = jsonNumber(p.floorDampingRatio);
        params["slingStiffness"] = jsonNumber(p.slingStiffness);
        params["slingDampingRatio"] = jsonNumber(p.slingDampingRatio);
    }
    demo_common::writeJson(jsFile.stream(), js);
    tsFile.commit();
    snFile.commit();
    bendFile.commit();
    bendFigureFile.commit();
    jsFile.commit();  // last: a summary.json means the outputs are complete
}

}  // namespace

int main(int argc, char** argv) {
    Options o;
    try {
        o = parseCommandLine(argc, argv);
    } catch (const UsageError& e) {
        std::cerr << demo_common::usageErrorText("reeving-crane", e.what());
        return demo_common::kUsageExitStatus;
    }
    if (o.help) {
        std::cout << usage();
        return 0;
    }
    // The scene (every parameter's validation; --check: and the integrator), before anything is
    // written: a value only the scene can judge is a bad command line too.
    SpanOptions spans;
    spans.axialModes = o.axialModes;
    spans.transverseModes = o.transverseModes;
    spans.axialDynamics = o.axialDynamics;
    std::unique_ptr<CraneScene> scene;
    std::unique_ptr<RopeLifeMonitor> life;
    try {
        scene = std::make_unique<CraneScene>(o.parameters, o.cycle(), spans);
        life = std::make_unique<RopeLifeMonitor>(scene->reeving(), 0, o.ropeLife.options());
        if (o.check) makeIntegrator(o.integrator, scene->system());
    } catch (const std::exception& e) {
        std::cerr << demo_common::usageErrorText("reeving-crane", e.what());
        return demo_common::kUsageExitStatus;
    }
    if (o.check) return 0;
    // The output folder must exist or be creatable, and be writable, before anything is simulated.
    if (!demo_common::prepareOutputFolder("reeving-crane", o.outDir)) return demo_common::kUsageExitStatus;
    demo_common::installInterruptHandlers();
    const auto start = std::chrono::steady_clock::now();

    RunResult result;
    try {
        result = run(o, *scene, *life);
    } catch (const Interrupted& e) {
        std::cerr << "\nreeving-crane: interrupted at t = " << e.time << " s; no outputs written\n";
        return demo_common::kInterruptedExitStatus;
    } catch (const StepLimitReached& e) {
        std::cerr << "reeving-crane: stopped: " << e.what() << "; nothing written\n";
        return 1;
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
        writeOutputs(out, o, *scene, result, figures, *life);
    } catch (const std::exception& e) {
        std::cerr << "reeving-crane: writing the outputs failed: " << e.what() << "\n";
        return 1;
    }
    const auto& p = scene->parameters();
    if (o.plots) makePlots(out, *scene, result.snapshots, (p.payloadMass + p.hookMass) * p.g / scene->falls());
    if (o.liftOff())
        std::printf("reeving-crane: lift-off at t = %.4f s, dynamic factor %.4f (peak rope force %.1f kN over the "
                    "static %.1f kN; spring-mass reference 1 + v_h sqrt(k / M) / g = %.4f)\n",
                    figures.liftOffTime, figures.peakRopeForce / scene->staticRopeForce(), figures.peakRopeForce / 1000,
                    scene->staticRopeForce() / 1000, scene->springMassDynamicFactor());

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
