// reeving-elevator: a traction elevator, roped 1:1 or 2:1, through EN 81-50's traction checks:
// a trip, loading to 125 %, an emergency stop and a stalled counterweight, the hoist ropes over a
// traction sheave that sticks and slips (capstan law). See --help and README.md.
#include "common/Cli.h"
#include "common/DemoOutput.h"
#include "common/DemoVisualizer.h"
#include "common/Interrupt.h"
#include "common/RopeLifeOutput.h"

#include <SimbodyReeving/scenes/ElevatorScene.h>
#include <SimbodyReeving/simbody/Integrators.h>
#include <SimbodyReeving/simbody/InterpolatingTimeStepper.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

namespace fs = std::filesystem;
using namespace SimbodyReeving;
using demo_common::Json;
using demo_common::jsonNumber;
using SimTK::Stage;
using SimTK::State;

namespace {

constexpr const char* kProgram = "reeving-elevator";

struct Options {
    std::string scenario = "all", roping = "1:1", tractionSlip = "constraint";
    ElevatorParameters parameters;
    int axialModes = 1, transverseModes = 1;
    std::string integrator = "rk-merson";
    double accuracy = 1e-6, reportInterval = 0.01, tEnd = 0;  // tEnd 0: each scenario's own duration
    std::string outDir = "out/elevator";
    bool plots = true, quiet = false, visualize = false, check = false;
    long maxSteps = 0;  // 0: no limit
    // Bending cycles per section of the hoist ropes (RopeLifeMonitor, rope 0): one 10 mm rope of the set.
    demo_common::RopeLifeCli ropeLife{0.010};
};

struct Row {
    double t, carY, carV, carA, cwtY, travel, pCar, pCwt, ratio, limit, slipRate, slipDistance, frictionWork,
        dampingWork, machineWork, residual, pitY, wrap;
    int mode;
    std::vector<std::pair<int, double>> sheaveWraps;  // (node, wrap angle) of the hoist rope's sheaves
};

struct Result {
    std::string scenario;
    std::vector<Row> rows;
    long steps = 0, rhs = 0;
    double wall = 0, duration = 0, carLoad = 0, carPosition = 0;
    int transitions = 0;
    Json ropeLife;                         // summary.json's rope_life of the hoist ropes
    std::string bendingCsv, bendingFigure;  // rope_bending_<scenario>.csv and .dat
};

struct Interrupted : std::runtime_error {
    Interrupted() : std::runtime_error("interrupted") {}
};

/// --max-steps reached: what() says when.
struct StepLimitReached : std::runtime_error {
    using std::runtime_error::runtime_error;
};

// The scene's options for one scenario.
ElevatorParameters scenarioParameters(const Options& o, ElevatorScenario scenario) {
    ElevatorParameters p = o.parameters;
    p.scenario = scenario;
    return p;
}
SpanOptions spanOptions(const Options& o) {
    SpanOptions spans;
    spans.axialModes = o.axialModes;
    spans.transverseModes = o.transverseModes;
    return spans;
}

Row observe(const ElevatorScene& scene, const State& s, double e0) {
    scene.system().realize(s, Stage::Acceleration);
    const ReevingSubsystem& rv = scene.reeving();
    Row r{};
    r.t = s.getTime();
    r.carY = scene.carHeight(s);
    r.carV = scene.carVelocity(s);
    r.carA = scene.carAcceleration(s);
    r.cwtY = scene.counterweightHeight(s);
    r.pitY = scene.pitSheaveHeight(s);
    r.travel = scene.ropeTravel(s);
    r.pCar = scene.carSideForce(s);
    r.pCwt = scene.counterweightSideForce(s);
    r.ratio = r.pCar / r.pCwt;
    const int node = scene.tractionNode();
    const SimbodyReeving::TractionSheaveHandle traction = scene.tractionSheave();
    r.limit = traction.getTractionLimit(s);
    r.wrap = scene.tractionWrapAngle(s);
    // Every sheave of the hoist rope with a wrap angle: all of them wrapped, the traction sheave's
    // given one with point sheaves.
    const bool wrapped = rv.getRopeSpec(0).sheaveModel == SimbodyReeving::SheaveModel::Wrapped;
    for (int k = 1; k < rv.getNumSpans(0); ++k)
        if (wrapped || k == node) r.sheaveWraps.emplace_back(k, rv.getWrapAngle(s, 0, k));
    r.mode = static_cast<int>(traction.getTractionMode(s));
    r.slipRate = traction.getSlipRate(s);
    r.slipDistance = traction.getSlipDistance(s);
    r.frictionWork = rv.getTotalFrictionWork(s);
    r.dampingWork = rv.getDampingWork(s);
    r.machineWork = scene.workMeter().getWork(s);
    r.residual = scene.energyResidual(s, e0);
    return r;
}

Result run(const Options& o, ElevatorScenario scenario) {
    const ElevatorParameters p = scenarioParameters(o, scenario);
    ElevatorScene scene(p, spanOptions(o));
    Result r;
    r.scenario = toString(scenario);
    r.duration = o.tEnd > 0 ? o.tEnd : scene.duration();
    r.carLoad = p.ratedLoad > 0 ? (scene.carTotalMass() - p.carMass) / p.ratedLoad : 0.0;
    State s0 = scene.makeInitialState();
    const double e0 = scene.reeving().calcMechanicalEnergy(s0);
    demo_common::DemoVisualizer viz(scene.system(), scene.reeving(), kProgram, o.visualize);
    viz.lookAt(SimTK::Vec3(6, -0.5 * p.hoistway, 0.9 * p.hoistway), SimTK::Vec3(0, -0.5 * p.hoistway, 0));
    viz.report(s0);
    auto integ = makeIntegrator(o.integrator, scene.system());
    integ->setAccuracy(o.accuracy);
    InterpolatingTimeStepper ts(scene.system(), *integ);
    ts.initialize(s0);
    RopeLifeMonitor life(scene.reeving(), 0, o.ropeLife.options());
    const auto start = std::chrono::steady_clock::now();
    r.rows.push_back(observe(scene, ts.getState(), e0));
    life.record(ts.getState());
    const auto ropeAtStart = demo_common::sampleRopePath(scene.reeving(), ts.getState(), 0, 41);
    const auto nodesAtStart = demo_common::nodeMaterialCoordinates(scene.reeving(), ts.getState(), 0);
    // The car's start above the bottom landing as set (ElevatorParameters::carPosition, else the
    // scenario's own), before the static equilibrium stretches the rope.
    r.carPosition = p.carPosition                                ? *p.carPosition
                    : scenario == ElevatorScenario::EmergencyStop ? 0.5 * p.hoistway
                                                                  : 0.0;
    const int reports = static_cast<int>(std::floor(r.duration / o.reportInterval + 1e-9));
    for (int n = 1; n <= reports; ++n) {
        if (demo_common::interrupted()) throw Interrupted();
        // --max-steps: the stepper returns once the integrator has taken the steps left.
        for (;;) {
            if (o.maxSteps > 0) {
                const long left = o.maxSteps - integ->getNumStepsTaken();
                if (left <= 0)
                    throw StepLimitReached(r.scenario + ": the integrator took --max-steps " +
                                           std::to_string(o.maxSteps) + " steps at t = " +
                                           demo_common::numberText(ts.getState().getTime()) + " s, before the end (" +
                                           demo_common::numberText(r.duration) + " s)");
                ts.setStepLimit(static_cast<int>(std::min<long>(left, 1000000000L)));
            }
            if (ts.stepTo(n * o.reportInterval) != SimTK::Integrator::ReachedStepLimit) break;
        }
        r.rows.push_back(observe(scene, ts.getState(), e0));
        life.record(ts.getState());
        viz.report(ts.getState());
    }
    r.wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    r.steps = integ->getNumStepsTaken();
    r.rhs = integ->getNumRealizations();
    r.transitions = scene.tractionSheave().getNumTractionTransitions(ts.getState());
    r.ropeLife = demo_common::ropeLifeSummary(life, o.ropeLife);
    std::ostringstream csv, figure;
    demo_common::writeRopeBendingCsv(csv, life);
    demo_common::writeRopeBendingFigureData(figure, ropeAtStart, nodesAtStart, life);
    r.bendingCsv = csv.str();
    r.bendingFigure = figure.str();
    return r;
}

void writeTimeseries(const fs::path& path, const Result& r) {
    demo_common::OutputFile f(path);
    auto& out = f.stream();
    out << "t_s,car_y_m,car_v_mps,car_a_mps2,car_jerk_mps3,counterweight_y_m,rope_travel_m,car_side_force_N,"
           "counterweight_side_force_N,force_ratio,traction_limit,mode,slip_rate_mps,slip_distance_m,"
           "friction_work_J,damping_work_J,machine_work_J,energy_residual_J,pit_sheave_y_m,wrap_angle_rad\n";
    out.precision(10);
    for (size_t i = 0; i < r.rows.size(); ++i) {
        const Row& w = r.rows[i];
        // Jerk by central differences of the reported accelerations (one-sided at the ends).
        const size_t a = i == 0 ? 0 : i - 1, b = std::min(i + 1, r.rows.size() - 1);
        const double jerk = b > a ? (r.rows[b].carA - r.rows[a].carA) / (r.rows[b].t - r.rows[a].t) : 0.0;
        out << w.t << ',' << w.carY << ',' << w.carV << ',' << w.carA << ',' << jerk << ',' << w.cwtY << ','
            << w.travel << ',' << w.pCar << ',' << w.pCwt << ',' << w.ratio << ',' << w.limit << ',' << w.mode << ','
            << w.slipRate << ',' << w.slipDistance << ',' << w.frictionWork << ',' << w.dampingWork << ','
            << w.machineWork << ',' << w.residual << ',' << w.pitY << ',' << w.wrap << '\n';
    }
    f.commit();
}

Json summarize(const Result& r) {
    double maxRatio = 0, maxA = 0, maxResidual = 0, largest = 0;
    double minWrap = r.rows.front().wrap, maxWrap = minWrap;
    for (const Row& w : r.rows) {
        minWrap = std::min(minWrap, w.wrap);
        maxWrap = std::max(maxWrap, w.wrap);
        if (w.pCwt > 0) maxRatio = std::max(maxRatio, std::max(w.ratio, 1.0 / w.ratio));
        maxA = std::max(maxA, std::abs(w.carA));
        maxResidual = std::max(maxResidual, std::abs(w.residual));
        largest = std::max({largest, std::abs(w.machineWork), w.frictionWork, w.dampingWork});
    }
    const Row& end = r.rows.back();
    const bool slipped = r.transitions > 0 || std::abs(end.slipDistance) > 1e-9;
    Json j;
    j["scenario"] = r.scenario;
    j["traction"] = slipped ? "slipped" : "held";
    j["traction_limit"] = jsonNumber(end.limit);
    j["wrap_angle_min_rad"] = jsonNumber(minWrap);  // the traction sheave's, over the run
    j["wrap_angle_max_rad"] = jsonNumber(maxWrap);
    // Per sheave of the hoist rope (node index in the rope), as the crane's and the pendulum's
    // summaries; planar: no fleet angle.
    Json sheaves = Json::array();
    for (size_t i = 0; i < r.rows.front().sheaveWraps.size(); ++i) {
        double lo = r.rows.front().sheaveWraps[i].second, hi = lo;
        for (const Row& w : r.rows) {
            lo = std::min(lo, w.sheaveWraps[i].second);
            hi = std::max(hi, w.sheaveWraps[i].second);
        }
        Json e;
        e["node"] = r.rows.front().sheaveWraps[i].first;
        e["min_rad"] = jsonNumber(lo);
        e["max_rad"] = jsonNumber(hi);
        sheaves.push_back(e);
    }
    j["sheave_wrap_angles"] = sheaves;
    j["max_fleet_angle_rad"] = 0.0;
    j["largest_force_ratio"] = jsonNumber(maxRatio);
    j["traction_margin"] = jsonNumber(end.limit / maxRatio);  // > 1: held with this factor to spare
    j["car_load"] = jsonNumber(r.carLoad);
    j["car_position_m"] = jsonNumber(r.carPosition);
    j["slip_distance_m"] = jsonNumber(end.slipDistance);
    j["stick_slip_transitions"] = r.transitions;
    j["car_rise_m"] = jsonNumber(end.carY - r.rows.front().carY);
    j["rope_travel_m"] = jsonNumber(end.travel - r.rows.front().travel);
    j["max_car_acceleration_mps2"] = jsonNumber(maxA);
    j["friction_work_J"] = jsonNumber(end.frictionWork);
    j["damping_work_J"] = jsonNumber(end.dampingWork);
    j["machine_work_J"] = jsonNumber(end.machineWork);
    j["max_energy_residual_J"] = jsonNumber(maxResidual);
    j["energy_residual_relative"] = jsonNumber(largest > 0 ? maxResidual / largest : 0.0);
    j["rope_life"] = r.ropeLife;  // the hoist ropes' most bent section over the scenario
    j["simulated_s"] = jsonNumber(r.duration);
    j["steps"] = r.steps;
    j["rhs_evaluations"] = r.rhs;
    j["wall_s"] = jsonNumber(r.wall);
    j["real_time_factor"] = jsonNumber(r.wall > 0 ? r.duration / r.wall : 0.0);
    return j;
}

// Snapshots of the machine at five instants of a run (gnuplot commands for one multiplot row):
// the traction sheave, the rope's falls (green in stick, red in slip), car and counterweight as
// boxes under their hitches, the 2:1 sheaves on car and counterweight. The falls are drawn straight:
// their sag under the rope's weight is below a millimetre here.
void writeSnapshots(std::ostream& g, const Result& r, const ElevatorParameters& p) {
    const double R = p.sheaveRadius, rc = p.carSheaveRadius;
    const bool twoToOne = p.roping == 2;
    const double xRail = twoToOne ? R + rc : R;
    const double carX = twoToOne ? xRail : R + p.carHitchOffset;
    const double cwtX = twoToOne ? xRail : (p.deflector ? p.counterweightRail : R);
    const double floorY = -p.hoistway - (p.compensation ? 11.0 : 4.0);  // under the pit sheave
    g << "set multiplot layout 1,5 title 'reeving-elevator: " << r.scenario << ", " << p.roping
      << ":1 roping" << (p.compensation ? ", compensated" : "") << " (rope green in stick, red in slip)'\n"
      << "unset key\nunset grid\nunset xlabel\nset ylabel 'height [m]'\nset size ratio -1\nset xrange [-3:3]\n"
      << "set yrange [" << floorY << ":2]\nset xtics 2\nset ytics 5\n";
    for (int k = 0; k < 5; ++k) {
        const Row& w = r.rows[std::min(r.rows.size() - 1, static_cast<size_t>(k * (r.rows.size() - 1) / 4))];
        const char* colour = w.mode == static_cast<int>(TractionMode::Stick) ? "#2a9d3f" : "#d62728";
        g << "unset object\nunset arrow\nunset label\n";
        g << "set title sprintf('t = %.2f s, slip %.3f m', " << w.t << ", " << w.slipDistance << ")\n";
        int id = 1;
        auto line = [&](double x1, double y1, double x2, double y2) {
            g << "set arrow " << id++ << " from " << x1 << "," << y1 << " to " << x2 << "," << y2 << " nohead lw 2 lc rgb '"
              << colour << "'\n";
        };
        auto circle = [&](double x, double y, double radius) {
            g << "set object " << id++ << " circle at " << x << "," << y << " size " << radius
              << " fs empty border lc rgb 'black' lw 1.5\n";
        };
        auto box = [&](double x, double yTop, double half, double height, const char* fill) {
            g << "set object " << id++ << " rect from " << x - half << "," << yTop - height << " to " << x + half << ","
              << yTop << " fc rgb '" << fill << "' fs solid 0.6 border lc rgb 'black'\n";
        };
        circle(0, 0, R);
        if (twoToOne) {
            line(-(R + 2 * rc), 0, -(R + 2 * rc), w.carY);
            line(-R, 0, -R, w.carY);
            line(R, 0, R, w.cwtY);
            line(R + 2 * rc, 0, R + 2 * rc, w.cwtY);
            circle(-xRail, w.carY, rc);
            circle(xRail, w.cwtY, rc);
        } else if (p.sheaveModel == SimbodyReeving::SheaveModel::Wrapped) {
            // The car's fall to its tangent point (leaning by psi with a hitch offset e); the lead-off
            // span to the deflector (theta from vertical) and the counterweight's fall from it.
            const double e = p.carHitchOffset, rho = std::hypot(R + e, w.carY);
            const double psi = std::acos(R / rho) - std::atan2(-w.carY, R + e);
            line(-(R + e), w.carY, -R * std::cos(psi), R * std::sin(psi));
            if (p.deflector) {
                const double rd = p.deflectorRadius, dx = p.counterweightRail - rd, drop = p.deflectorDrop;
                const double theta = std::atan2(dx, drop) + std::asin((rd - R) / std::hypot(dx, drop));
                line(R * std::cos(theta), R * std::sin(theta), dx + rd * std::cos(theta), -drop + rd * std::sin(theta));
                line(p.counterweightRail, -drop, p.counterweightRail, w.cwtY);
                circle(dx, -drop, rd);
            } else {
                line(R, 0, R, w.cwtY);
            }
        } else {
            line(-R, 0, -R, w.carY);
            line(R, 0, R, w.cwtY);
        }
        if (std::isfinite(w.pitY)) {  // the compensating rope (black) around the pit sheave
            g << "set arrow " << id++ << " from " << -carX << "," << w.carY - 2.5 << " to " << -carX << "," << w.pitY
              << " nohead lw 1.5 lc rgb 'black'\n";
            g << "set arrow " << id++ << " from " << cwtX << "," << w.cwtY - 3.0 << " to " << cwtX << "," << w.pitY
              << " nohead lw 1.5 lc rgb 'black'\n";
            circle(0.5 * (cwtX - carX), w.pitY, 0.5 * (cwtX + carX));
        }
        box(-carX - 0.6, w.carY - (twoToOne ? rc : 0), 0.75, 2.4, "#9ecae1");  // car
        box(cwtX + 0.3, w.cwtY - (twoToOne ? rc : 0), 0.25, 3.0, "#969696");   // counterweight
        g << "set object " << id++ << " rect from -3," << floorY << " to 3," << floorY + 1.5
          << " fc rgb '#d9d9d9' fs solid border lc rgb '#d9d9d9' behind\n";  // pit floor
        g << "plot NaN\n";
    }
    g << "unset multiplot\nunset object\nunset arrow\nunset title\nset size noratio\nset autoscale xy\n"
      << "set xtics autofreq\nset ytics autofreq\nset grid\nset key top left\n";
}

void plot(const fs::path& dir, const std::vector<Result>& results, const ElevatorParameters& parameters) {
    if (std::system("command -v gnuplot > /dev/null 2>&1") != 0) {
        std::cerr << kProgram << ": gnuplot not found, figures skipped (apt-get install gnuplot-nox)\n";
        return;
    }
    demo_common::OutputFile gp(dir / "plots.gp");
    auto& g = gp.stream();
    g << "set terminal pngcairo size 1200,900 noenhanced\nset datafile separator ','\nset key top left\nset grid\n";
    for (const Result& r : results) {
        const std::string csv = "timeseries_" + r.scenario + ".csv";
        g << "set output 'elevator_" << r.scenario << ".png'\nset multiplot layout 3,1 title 'reeving-elevator: "
          << r.scenario << "'\n"
          << "set ylabel 'm'\nplot '" << csv << "' u 1:($2-(" << r.rows.front().carY << ")) w l t 'car rise', '" << csv
          << "' u 1:(-$7) w l t 'rope travel (car up)', '" << csv << "' u 1:14 w l t 'slip distance'\n"
          << "set ylabel 'kN'\nplot '" << csv << "' u 1:($8/1000) w l t 'car side P_a', '" << csv
          << "' u 1:($9/1000) w l t 'counterweight side P_b'\n"
          << "set ylabel 'ratio'\nset xlabel 't [s]'\nplot '" << csv << "' u 1:10 w l t 'P_a / P_b', '" << csv
          << "' u 1:11 w l dt 2 t 'e^(mu alpha)', '" << csv << "' u 1:(1/$11) w l dt 2 t 'e^(-mu alpha)'\n"
          << "unset multiplot\nunset xlabel\n";
        g << "set terminal pngcairo size 1500,900 noenhanced\nset output 'elevator_" << r.scenario << "_machine.png'\n";
        writeSnapshots(g, r, parameters);
        g << demo_common::ropeBendingPlot("elevator_" + r.scenario + "_rope_bending.png",
                                          "rope_bending_" + r.scenario + ".csv", "rope_bending_" + r.scenario + ".dat",
                                          "reeving-elevator: " + r.scenario + ", bending cycles per section of the hoist ropes");
        g << "set terminal pngcairo size 1200,900 noenhanced\nset datafile separator ','\nset key top left\nset grid\n";
    }
    gp.commit();
    const std::string cmd = "cd '" + dir.string() + "' && gnuplot plots.gp";
    if (std::system(cmd.c_str()) != 0) std::cerr << kProgram << ": gnuplot failed; see " << (dir / "plots.gp").string() << "\n";
}

}  // namespace

