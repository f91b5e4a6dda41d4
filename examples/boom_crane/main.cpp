// reeving-boom-crane: a slewing, luffing boom crane's lift-slew-lower cycle from one command: a
// superstructure slewing on a ring, a boom held by three falls of its luffing rope, a two-fall hoist
// rope to a hook block, a payload on a sling; both ropes spatial, so the slew swings the load out
// of the boom's plane and the ropes run onto the grooves at fleet angles. See --help and README.md.
#include "BoomCraneCli.h"
#include "BoomCraneFigures.h"
#include "common/DemoOutput.h"
#include "common/DemoVisualizer.h"
#include "common/Interrupt.h"
#include "common/RopeLifeOutput.h"

#include <SimbodyReeving/scenes/BoomCraneScene.h>
#include <SimbodyReeving/simbody/Integrators.h>
#include <SimbodyReeving/simbody/InterpolatingTimeStepper.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <memory>

namespace fs = std::filesystem;
using SimTK::Stage;
using SimTK::State;
using namespace boom_crane_demo;
using namespace SimbodyReeving;
using demo_common::OutputFile;

namespace {

constexpr int kRopes = 2;
constexpr int kSpans = BoomCraneScene::kSpans;
constexpr int kSheaves = 3;  // per rope, nodes 1..3
const char* const kRopeKeys[kRopes] = {"luffing", "hoist"};
const char* const kRopeNames[kRopes] = {"luffing rope", "hoist rope"};
// Sheave names per rope, nodes 1..3 (timeseries.csv's wrap_<name>_rad columns).
const char* const kSheaveNames[kRopes][kSheaves] = {{"a_frame_1", "luffing_tip", "a_frame_2"}, {"foot", "hoist_tip", "hook"}};

struct Interrupted : std::runtime_error {
    explicit Interrupted(double t) : std::runtime_error("interrupted"), time(t) {}
    double time;
};

/// --max-steps reached: what() says when.
struct StepLimitReached : std::runtime_error {
    using std::runtime_error::runtime_error;
};

/// The three prescribed drives: slewing ring, luffing drum, hoist drum.
enum Drive { Slew = 0, Luff = 1, Hoist = 2 };
const char* const kDriveKeys[3] = {"slew", "luff", "hoist"};

/// One report: the columns of timeseries.csv.
struct Row {
    double t = 0, slewAngle = 0, boomAngle = 0, hookRadius = 0, swingInPlane = 0, swingOutOfPlane = 0;
    SimTK::Vec3 hook{0};
    std::array<std::array<double, kSpans>, kRopes> spanForce{};
    std::array<double, kRopes> largestFleet{}, drumFleet{}, ropeOnDrum{};
    std::array<std::array<double, kSheaves>, kRopes> wrap{};
    std::array<double, 3> torque{}, power{};
    double work = 0, residual = 0;
};

struct RunResult {
    std::vector<Row> rows;
    std::vector<Snapshot> snapshots;
    long steps = 0, rhsEvaluations = 0;
    double wallSeconds = 0, energy0 = 0;
    std::string limit;  // "" or the rope limit that ended the run
    // Each rope drawn at t = 0 and its nodes' material coordinates, for fig_rope_bending_<rope>.png.
    std::array<std::vector<demo_common::RopePathPoint>, kRopes> ropeAtStart;
    std::array<std::vector<double>, kRopes> nodesAtStart;
};

/// The bending counts of both ropes (RopeLifeMonitor; index: BoomCraneScene::kLuffingRope, kHoistRope).
using RopeLifeMonitors = std::array<std::unique_ptr<RopeLifeMonitor>, kRopes>;

Row observe(const BoomCraneScene& scene, const State& s, double energy0) {
    // Stage::Acceleration: the drives' generalized forces (and the QuasiStatic force correction).
    scene.system().realize(s, Stage::Acceleration);
    Row r;
    r.t = s.getTime();
    r.slewAngle = scene.slewAngle(s);
    r.boomAngle = scene.boomAngle(s);
    r.hook = scene.hookPosition(s);
    r.hookRadius = scene.hookRadius(s);
    r.swingInPlane = scene.inPlaneSwing(s);
    r.swingOutOfPlane = scene.outOfPlaneSwing(s);
    for (int rope = 0; rope < kRopes; ++rope) {
        for (int k = 0; k < kSpans; ++k) r.spanForce[rope][k] = scene.spanForce(s, rope, k);
        r.largestFleet[rope] = scene.largestFleetAngle(s, rope);
        r.drumFleet[rope] = scene.drumFleetAngle(s, rope);
        for (int k = 1; k <= kSheaves; ++k) r.wrap[rope][k - 1] = scene.wrapAngle(s, rope, k);
        r.ropeOnDrum[rope] = scene.ropeOnDrum(s, rope);
    }
    r.torque = {scene.slewTorque(s), scene.luffTorque(s), scene.hoistTorque(s)};
    r.power = {r.torque[Slew] * scene.superstructure().getOneU(s, 0), r.torque[Luff] * scene.luffDrum().getOneU(s, 0),
               r.torque[Hoist] * scene.hoistDrum().getOneU(s, 0)};
    r.work = scene.workMeter().getWork(s);
    r.residual = scene.energyResidual(s, energy0);
    return r;
}

Snapshot snapshotOf(const BoomCraneScene& scene, const State& s, const std::string& phase) {
    return {s.getTime(), phase, boomPlaneDirection(scene, s), drawBoomCrane(scene, s)};
}

RunResult run(const Options& o, BoomCraneScene& scene, RopeLifeMonitors& life) {
    RunResult r;
    State s0 = scene.makeInitialState();
    r.energy0 = scene.reeving().calcMechanicalEnergy(s0);
    demo_common::DemoVisualizer viz(scene.system(), scene.reeving(), "reeving-boom-crane", o.visualize);
    const auto& p = scene.parameters();
    const SimTK::Vec3 centre(0.3 * p.boomLength, 0.4 * p.boomLength, 0);
    viz.lookAt(centre + SimTK::Vec3(18, 8, 40), centre);  // oblique: the slew to -z shows
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
    auto wanted = [&](int n) { return std::count(snapshotReports.begin(), snapshotReports.end(), n) > 0; };
    const auto start = std::chrono::steady_clock::now();
    auto lastPrint = start;
    bool printed = false;
    r.rows.push_back(observe(scene, ts.getState(), r.energy0));
    for (int rope = 0; rope < kRopes; ++rope) {
        life[rope]->record(ts.getState());
        r.ropeAtStart[rope] = demo_common::sampleRopePath(scene.reeving(), ts.getState(), rope, 41);
        r.nodesAtStart[rope] = demo_common::nodeMaterialCoordinates(scene.reeving(), ts.getState(), rope);
    }
    if (wanted(0)) r.snapshots.push_back(snapshotOf(scene, ts.getState(), phaseAt(scene.cycle(), 0)));
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
        for (auto& monitor : life) monitor->record(st);
        viz.report(st);
        if (!scene.reeving().getLimitReached().empty() || integ->isSimulationOver()) {
            // A rope limit (two-blocking, empty drum, fleet angle) requested termination: the run ends here.
            r.limit = scene.reeving().getLimitReached();
            if (r.limit.empty()) r.limit = "the integrator ended the simulation at t = " + std::to_string(st.getTime()) + " s";
            r.snapshots.push_back(snapshotOf(scene, st, "limit reached"));
            break;
        }
        if (wanted(n)) r.snapshots.push_back(snapshotOf(scene, st, phaseAt(scene.cycle(), st.getTime())));
        const auto now = std::chrono::steady_clock::now();
        if (!o.quiet && std::chrono::duration<double>(now - start).count() > 2.0 &&
            std::chrono::duration<double>(now - lastPrint).count() > 1.0) {
            std::fprintf(stderr, "\rreeving-boom-crane: t = %.1f of %.1f s, wall %.1f s", st.getTime(), o.tEnd,
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

/// Extremes over the reports.
struct Figures {
    std::array<std::array<double, kSpans>, kRopes> maxSpanForce{};
    std::array<double, kRopes> maxFleet{}, maxDrumFleet{};
    std::array<std::array<double, kSheaves>, kRopes> minWrap{}, maxWrap{};
    std::array<double, 3> maxTorque{}, maxPower{};
    double maxSwingOut = 0, maxSwingIn = 0, minHookRadius = 0, maxHookRadius = 0, maxBoomAngle = 0, minBoomAngle = 0;
    double maxResidual = 0, maxWork = 0;
    double residualRelative() const { return maxWork > 0 ? maxResidual / maxWork : 0.0; }
};

Figures summarize(const RunResult& r) {
    Figures f;
    const Row& first = r.rows.front();
    f.minWrap = f.maxWrap = first.wrap;
    f.maxSpanForce = first.spanForce;
    f.minHookRadius = f.maxHookRadius = first.hookRadius;
    f.minBoomAngle = f.maxBoomAngle = first.boomAngle;
    for (const Row& w : r.rows) {
        for (int rope = 0; rope < kRopes; ++rope) {
            for (int k = 0; k < kSpans; ++k) f.maxSpanForce[rope][k] = std::max(f.maxSpanForce[rope][k], w.spanForce[rope][k]);
            f.maxFleet[rope] = std::max(f.maxFleet[rope], w.largestFleet[rope]);
            f.maxDrumFleet[rope] = std::max(f.maxDrumFleet[rope], w.drumFleet[rope]);
            for (int k = 0; k < kSheaves; ++k) {
                f.minWrap[rope][k] = std::min(f.minWrap[rope][k], w.wrap[rope][k]);
                f.maxWrap[rope][k] = std::max(f.maxWrap[rope][k], w.wrap[rope][k]);
            }
        }
        for (int d = 0; d < 3; ++d) {
            f.maxTorque[d] = std::max(f.maxTorque[d], std::abs(w.torque[d]));
            f.maxPower[d] = std::max(f.maxPower[d], std::abs(w.power[d]));
        }
        f.maxSwingOut = std::max(f.maxSwingOut, std::abs(w.swingOutOfPlane));
        f.maxSwingIn = std::max(f.maxSwingIn, std::abs(w.swingInPlane));
        f.minHookRadius = std::min(f.minHookRadius, w.hookRadius);
        f.maxHookRadius = std::max(f.maxHookRadius, w.hookRadius);
        f.minBoomAngle = std::min(f.minBoomAngle, w.boomAngle);
        f.maxBoomAngle = std::max(f.maxBoomAngle, w.boomAngle);
        f.maxResidual = std::max(f.maxResidual, std::abs(w.residual));
        f.maxWork = std::max(f.maxWork, std::abs(w.work));
    }
    return f;
}

void writeTimeseries(std::ostream& ts, const RunResult& r) {
    ts << "t,slew_angle_rad,boom_angle_rad,hook_x_m,hook_y_m,hook_z_m,hook_radius_m,swing_in_plane_rad,"
          "swing_out_of_plane_rad";
    for (int rope = 0; rope < kRopes; ++rope)
        for (int k = 1; k <= kSpans; ++k) ts << ',' << kRopeKeys[rope] << "_span_" << k << "_N";
    for (int rope = 0; rope < kRopes; ++rope) ts << ',' << kRopeKeys[rope] << "_fleet_max_rad";
    for (int rope = 0; rope < kRopes; ++rope) ts << ',' << kRopeKeys[rope] << "_drum_fleet_rad";
    for (int rope = 0; rope < kRopes; ++rope)
        for (int k = 0; k < kSheaves; ++k) ts << ",wrap_" << kSheaveNames[rope][k] << "_rad";
    for (const char* d : kDriveKeys) ts << ',' << d << "_torque_Nm";
    for (const char* d : kDriveKeys) ts << ',' << d << "_power_W";
    for (int rope = 0; rope < kRopes; ++rope) ts << ',' << kRopeKeys[rope] << "_rope_on_drum_m";
    ts << ",motion_work_J,energy_residual_J\n" << std::setprecision(12);
    for (const Row& w : r.rows) {
        ts << w.t << ',' << w.slewAngle << ',' << w.boomAngle << ',' << w.hook[0] << ',' << w.hook[1] << ',' << w.hook[2]
           << ',' << w.hookRadius << ',' << w.swingInPlane << ',' << w.swingOutOfPlane;
        for (const auto& forces : w.spanForce)
            for (double x : forces) ts << ',' << x;
        for (double x : w.largestFleet) ts << ',' << x;
        for (double x : w.drumFleet) ts << ',' << x;
        for (const auto& wraps : w.wrap)
            for (double x : wraps) ts << ',' << x;
        for (double x : w.torque) ts << ',' << x;
        for (double x : w.power) ts << ',' << x;
        for (double x : w.ropeOnDrum) ts << ',' << x;
        ts << ',' << w.work << ',' << w.residual << '\n';
    }
}

demo_common::Json vec3Json(const SimTK::Vec3& v) {
    using demo_common::jsonNumber;
    return demo_common::Json::array({jsonNumber(v[0]), jsonNumber(v[1]), jsonNumber(v[2])});
}

demo_common::Json parametersJson(const BoomCraneParameters& p) {
    using demo_common::jsonNumber;
    demo_common::Json j;
    j["g"] = jsonNumber(p.g);
    j["superstructureMass"] = jsonNumber(p.superstructureMass);
    j["superstructureInertia"] = jsonNumber(p.superstructureInertia);
    j["boomFoot"] = vec3Json(p.boomFoot);
    j["boomLength"] = jsonNumber(p.boomLength);
    j["boomMass"] = jsonNumber(p.boomMass);
    j["boomAngle"] = jsonNumber(p.boomAngle);
    j["aFrameTop"] = vec3Json(p.aFrameTop);
    j["luffDrumCentre"] = vec3Json(p.luffDrumCentre);
    j["luffSheaveRadius"] = jsonNumber(p.luffSheaveRadius);
    j["luffSheaveSpacing"] = jsonNumber(p.luffSheaveSpacing);
    j["hoistDrumCentre"] = vec3Json(p.hoistDrumCentre);
    j["footSheaveOffset"] = jsonNumber(p.footSheaveOffset);
    j["footSheaveHeight"] = jsonNumber(p.footSheaveHeight);
    j["hoistSheaveRadius"] = jsonNumber(p.hoistSheaveRadius);
    j["drumRadius"] = jsonNumber(p.drumRadius);
    j["drumMass"] = jsonNumber(p.drumMass);
    j["drumInertia"] = jsonNumber(p.drumInertia);
    j["ropeOnDrum"] = jsonNumber(p.ropeOnDrum);
    j["drumPitch"] = jsonNumber(p.drumPitch);
    j["hookMass"] = jsonNumber(p.hookMass);
    j["hookInertia"] = jsonNumber(p.hookInertia);
    j["hookComBelow"] = jsonNumber(p.hookComBelow);
    j["hookPinBelow"] = jsonNumber(p.hookPinBelow);
    j["initialHookDepth"] = jsonNumber(p.initialHookDepth);
    j["payloadMass"] = jsonNumber(p.payloadMass);
    j["payloadInertia"] = jsonNumber(p.payloadInertia);
    j["slingLength"] = jsonNumber(p.slingLength);
    j["rhoA"] = jsonNumber(p.rhoA);
    j["EA"] = jsonNumber(p.EA);
    j["EI"] = jsonNumber(p.EI);
    j["minimumSpanLength"] = jsonNumber(p.minimumSpanLength);
    return j;
}

void writeOutputs(const fs::path& dir, const Options& o, const BoomCraneScene& scene, const RunResult& r, const Figures& f,
                  const RopeLifeMonitors& life) {
    OutputFile tsFile(dir / "timeseries.csv"), snFile(dir / "snapshots.dat"), jsFile(dir / "summary.json");
    std::vector<std::unique_ptr<OutputFile>> bendFiles;
    for (int rope = 0; rope < kRopes; ++rope) {
        const std::string base = std::string("rope_bending_") + kRopeKeys[rope];
        bendFiles.push_back(std::make_unique<OutputFile>(dir / (base + ".csv")));
        demo_common::writeRopeBendingCsv(bendFiles.back()->stream(), *life[rope]);
        bendFiles.push_back(std::make_unique<OutputFile>(dir / (base + ".dat")));
        demo_common::writeRopeBendingFigureData(bendFiles.back()->stream(), r.ropeAtStart[rope], r.nodesAtStart[rope],
                                                *life[rope]);
    }
    writeTimeseries(tsFile.stream(), r);
    writeSnapshots(snFile.stream(), r.snapshots);

    const auto& p = scene.parameters();
    const Row &first = r.rows.front(), &last = r.rows.back();
    const double deg = 180.0 / SimTK::Pi;
    using demo_common::Json;
    using demo_common::jsonNumber;
    auto jsonArray = [](const auto& v) {
        Json a = Json::array();
        for (double x : v) a.push_back(jsonNumber(x));
        return a;
    };
    // Span forces are axial forces P = EA eps at the top of each span (BoomCraneScene::spanForce),
    // not tensions T = P |dr/ds|; the hoist rope's reference is the static share of the hook load,
    // (M + m_hook) g / 2 (two falls).
    Json js;
    js["program"] = "reeving-boom-crane";
    js["sheaves"] = p.sheaveModel == SheaveModel::Wrapped ? "wrapped" : "point";
    js["axial_modes"] = o.axialModes;
    js["transverse_modes"] = o.transverseModes;
    js["axial_dynamics"] = axialDynamicsName(o.axialDynamics);
    js["integrator"] = o.integrator;
    js["accuracy"] = jsonNumber(o.accuracy);
    js["fixed_step"] = jsonNumber(o.step);
    js["report_interval"] = jsonNumber(o.reportInterval);
    js["lift_m"] = jsonNumber(o.lift);
    js["slew_deg"] = jsonNumber(o.slewDeg);
    js["luff_deg"] = jsonNumber(o.luffDeg);
    js["t_end"] = jsonNumber(o.tEnd);
    js["t_reached"] = jsonNumber(last.t);
    js["termination"] = r.limit.empty() ? "completed" : "limit_reached";
    js["limit"] = r.limit;
    js["static_reference_hoist_axial_force_N"] = jsonNumber((p.payloadMass + p.hookMass) * p.g / 2);
    // Per rope: span axial forces at rest (t = 0) and their largest values over the reports; the
    // largest |fleet angle| of any span at any groove over the reports [deg] (0 with point sheaves);
    // per sheave (nodes 1..3) the wrap angle at rest and its range over the reports [rad] (0 with
    // point sheaves); the rope stored on its drum at the end [m].
    Json ropes = Json::array();
    for (int rope = 0; rope < kRopes; ++rope) {
        Json j;
        j["name"] = kRopeNames[rope];
        j["static_span_axial_force_N"] = jsonArray(first.spanForce[rope]);
        j["max_span_axial_force_N"] = jsonArray(f.maxSpanForce[rope]);
        j["max_fleet_angle_deg"] = jsonNumber(f.maxFleet[rope] * deg);
        // Where the rope leaves its drum, against the usual limits (BoomCraneScene).
        j["max_drum_fleet_angle_deg"] = jsonNumber(f.maxDrumFleet[rope] * deg);
        j["drum_fleet_limit_plain_deg"] = jsonNumber(BoomCraneScene::kPlainDrumFleetLimit * deg);
        j["drum_fleet_limit_grooved_deg"] = jsonNumber(BoomCraneScene::kGroovedDrumFleetLimit * deg);
        j["drum_fleet_within_plain_limit"] = f.maxDrumFleet[rope] <= BoomCraneScene::kPlainDrumFleetLimit;
        j["drum_fleet_within_grooved_limit"] = f.maxDrumFleet[rope] <= BoomCraneScene::kGroovedDrumFleetLimit;
        Json wraps = Json::array();
        for (int k = 0; k < kSheaves; ++k)
            wraps.push_back({{"sheave", k + 1},
                             {"name", kSheaveNames[rope][k]},
                             {"initial_rad", jsonNumber(first.wrap[rope][k])},
                             {"min_rad", jsonNumber(f.minWrap[rope][k])},
                             {"max_rad", jsonNumber(f.maxWrap[rope][k])}});
        j["wrap_angles"] = wraps;
        j["final_rope_on_drum_m"] = jsonNumber(last.ropeOnDrum[rope]);
        ropes.push_back(j);
    }
    js["ropes"] = ropes;
    for (int d = 0; d < 3; ++d) {
        js[std::string("max_abs_") + kDriveKeys[d] + "_torque_Nm"] = jsonNumber(f.maxTorque[d]);
        js[std::string("max_abs_") + kDriveKeys[d] + "_power_W"] = jsonNumber(f.maxPower[d]);
    }
    js["max_abs_out_of_plane_swing_rad"] = jsonNumber(f.maxSwingOut);
    js["max_abs_in_plane_swing_rad"] = jsonNumber(f.maxSwingIn);
    js["initial_slew_angle_deg"] = jsonNumber(first.slewAngle * deg);
    js["final_slew_angle_deg"] = jsonNumber(last.slewAngle * deg);
    js["initial_boom_angle_deg"] = jsonNumber(first.boomAngle * deg);
    js["final_boom_angle_deg"] = jsonNumber(last.boomAngle * deg);
    js["min_boom_angle_deg"] = jsonNumber(f.minBoomAngle * deg);
    js["max_boom_angle_deg"] = jsonNumber(f.maxBoomAngle * deg);
    js["initial_hook_radius_m"] = jsonNumber(first.hookRadius);
    js["min_hook_radius_m"] = jsonNumber(f.minHookRadius);
    js["max_hook_radius_m"] = jsonNumber(f.maxHookRadius);
    js["final_hook_radius_m"] = jsonNumber(last.hookRadius);
    js["final_motion_work_J"] = jsonNumber(last.work);
    js["max_abs_motion_work_J"] = jsonNumber(f.maxWork);
    js["max_abs_energy_residual_J"] = jsonNumber(f.maxResidual);
    js["energy_residual_relative"] = jsonNumber(f.residualRelative());
    // Each rope's most bent section over the run (no life law: the demo has no rope constants).
    Json& ropeLife = js["rope_life"];
    for (int rope = 0; rope < kRopes; ++rope) ropeLife[kRopeKeys[rope]] = demo_common::ropeLifeSummary(*life[rope], o.ropeLife);
    js["steps"] = r.steps;
    js["rhs_evaluations"] = r.rhsEvaluations;
    js["wall_seconds"] = jsonNumber(r.wallSeconds);
    js["real_time_factor"] = jsonNumber(r.wallSeconds > 0 ? last.t / r.wallSeconds : 0.0);
    std::vector<double> snapshotTimes;
    for (const Snapshot& s : r.snapshots) snapshotTimes.push_back(s.t);
    js["snapshot_times"] = jsonArray(snapshotTimes);
    js["parameters"] = parametersJson(p);
    demo_common::writeJson(jsFile.stream(), js);
    tsFile.commit();
    snFile.commit();
    for (auto& file : bendFiles) file->commit();
    jsFile.commit();  // last: a summary.json means the outputs are complete
}

}  // namespace

int main(int argc, char** argv) {
    Options o;
    try {
        o = parseCommandLine(argc, argv);
    } catch (const UsageError& e) {
        std::cerr << demo_common::usageErrorText("reeving-boom-crane", e.what());
        return demo_common::kUsageExitStatus;
    }
    if (o.help) {
        std::cout << usage();
        return 0;
    }
    // The cycle and the scene (every parameter's validation; --check: and the integrator), before
    // anything is written: a value only the scene can judge is a bad command line too.
    SpanOptions spans;
    spans.axialModes = o.axialModes;
    spans.transverseModes = o.transverseModes;
    spans.axialDynamics = o.axialDynamics;
    std::unique_ptr<BoomCraneScene> scene;
    RopeLifeMonitors life;
    try {
        scene = std::make_unique<BoomCraneScene>(o.parameters, o.cycle(), spans);
        for (int rope = 0; rope < kRopes; ++rope)
            life[rope] = std::make_unique<RopeLifeMonitor>(scene->reeving(), rope, o.ropeLife.options());
        if (o.check) makeIntegrator(o.integrator, scene->system());
    } catch (const std::exception& e) {
        std::cerr << demo_common::usageErrorText("reeving-boom-crane", e.what());
        return demo_common::kUsageExitStatus;
    }
    if (o.check) return 0;
    // The output folder must exist or be creatable, and be writable, before anything is simulated.
    if (!demo_common::prepareOutputFolder("reeving-boom-crane", o.outDir)) return demo_common::kUsageExitStatus;
    demo_common::installInterruptHandlers();
    const auto start = std::chrono::steady_clock::now();

    RunResult result;
    try {
        result = run(o, *scene, life);
    } catch (const Interrupted& e) {
        std::cerr << "\nreeving-boom-crane: interrupted at t = " << e.time << " s; no outputs written\n";
        return demo_common::kInterruptedExitStatus;
    } catch (const StepLimitReached& e) {
        std::cerr << "reeving-boom-crane: stopped: " << e.what() << "; nothing written\n";
        return 1;
    } catch (const std::exception& e) {
        std::cerr << "reeving-boom-crane: simulation failed: " << e.what() << "\n";
        return 1;
    }
    if (demo_common::interrupted()) {
        std::cerr << "reeving-boom-crane: interrupted after the simulation; no outputs written\n";
        return demo_common::kInterruptedExitStatus;
    }

    const fs::path out(o.outDir);
    const Figures figures = summarize(result);
    try {
        writeOutputs(out, o, *scene, result, figures, life);
    } catch (const std::exception& e) {
        std::cerr << "reeving-boom-crane: writing the outputs failed: " << e.what() << "\n";
        return 1;
    }
    const auto& p = scene->parameters();
    if (o.plots)
        makePlots(out, result.snapshots, (p.payloadMass + p.hookMass) * p.g / 2, p.sheaveModel == SheaveModel::Wrapped);

    const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    const Row &first = result.rows.front(), &last = result.rows.back();
    const double deg = 180.0 / SimTK::Pi;
    std::printf("reeving-boom-crane: %s sheaves, n_a = %d, %.2f s simulated in %.2f s (%.0fx real time, %ld steps), "
                "slew %.1f deg, boom %.1f -> %.1f deg, max swing out of plane %.3f rad, max energy residual %.2e of "
                "the motion work, outputs in %s\n",
                p.sheaveModel == SheaveModel::Wrapped ? "wrapped" : "point", o.axialModes, last.t, wall,
                result.wallSeconds > 0 ? last.t / result.wallSeconds : 0.0, result.steps, last.slewAngle * deg,
                first.boomAngle * deg, last.boomAngle * deg, figures.maxSwingOut, figures.residualRelative(),
                out.string().c_str());
    if (!result.limit.empty()) {
        std::string line = result.limit;
        std::replace(line.begin(), line.end(), '\n', ' ');
        std::cerr << "reeving-boom-crane: rope limit reached at t = " << last.t << " s: " << line << "\n";
        return kLimitReachedExitStatus;
    }
    return 0;
}
