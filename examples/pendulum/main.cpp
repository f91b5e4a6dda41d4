// reeving-pendulum: the paper's two-branch pendulum study (Mohammadi & Escalona, section 3, Table 1),
// reproducible from one command. See --help and README.md.
#include "PendulumCli.h"
#include "common/DemoOutput.h"
#include "common/DemoVisualizer.h"
#include "common/Interrupt.h"

#include <SimbodyReeving/simbody/Integrators.h>
#include <SimbodyReeving/simbody/InterpolatingTimeStepper.h>
#include <SimbodyReeving/scenes/PendulumScene.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <future>
#include <iomanip>
#include <iostream>
#include <memory>
#include <sstream>
#include <thread>

namespace fs = std::filesystem;
using SimTK::Stage;
using SimTK::State;
using namespace pendulum_demo;
using namespace SimbodyReeving;
using demo_common::OutputFile;

namespace {

/// Thrown by a case that saw demo_common::interrupted().
struct Interrupted : std::runtime_error {
    explicit Interrupted(double t) : std::runtime_error("interrupted"), time(t) {}
    double time;
};

/// Thrown by a case whose integrator took --max-steps steps: what() says when.
struct StepLimitReached : std::runtime_error {
    using std::runtime_error::runtime_error;
};

struct Row {
    // axialForcePayload, axialForceSheave: the axial force P = EA eps [N] at the two ends of the
    // vertical span (not the tension T = P |dr/ds|).
    double t, x, y, theta, axialForcePayload, axialForceSheave, sSheave, energy, constraintError;
    double wrapAngle;  // the sheave's wrap angle [rad] (SheaveModel::Wrapped; 0 with the point sheave)
};
struct StaticRow {
    int span;
    double s, axialForce;
};
struct CaseResult {
    int axialModes = 0;
    std::vector<Row> rows;
    std::vector<StaticRow> staticRows;
    long steps = 0, rhsEvaluations = 0;
    double wallSeconds = 0, initialKineticEnergy = 0, maxEnergyDrift = 0, maxConstraintError = 0;
    std::string limit;  // "" or the rope limit that ended the run (ReevingSubsystem::getLimitReached)
};

Row observe(const PendulumScene& scene, const State& s) {
    // Stage::Dynamics: the axial forces of QuasiStatic spans include the mode-acceleration correction.
    scene.system().realize(s, Stage::Dynamics);
    const SimTK::Vec3 p = scene.payloadPosition(s);
    const ReevingSubsystem& rv = scene.reeving();
    return {s.getTime(),
            p[0],
            p[1],
            scene.payloadAngle(s),
            scene.axialForceAtPayload(s),
            scene.axialForceAtSheave(s),
            scene.sheaveMaterialCoordinate(s),
            rv.calcMechanicalEnergy(s),
            rv.getConstraintError(s, 0, 1),
            rv.getRopeSpec(0).sheaveModel == SimbodyReeving::SheaveModel::Wrapped ? rv.getWrapAngle(s, 0, 1) : 0.0};
}

// The scene of the case with n_a = na.
std::unique_ptr<PendulumScene> makeScene(const Options& o, int na) {
    SpanOptions spans;
    spans.axialModes = na;
    spans.transverseModes = o.transverseModes;
    spans.axialDynamics = o.axialDynamics;
    SpanOptions condensed = spans;
    condensed.transverseDynamics = TransverseDynamics::QuasiStatic;
    using QST = Options::QuasiStaticTransverse;
    if (o.quasiStaticTransverse == QST::All) spans = condensed;
    return std::make_unique<PendulumScene>(
        o.parameters, spans, true,
        o.quasiStaticTransverse == QST::Horizontal ? std::optional<SpanOptions>(condensed) : std::nullopt);
}

CaseResult runCase(const Options& o, int na, std::atomic<double>& progress, bool visualize) {
    const std::unique_ptr<PendulumScene> scenePointer = makeScene(o, na);
    PendulumScene& scene = *scenePointer;
    CaseResult r;
    r.axialModes = na;
    State s = scene.makeInitialState(o.vx0, o.vy0);
    const ReevingSubsystem& rv = scene.reeving();
    for (int span = 0; span < 2; ++span) {
        const auto [s1, s2] = rv.getSpanMaterialRange(s, 0, span);
        for (int k = 0; k < 60; ++k) {
            const double sk = s1 + (s2 - s1) * k / 59.0;
            r.staticRows.push_back({span, sk, rv.getAxialForce(s, 0, span, std::min(sk, s2))});
        }
    }
    r.initialKineticEnergy = scene.system().calcKineticEnergy(s) + rv.calcRopeKineticEnergy(s);
    const double e0 = rv.calcMechanicalEnergy(s);

    demo_common::DemoVisualizer viz(scene.system(), scene.reeving(), "reeving-pendulum", visualize);
    viz.lookAt(SimTK::Vec3(1.5, -10.2, 27), SimTK::Vec3(1.5, -10.2, 0));  // the whole pendulum, side on
    viz.report(s);
    auto integ = makeIntegrator(o.integrator, scene.system());
    integ->setAccuracy(o.accuracy);
    if (o.step > 0) integ->setFixedStepSize(o.step);
    // Reports are interpolated: the step count does not grow with the report rate.
    InterpolatingTimeStepper ts(scene.system(), *integ);
    ts.initialize(s);
    const auto start = std::chrono::steady_clock::now();
    r.rows.push_back(observe(scene, ts.getState()));
    const int reports = static_cast<int>(std::floor(o.tEnd / o.reportInterval + 1e-9));
    for (int n = 1; n <= reports; ++n) {
        if (demo_common::interrupted()) throw Interrupted(ts.getState().getTime());
        try {
            // --max-steps: the stepper returns once the integrator has taken the steps left.
            for (;;) {
                if (o.maxSteps > 0) {
                    const long left = o.maxSteps - integ->getNumStepsTaken();
                    if (left <= 0)
                        throw StepLimitReached("n_a = " + std::to_string(na) + ": the integrator took --max-steps " +
                                               std::to_string(o.maxSteps) + " steps at t = " +
                                               demo_common::numberText(ts.getState().getTime()) +
                                               " s, before --t-end (" + demo_common::numberText(o.tEnd) + " s)");
                    ts.setStepLimit(static_cast<int>(std::min<long>(left, 1000000000L)));
                }
                if (ts.stepTo(n * o.reportInterval) != SimTK::Integrator::ReachedStepLimit) break;
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
        r.rows.push_back(observe(scene, st));
        viz.report(st);
        progress = st.getTime() / o.tEnd;
        if (!scene.reeving().getLimitReached().empty() || integ->isSimulationOver()) {
            // A rope limit (a span at minimumSpanLength, a wrapped sheave's wrap angle at 0)
            // requested termination: the run ends here, its reports so far kept.
            r.limit = scene.reeving().getLimitReached();
            if (r.limit.empty()) r.limit = "the integrator ended the simulation at t = " + std::to_string(st.getTime()) + " s";
            break;
        }
    }
    viz.close();  // the window closes and its process ends with the run
    r.wallSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    r.steps = integ->getNumStepsTaken();
    r.rhsEvaluations = ts.getNumRealizations();
    for (const Row& row : r.rows) {
        r.maxEnergyDrift = std::max(r.maxEnergyDrift, std::abs(row.energy - e0));
        r.maxConstraintError = std::max(r.maxConstraintError, std::abs(row.constraintError));
    }
    progress = 1.0;
    return r;
}

void writeCase(const fs::path& dir, const Options& o, const CaseResult& r) {
    fs::create_directories(dir);
    OutputFile tsFile(dir / "timeseries.csv"), stFile(dir / "static_axial_force.csv"), jsFile(dir / "summary.json");
    std::ofstream& ts = tsFile.stream();
    ts << "t,x,y,theta,axial_force_payload,axial_force_sheave,s_sheave,energy,constraint_error\n"
       << std::setprecision(12);
    for (const Row& w : r.rows)
        ts << w.t << ',' << w.x << ',' << w.y << ',' << w.theta << ',' << w.axialForcePayload << ','
           << w.axialForceSheave << ',' << w.sSheave << ',' << w.energy << ',' << w.constraintError << '\n';
    std::ofstream& st = stFile.stream();
    st << "span,s,axial_force\n" << std::setprecision(12);
    for (const StaticRow& w : r.staticRows) st << w.span << ',' << w.s << ',' << w.axialForce << '\n';
    const auto& p = o.parameters;
    using demo_common::jsonNumber;
    demo_common::Json js;
    js["integrator"] = o.integrator;
    js["accuracy"] = jsonNumber(o.accuracy);
    js["fixed_step"] = jsonNumber(o.step);
    js["axial_modes"] = r.axialModes;
    js["transverse_modes"] = o.transverseModes;
    js["axial_dynamics"] = axialDynamicsName(o.axialDynamics);
    js["quasi_static_transverse"] = quasiStaticTransverseName(o.quasiStaticTransverse);
    js["axial_law"] = o.parameters.tensionOnly ? "tension-only" : "linear";
    js["sheaves"] = o.parameters.sheaveModel == SimbodyReeving::SheaveModel::Wrapped ? "wrapped" : "point";
    js["t_end"] = jsonNumber(o.tEnd);
    js["t_reached"] = jsonNumber(r.rows.back().t);
    js["termination"] = r.limit.empty() ? "completed" : "limit_reached";
    js["limit"] = r.limit;
    js["vx0"] = jsonNumber(o.vx0);
    js["vy0"] = jsonNumber(o.vy0);
    js["steps"] = r.steps;
    js["rhs_evaluations"] = r.rhsEvaluations;
    js["wall_seconds"] = jsonNumber(r.wallSeconds);
    js["initial_kinetic_energy_J"] = jsonNumber(r.initialKineticEnergy);
    js["max_energy_drift_J"] = jsonNumber(r.maxEnergyDrift);
    js["max_constraint_error_N"] = jsonNumber(r.maxConstraintError);
    // The sheave's wrap angle range over the output rows [rad] (0 with the point sheave) and the
    // largest fleet angle (0: the rope is planar).
    {
        double lo = r.rows.front().wrapAngle, hi = lo;
        for (const Row& row : r.rows) {
            lo = std::min(lo, row.wrapAngle);
            hi = std::max(hi, row.wrapAngle);
        }
        js["sheave_wrap_angles"] = demo_common::Json::array({{{"sheave", 1}, {"min_rad", jsonNumber(lo)}, {"max_rad", jsonNumber(hi)}}});
    }
    js["max_fleet_angle_rad"] = jsonNumber(0.0);
    js["parameters"] = {{"a", jsonNumber(p.a)},   {"L", jsonNumber(p.L)},   {"d", jsonNumber(p.d)},
                        {"r", jsonNumber(p.r)},   {"g", jsonNumber(p.g)},   {"rhoA", jsonNumber(p.rhoA)},
                        {"EA", jsonNumber(p.EA)}, {"EI", jsonNumber(p.EI)}, {"M", jsonNumber(p.M)},
                        {"J", jsonNumber(p.J)}};
    demo_common::writeJson(jsFile.stream(), js);
    tsFile.commit();
    stFile.commit();
    jsFile.commit();  // last: a summary.json means the case's outputs are complete
}

// One CSV with every case side by side (same report times), for the comparison figures.
void writeComparison(const fs::path& dir, const std::vector<CaseResult>& cases) {
    OutputFile file(dir / "comparison.csv");
    std::ofstream& c = file.stream();
    c << "t";
    for (const auto& r : cases) c << ",x_" << r.axialModes << ",axial_force_payload_" << r.axialModes;
    c << '\n' << std::setprecision(12);
    size_t rows = cases.front().rows.size();  // a case that reached a rope limit ends early
    for (const auto& r : cases) rows = std::min(rows, r.rows.size());
    for (size_t k = 0; k < rows; ++k) {
        c << cases.front().rows[k].t;
        for (const auto& r : cases) c << ',' << r.rows[k].x << ',' << r.rows[k].axialForcePayload;
        c << '\n';
    }
    file.commit();
}

bool makePlots(const fs::path& dir, const std::vector<CaseResult>& cases, bool single, const Options& o) {
    if (std::system("command -v gnuplot > /dev/null 2>&1") != 0) {
        std::cerr << "reeving-pendulum: gnuplot not found, figures skipped (apt-get install gnuplot-nox)\n";
        return false;
    }
    std::ofstream gp(dir / "plots.gp");
    gp << "set terminal pngcairo size 900,560 font 'DejaVu Sans,11'\nset datafile separator ','\nset grid\n"
       << "set key outside right\n";
    auto path = [&](const CaseResult& r, const char* file) {
        return single ? std::string(file) : "modes-" + std::to_string(r.axialModes) + "/" + file;
    };
    auto label = [](const CaseResult& r) { return "n_a = " + std::to_string(r.axialModes); };
    const double a = o.parameters.a;
    gp << "set output 'fig2_payload_displacement.png'\nset title 'Payload horizontal displacement'\n"
       << "set xlabel 't [s]'\nset ylabel 'x - a [m]'\nplot ";
    for (size_t i = 0; i < cases.size(); ++i)
        gp << (i ? ", " : "") << "'" << path(cases[i], "timeseries.csv") << "' every ::1 using 1:($2-" << a
           << ") with lines lw 2 title '" << label(cases[i]) << "'";
    // Reference: the hanging rope below the sheave, T(s) = M g + rhoA g (a + L - s), as the axial
    // force P = EA eps = T / sqrt(1 + 2 eps) ~ T (1 - T/EA).
    const auto& pp = o.parameters;
    gp << "\nset output 'fig3_static_axial_force.png'\nset title 'Axial force along the rope at static equilibrium'\n"
       << "set xlabel 's [m]'\nset ylabel 'P = EA eps [N]'\nset samples 200\n"
       << "T(s) = " << pp.M * pp.g << " + " << pp.rhoA * pp.g << " * (" << pp.a + pp.L << " - s)\n"
       << "hanging(s) = (s >= " << pp.a << ") ? T(s) * (1 - T(s) / " << pp.EA << ") : 1/0\nplot ";
    for (size_t i = 0; i < cases.size(); ++i)
        gp << (i ? ", " : "") << "'" << path(cases[i], "static_axial_force.csv")
           << "' every ::1 using 2:3 with lines lw 2 title '" << label(cases[i]) << "'";
    gp << ", [" << pp.a << ":" << pp.a + pp.L << "] hanging(x) with lines dt 2 lw 2 lc 'black' title 'hanging rope'";
    gp << "\nset output 'fig4_payload_end_axial_force.png'\nset title 'Axial force at the payload end'\n"
       << "set xlabel 't [s]'\nset ylabel 'P [N]'\nplot ";
    for (size_t i = 0; i < cases.size(); ++i)
        gp << (i ? ", " : "") << "'" << path(cases[i], "timeseries.csv") << "' every ::1 using 1:5 with lines lw 2 title '"
           << label(cases[i]) << "'";
    gp << "\n";
    int zeroColumn = -1;
    for (size_t i = 0; i < cases.size(); ++i)
        if (cases[i].axialModes == 0) zeroColumn = 3 + 2 * static_cast<int>(i);
    if (!single && zeroColumn > 0 && cases.size() > 1) {
        gp << "set output 'fig5_axial_force_difference.png'\n"
           << "set title 'Payload-end axial force minus the n_a = 0 case'\n"
           << "set xlabel 't [s]'\nset ylabel 'P - P(n_a = 0) [N]'\nplot ";
        bool first = true;
        for (size_t i = 0; i < cases.size(); ++i) {
            if (cases[i].axialModes == 0) continue;
            gp << (first ? "" : ", ") << "'comparison.csv' every ::1 using 1:($" << 3 + 2 * i << "-$" << zeroColumn
               << ") with lines lw 2 title '" << label(cases[i]) << "'";
            first = false;
        }
        gp << "\n";
    } else {
        std::cerr << "reeving-pendulum: fig5 needs n_a = 0 and another n_a in --axial-modes; skipped\n";
    }
    gp.close();
    const std::string cmd = "cd '" + dir.string() + "' && gnuplot plots.gp";
    if (std::system(cmd.c_str()) != 0) {
        std::cerr << "reeving-pendulum: gnuplot failed; see " << (dir / "plots.gp").string() << "\n";
        return false;
    }
    return true;
}

}  // namespace

int main(int argc, char** argv) {
    Options o;
    try {
        o = parseCommandLine(argc, argv);
    } catch (const UsageError& e) {
        std::cerr << demo_common::usageErrorText("reeving-pendulum", e.what());
        return demo_common::kUsageExitStatus;
    }
    if (o.help) {
        std::cout << usage();
        return 0;
    }
    // --check: every case's scene and integrator built (the scenes' own validation), nothing run.
    if (o.check) {
        for (int na : o.axialModes) {
            try {
                const std::unique_ptr<PendulumScene> scene = makeScene(o, na);
                makeIntegrator(o.integrator, scene->system());
            } catch (const std::exception& e) {
                std::cerr << demo_common::usageErrorText("reeving-pendulum",
                                                         "n_a = " + std::to_string(na) + ": " + e.what());
                return demo_common::kUsageExitStatus;
            }
        }
        return 0;
    }
    // The output folder must exist or be creatable, and be writable, before anything is simulated.
    if (!demo_common::prepareOutputFolder("reeving-pendulum", o.outDir)) return demo_common::kUsageExitStatus;
    // SIGINT / SIGTERM stop the cases at their next report; nothing is written then.
    demo_common::installInterruptHandlers();
    const bool visualize = o.visualize;
    const auto start = std::chrono::steady_clock::now();
    std::vector<std::atomic<double>> progress(o.axialModes.size());
    for (auto& p : progress) p = 0.0;
    std::vector<CaseResult> cases(o.axialModes.size());
    try {
        // Cases run concurrently (one Simbody system each); the Visualizer shows the first one alone.
        std::vector<std::future<CaseResult>> futures;
        const size_t workers = visualize ? 1 : std::max(1u, std::thread::hardware_concurrency());
        size_t next = 0;
        std::vector<size_t> running;
        auto launch = [&](size_t i) {
            futures.resize(o.axialModes.size());
            futures[i] = std::async(std::launch::async, [&, i] {
                return runCase(o, o.axialModes[i], progress[i], visualize && i == 0);
            });
            running.push_back(i);
        };
        // Launch the costliest cases (most axial modes: stiffest) first.
        std::vector<size_t> order(o.axialModes.size());
        for (size_t i = 0; i < order.size(); ++i) order[i] = i;
        std::stable_sort(order.begin(), order.end(),
                         [&](size_t a, size_t b) { return o.axialModes[a] > o.axialModes[b]; });
        while (next < order.size() && running.size() < workers) launch(order[next++]);
        auto lastPrint = std::chrono::steady_clock::now();
        bool printed = false;
        while (!running.empty()) {
            for (size_t k = 0; k < running.size(); ++k) {
                const size_t i = running[k];
                if (futures[i].wait_for(std::chrono::milliseconds(50)) == std::future_status::ready) {
                    cases[i] = futures[i].get();
                    running.erase(running.begin() + static_cast<long>(k));
                    if (next < order.size()) launch(order[next++]);
                    break;
                }
            }
            const auto now = std::chrono::steady_clock::now();
            if (!o.quiet && std::chrono::duration<double>(now - start).count() > 2.0 &&
                std::chrono::duration<double>(now - lastPrint).count() > 1.0) {
                std::ostringstream line;
                line << "\rreeving-pendulum: " << std::fixed << std::setprecision(0);
                for (size_t i = 0; i < o.axialModes.size(); ++i)
                    line << "n_a=" << o.axialModes[i] << " " << 100 * progress[i].load() << "%  ";
                line << std::setprecision(1) << std::chrono::duration<double>(now - start).count() << " s";
                std::cerr << line.str() << std::flush;
                lastPrint = now;
                printed = true;
            }
        }
        if (printed) std::cerr << "\n";
    } catch (const Interrupted& e) {
        std::cerr << "\nreeving-pendulum: interrupted at t = " << e.time << " s; no outputs written\n";
        return demo_common::kInterruptedExitStatus;
    } catch (const StepLimitReached& e) {
        std::cerr << "reeving-pendulum: stopped: " << e.what() << "; no outputs written\n";
        return 1;
    } catch (const std::exception& e) {
        std::cerr << "reeving-pendulum: simulation failed: " << e.what() << "\n";
        return 1;
    }
    if (demo_common::interrupted()) {
        std::cerr << "reeving-pendulum: interrupted after the simulation; no outputs written\n";
        return demo_common::kInterruptedExitStatus;
    }

    const fs::path out(o.outDir);
    const bool single = cases.size() == 1;
    try {
        for (const CaseResult& r : cases)
            writeCase(single ? out : out / ("modes-" + std::to_string(r.axialModes)), o, r);
        if (!single) writeComparison(out, cases);
    } catch (const std::exception& e) {
        std::cerr << "reeving-pendulum: writing the outputs failed: " << e.what() << "\n";
        return 1;
    }
    if (o.plots) makePlots(out, cases, single, o);

    const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    long steps = 0;
    double drift = 0;
    bool limited = false;
    for (const CaseResult& r : cases) {
        steps += r.steps;
        drift = std::max(drift, r.maxEnergyDrift);
        if (!r.limit.empty()) {
            limited = true;
            std::fprintf(stderr, "reeving-pendulum: n_a = %d: %s; outputs up to t = %.6g s written\n", r.axialModes,
                         r.limit.c_str(), r.rows.back().t);
        }
    }
    std::printf("reeving-pendulum: %zu case(s), %.1f s simulated each%s, wall %.2f s, %ld steps, max energy drift %.3e J, "
                "outputs in %s\n",
                cases.size(), o.tEnd, limited ? " (or up to a rope limit)" : "", wall, steps, drift, out.string().c_str());
    return limited ? 3 : 0;
}