int main(int argc, char** argv) {
    using namespace demo_common;
    Options o;
    CLI::App app(
        "reeving-elevator: a traction elevator, roped 1:1 or 2:1 (car with its rated load, counterweight at car +\n"
        "half the rated load, the rope set as one rope) through EN 81-50's traction checks, the hoist ropes\n"
        "over a traction sheave that sticks and slips by the capstan law P_tight = e^(mu alpha) P_slack.\n"
        "Outputs in DIR: timeseries_<scenario>.csv, summary.json (the traction table: held or slipped,\n"
        "margin, the hoist ropes' most bent section), rope_bending_<scenario>.csv (bending cycles per rope\n"
        "section) and, with gnuplot, elevator_<scenario>.png (time plots), elevator_<scenario>_machine.png\n"
        "(snapshots of the machine) and elevator_<scenario>_rope_bending.png (cycles along the rope).",
        kProgram);
    applyConventions(app);
    app.footer(
        "Exit status: 0 every scenario run (held or slipped: both are results; with --check: the options\n"
        "are valid); 2 bad command line or unusable --out (nothing written); 1 the simulation failed or\n"
        "reached --max-steps (nothing written); 130 interrupted (SIGINT/SIGTERM, nothing written).");
    app.add_option("--scenario", o.scenario, "trip, loading, emergency-stop, stall or all (default all)")
        ->check(oneOf({"all", "trip", "loading", "emergency-stop", "stall"}));
    app.add_option("--roping", o.roping,
                   "1:1 (rope ends on car and counterweight) or 2:1 (sheaves on car and counterweight, rope ends\n"
                   "at the hoistway's top) (default 1:1)")
        ->check(oneOf({"1:1", "2:1"}));
    addSheaveModelOption(app, o.parameters.sheaveModel,
                         "every sheave (traction, deflector, 2:1 car and counterweight, pit):\n"
                         "wrapped (default: the rope on their grooves, the falls vertical, the\n"
                         "traction sheave's wrap angle from the geometry) or point (the paper's\n"
                         "point sheaves, wrap angle pi)");
    app.add_flag("--deflector", o.parameters.deflector,
                 "1:1, wrapped: a deflector sheave (r 0.2 m, 0.8 m under the traction sheave)\n"
                 "leads the counterweight's fall off to x = 0.7 m (wrap angle 155 deg)");
    app.add_option("--car-hitch-offset", o.parameters.carHitchOffset,
                   "1:1: the car's hitch this far [m] outside the traction sheave's tangent,\n"
                   "0..0.5 (default 0): its fall leans, the wrap angle changes with the car")
        ->check(finiteNumber());
    app.add_flag("--compensation", o.parameters.compensation,
                 "a compensating rope under car and counterweight over a weighted pit sheave (500 kg)");
    app.add_option("--friction", o.parameters.friction, "effective groove friction coefficient mu (default 0.2)")
        ->check(positiveNumber());
    app.add_option("--rated-load", o.parameters.ratedLoad, "[kg] (default 630)")->check(positiveNumber());
    app.add_option_function<double>(
           "--car-load", [&o](double v) { o.parameters.carLoad = v; },
           "the car's load as a fraction of the rated load, 0..1.25 (default: the\n"
           "scenario's own: trip and emergency-stop 1, loading 1.25, stall 0)")
        ->type_name("F")
        ->check(finiteNumber());
    app.add_option_function<double>(
           "--car-position", [&o](double v) { o.parameters.carPosition = v; },
           "the car's height above the bottom landing at t = 0 [m], the\n"
           "counterweight where the rope puts it (default: the scenario's own:\n"
           "0; mid-shaft, 20, in emergency-stop); 0..38 in the 40 m shaft\n"
           "(emergency-stop: 2..38; trip: below 24, so that its 12 m end 4 m\n"
           "below the sheave)")
        ->type_name("Z")
        ->check(finiteNumber());
    app.add_option("--traction-slip", o.tractionSlip,
                   "how the rope slips over the traction sheave: constraint (default: a\n"
                   "massless contact point, the capstan law at every instant) or momentum\n"
                   "(the rope's inertia at the groove and the centrifugal term rhoA v^2)")
        ->check(oneOf({"constraint", "momentum"}));
    app.add_option("--retardation-time", o.parameters.retardationTime,
                   "Kelvin-Voigt rope damping c [s] (default 0: no damping)")
        ->check(finiteNumber());
    app.add_option("--axial-modes", o.axialModes, "n_a of both spans, 0..16 (default 1)")->transform(integerIn(0, 16));
    app.add_option("--transverse-modes", o.transverseModes, "n_t, 0..16 (default 1)")->transform(integerIn(0, 16));
    app.add_option("--integrator", o.integrator,
                   "rk-merson (default), rk3, rk-feldberg, cpodes, verlet,\nsemi-explicit-euler2, explicit-euler")
        ->check(oneOf(integratorNames()));
    app.add_option("--accuracy", o.accuracy, "integrator accuracy, 0 < TOL < 1 (default 1e-6)")
        ->check(numberInOpenInterval(0, 1));
    app.add_option("--t-end", o.tEnd, "end time of each scenario [s] (default: the scenario's own, 4.5-15 s)")
        ->type_name("T")
        ->check(positiveNumber());
    app.add_option("--report-interval", o.reportInterval, "output interval [s] (default 0.01)")->check(positiveNumber());
    demo_common::addRopeLifeOptions(app, o.ropeLife);
    app.add_option("--max-steps", o.maxSteps,
                   "stop a scenario with exit status 1 (nothing written) once the integrator\n"
                   "has taken N steps (default: no limit)")
        ->type_name("N")
        ->transform(integerIn(1, 1000000000L));
    app.add_flag("--check", o.check,
                 "check the options and build every scenario's scene, all validation\n"
                 "included, then exit: 0 valid, 2 not (nothing run or written)");
    app.add_option("--out", o.outDir, "output folder (default out/elevator)")->type_name("DIR")->check(nonEmpty());
    app.add_flag_callback("--no-plots", [&o] { o.plots = false; }, "do not make PNG figures");
    app.add_flag("--quiet", o.quiet, "no progress output");
    app.add_flag("--visualize", o.visualize, "show the runs in Simbody's Visualizer (headless without a display)");
    const int status = parseOrExitStatus(app, argc, argv);
    if (status >= 0) return status;
    o.parameters.roping = o.roping == "2:1" ? 2 : 1;
    o.parameters.tractionSlip = o.tractionSlip == "momentum" ? SimbodyReeving::TractionSlip::RopeMomentum
                                                             : SimbodyReeving::TractionSlip::CapstanConstraint;
    if (o.parameters.retardationTime < 0) {
        std::cerr << usageErrorText(kProgram, "--retardation-time: '" + numberText(o.parameters.retardationTime) +
                                                  "' must be >= 0");
        return kUsageExitStatus;
    }
    std::vector<ElevatorScenario> scenarios;
    if (o.scenario == "all")
        scenarios = {ElevatorScenario::Trip, ElevatorScenario::Loading, ElevatorScenario::EmergencyStop,
                     ElevatorScenario::Stall};
    else
        scenarios = {elevatorScenarioFromString(o.scenario)};
    // Every scenario's parameters (carPosition's range depends on the scenario); --check also builds
    // the scenes and their integrators.
    for (ElevatorScenario sc : scenarios) {
        try {
            const ElevatorParameters p = scenarioParameters(o, sc);
            p.validate();
            // The scene, for the bending count's options (D/d at its sheaves); --check: the integrator too.
            ElevatorScene scene(p, spanOptions(o));
            [[maybe_unused]] const RopeLifeMonitor bendingCount(scene.reeving(), 0, o.ropeLife.options());
            if (o.check) makeIntegrator(o.integrator, scene.system());
        } catch (const std::exception& e) {
            const std::string which = scenarios.size() > 1 ? std::string(" (scenario ") + toString(sc) + ")" : "";
            std::cerr << usageErrorText(kProgram, e.what() + which);
            return kUsageExitStatus;
        }
    }
    if (o.check) return 0;
    if (!prepareOutputFolder(kProgram, o.outDir)) return kUsageExitStatus;
    installInterruptHandlers();
    std::vector<Result> results;
    Json summary;
    summary["program"] = kProgram;
    summary["roping"] = o.roping;
    summary["compensation"] = o.parameters.compensation;
    summary["sheaves"] = o.parameters.sheaveModel == SimbodyReeving::SheaveModel::Wrapped ? "wrapped" : "point";
    summary["traction_slip"] = o.tractionSlip;
    summary["friction"] = jsonNumber(o.parameters.friction);
    summary["rated_load_kg"] = jsonNumber(o.parameters.ratedLoad);
    summary["car_mass_kg"] = jsonNumber(o.parameters.carMass);
    summary["counterweight_kg"] = jsonNumber(o.parameters.counterweight());
    summary["retardation_time_s"] = jsonNumber(o.parameters.retardationTime);
    Json table = Json::array();
    try {
        for (ElevatorScenario sc : scenarios) {
            if (!o.quiet) std::cout << kProgram << ": " << toString(sc) << " ..." << std::flush;
            results.push_back(run(o, sc));
            const Json j = summarize(results.back());
            if (!o.quiet)
                std::cout << " " << j["traction"].get<std::string>() << " (margin " << j["traction_margin"].dump()
                          << ", " << results.back().steps << " steps, " << results.back().wall << " s)\n";
            table.push_back(j);
        }
    } catch (const Interrupted&) {
        std::cerr << kProgram << ": interrupted; nothing written\n";
        return 130;
    } catch (const StepLimitReached& e) {
        std::cerr << kProgram << ": stopped: " << e.what() << "; nothing written\n";
        return 1;
    } catch (const std::exception& e) {
        std::cerr << kProgram << ": the simulation failed: " << e.what() << "\n";
        return 1;
    }
    summary["traction_table"] = table;
    // The traction sheave's wrap angle at the first run's start (given, pi with point sheaves, or the
    // geometry's; each run's range is in its row of the table).
    summary["wrap_angle_rad"] = jsonNumber(results.front().rows.front().wrap);
    summary["deflector"] = o.parameters.deflector;
    const fs::path dir(o.outDir);
    for (const Result& r : results) {
        writeTimeseries(dir / ("timeseries_" + r.scenario + ".csv"), r);
        for (const auto& [name, text] : {std::pair{".csv", &r.bendingCsv}, std::pair{".dat", &r.bendingFigure}}) {
            demo_common::OutputFile f(dir / ("rope_bending_" + r.scenario + name));
            f.stream() << *text;
            f.commit();
        }
    }
    {
        OutputFile f(dir / "summary.json");
        writeJson(f.stream(), summary);
        f.commit();
    }
    if (o.plots) plot(dir, results, o.parameters);
    if (!o.quiet) std::cout << kProgram << ": outputs in " << dir.string() << "\n";
    return 0;
}
