#include "CraneCli.h"

#include <SimbodyReeving/simbody/Integrators.h>

#include <algorithm>
#include <map>

namespace crane_demo {
namespace {

using namespace demo_common;

const char* kDescription =
    "An overhead (gantry) crane: a trolley on a rail 15 m up with a prescribed traverse, a winch drum\n"
    "(radius 0.3 m) with a prescribed hoist profile, a 20 mm wire rope (rhoA 1.6 kg/m, EA 2.5e7 N)\n"
    "reeved in n falls between trolley sheaves and a 200 kg hook block, a 5 t payload on a 2 m sling.\n"
    "Scenario cycle (default), from static equilibrium: rest 1 s, lift 5 m (1-10 s), traverse 10 m\n"
    "(10.5-22.5 s), lower 5 m (23.5-32.5 s), settle until 36 s.\n"
    "Scenario lift-off: the payload rests on a compliant floor, the sling slack; the hoist reaches\n"
    "--hoist-speed v_h in 0.5 s, takes up the slack at v_h for 0.5 s, the sling tightens and the rope\n"
    "stretches at v_h until the load lifts off; the run ends half a bounce period later. summary.json:\n"
    "static_rope_force (M g + the falls' weight, all falls at their tops), peak_rope_force,\n"
    "dynamic_factor (their ratio), lift_off_time; the spring-mass reference 1 + v_h sqrt(k / M) / g.\n";

const char* kFooter =
    "Outputs in DIR: timeseries.csv, snapshots.dat (rope geometry), rope_bending.csv (bending cycles\n"
    "per rope section, from the start of the rope), summary.json (its rope_life: the most bent section) and,\n"
    "with gnuplot,\n"
    "fig_hook_height_sway.png, fig_fall_axial_forces.png, fig_energy.png, fig_snapshots.png,\n"
    "fig_rope_bending.png (cycles along the rope; lift-off: fig_lift_off.png too).\n"
    "Exit status: 0 run completed (with --check: the options are valid); 2 bad command line or\n"
    "unusable --out (nothing written); 3 a rope limit ended the run early (a span at\n"
    "minimumSpanLength: two-blocking; or the drum ran out of rope): the outputs up to that instant\n"
    "are written, summary.json says \"limit_reached\"; 1 the simulation failed or reached --max-steps\n"
    "(nothing written); 130 interrupted (SIGINT/SIGTERM, nothing written).";

// The --set keys: every numeric CraneParameters field but `falls` (--falls).
std::map<std::string, double*> parameterKeys(SimbodyReeving::CraneParameters& p) {
    return {{"g", &p.g},
            {"railHeight", &p.railHeight},
            {"trolleyX0", &p.trolleyX0},
            {"trolleyMass", &p.trolleyMass},
            {"sheavePitch", &p.sheavePitch},
            {"sheaveRadius", &p.sheaveRadius},
            {"drumRadius", &p.drumRadius},
            {"drumHeight", &p.drumHeight},
            {"drumMass", &p.drumMass},
            {"drumInertia", &p.drumInertia},
            {"ropeOnDrum", &p.ropeOnDrum},
            {"hookMass", &p.hookMass},
            {"hookInertia", &p.hookInertia},
            {"hookComBelow", &p.hookComBelow},
            {"hookPinBelow", &p.hookPinBelow},
            {"initialHookDepth", &p.initialHookDepth},
            {"payloadMass", &p.payloadMass},
            {"payloadInertia", &p.payloadInertia},
            {"slingLength", &p.slingLength},
            {"payloadWidth", &p.payloadWidth},
            {"payloadHeight", &p.payloadHeight},
            {"rhoA", &p.rhoA},
            {"EA", &p.EA},
            {"EI", &p.EI},
            {"minimumSpanLength", &p.minimumSpanLength},
            {"hoistRamp", &p.hoistRamp},
            {"slackTime", &p.slackTime},
            {"afterLiftOff", &p.afterLiftOff},
            {"floorStiffness", &p.floorStiffness},
            {"floorDampingRatio", &p.floorDampingRatio},
            {"slingStiffness", &p.slingStiffness},
            {"slingDampingRatio", &p.slingDampingRatio}};
}

// A --set item: KEY=VALUE with a known key and a finite number.
CLI::Validator setItem() {
    return CLI::Validator(
        [](std::string& text) {
            const auto eq = text.find('=');
            if (eq == std::string::npos) return "'" + text + "' must be KEY=VALUE";
            SimbodyReeving::CraneParameters dummy;
            if (!parameterKeys(dummy).count(text.substr(0, eq))) return "'" + text + "': unknown key (see --help)";
            double v;
            if (!toFiniteNumber(text.substr(eq + 1), v)) return "'" + text + "': the value is not a finite number";
            return std::string();
        },
        "", "KEY=VALUE");
}

// Binds every option to `o`. Callbacks (--axial-law, --axial-dynamics, --set) run after the whole
// command line is read, in this order.
void defineOptions(CLI::App& app, Options& o) {
    applyConventions(app);
    app.description(kDescription);
    app.footer(kFooter);
    app.add_option_function<std::string>(
           "--scenario",
           [&o](const std::string& v) {
               o.scenario = SimbodyReeving::craneScenarioFromString(v);
               o.parameters.scenario = o.scenario;
           },
           "cycle (default: lift, traverse, lower the hanging load) or lift-off\n"
           "(hoist a load resting on the floor at --hoist-speed)")
        ->type_name("NAME")
        ->check(oneOf({"cycle", "lift-off"}));
    app.add_option("--hoist-speed", o.parameters.hoistSpeed,
                   "lift-off: steady hoisting speed v_h of the hook [m/s] (default 0.3)")
        ->type_name("V")
        ->check(positiveNumber());
    addSheaveModelOption(app, o.parameters.sheaveModel,
                         "wrapped (default: the rope leaves the sheaves at tangent points\n"
                         "and lies on their grooves; the falls hang parallel, a sheave\n"
                         "diameter apart) or point (the paper's point sheave: the falls end\n"
                         "at sheave centres sheavePitch apart)");
    app.add_option("--falls", o.parameters.falls, "rope parts between trolley and hook block, 1..12 (default 4)")
        ->type_name("N")
        ->transform(integerIn(1, 12));
    app.add_option("--axial-modes", o.axialModes, "n_a of every fall, 0..16 (default 1)")
        ->type_name("N")
        ->transform(integerIn(0, SimbodyReeving::kMaxModesPerDirection));
    app.add_option("--transverse-modes", o.transverseModes, "n_t, 0..16 (default 1)")
        ->type_name("N")
        ->transform(integerIn(0, SimbodyReeving::kMaxModesPerDirection));
    app.add_option_function<std::string>(
           "--axial-dynamics",
           [&o](const std::string& v) {
               o.axialDynamics = v == "dynamic" ? SimbodyReeving::AxialDynamics::Dynamic
                                                : SimbodyReeving::AxialDynamics::QuasiStatic;
           },
           "quasi-static (default: axial modes condensed, no axial waves) or\n"
           "dynamic (axial modes as states: axial waves, much slower)")
        ->type_name("KIND")
        ->check(oneOf({"quasi-static", "dynamic"}));
    app.add_option_function<std::string>(
           "--axial-law", [&o](const std::string& v) { o.parameters.tensionOnly = v == "tension-only"; },
           "tension-only (default: a rope cannot push; slack spans carry no\n"
           "axial force) or linear (the paper's law: P = EA eps, may push)")
        ->type_name("LAW")
        ->check(oneOf({"tension-only", "linear"}));
    app.add_option("--lift", o.lift,
                   "hook lift of the cycle [m] (default 5; lowered back by as much);\n"
                   "about 10.8 m or more two-blocks the hook (see exit status 3)")
        ->type_name("M")
        ->check(positiveNumber());
    app.add_option("--traverse", o.traverse, "trolley travel of the cycle [m] (default 10; 0 or negative allowed)")
        ->type_name("M")
        ->check(finiteNumber());
    demo_common::addRopeLifeOptions(app, o.ropeLife);
    app.add_option("--t-end", o.tEnd, "end time [s] (default: the whole cycle, 36 s; lift-off: its duration)")
        ->type_name("T")
        ->check(positiveNumber());
    app.add_option("--integrator", o.integrator,
                   "rk-merson (default), rk3, rk-feldberg, cpodes, verlet,\nsemi-explicit-euler2, explicit-euler")
        ->type_name("NAME")
        ->check(oneOf(SimbodyReeving::integratorNames()));
    app.add_option("--accuracy", o.accuracy, "integrator accuracy, 0 < TOL < 1 (default 1e-6)")
        ->type_name("TOL")
        ->check(numberInOpenInterval(0, 1));
    app.add_option("--step", o.step, "fixed step size [s] (fixed-step use of the integrator)")
        ->type_name("H")
        ->check(positiveNumber());
    app.add_option_function<std::vector<std::string>>(
           "--set",
           [&o](const std::vector<std::string>& items) {
               for (const std::string& item : items) {
                   const auto eq = item.find('=');
                   double v = 0;
                   toFiniteNumber(item.substr(eq + 1), v);
                   *parameterKeys(o.parameters).at(item.substr(0, eq)) = v;
                   try {
                       o.parameters.validate();
                   } catch (const std::invalid_argument& e) {
                       throw CLI::ValidationError("--set", "'" + item + "': " + e.what());
                   }
               }
           },
           "crane parameter, repeatable (SI units): g railHeight trolleyX0\n"
           "trolleyMass sheavePitch sheaveRadius drumRadius drumHeight drumMass\n"
           "drumInertia ropeOnDrum hookMass hookInertia hookComBelow hookPinBelow\n"
           "initialHookDepth payloadMass payloadInertia slingLength payloadWidth\n"
           "payloadHeight rhoA EA EI minimumSpanLength; lift-off: hoistRamp\n"
           "slackTime afterLiftOff floorStiffness floorDampingRatio\n"
           "slingStiffness slingDampingRatio (see CraneScene.h)")
        ->type_name("KEY=VALUE")
        ->allow_extra_args(false)
        ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll)
        ->check(setItem());
    app.add_option("--report-interval", o.reportInterval, "output interval [s] (default 0.02; lift-off 0.001)")
        ->type_name("DT")
        ->check(positiveNumber());
    app.add_option("--max-steps", o.maxSteps,
                   "stop with exit status 1 (nothing written) once the integrator\n"
                   "has taken N steps (default: no limit)")
        ->type_name("N")
        ->transform(integerIn(1, 1000000000L));
    app.add_flag("--check", o.check,
                 "check the options and build the scene, all validation\n"
                 "included, then exit: 0 valid, 2 not (nothing run or written)");
    app.add_option("--snapshots", o.snapshots, "rope-geometry snapshots over [0, t_end], 1..12 (default 6)")
        ->type_name("N")
        ->transform(integerIn(1, 12));
    app.add_option("--out", o.outDir, "output folder (default out/crane)")->type_name("DIR")->check(nonEmpty());
    app.add_flag_callback("--no-plots", [&o] { o.plots = false; }, "do not make PNG figures");
    app.add_flag("--quiet", o.quiet, "no progress output");
    app.add_flag("--visualize", o.visualize, "show the run in Simbody's Visualizer (runs headless without a display)");
}

}  // namespace

std::string axialDynamicsName(SimbodyReeving::AxialDynamics a) {
    return a == SimbodyReeving::AxialDynamics::Dynamic ? "dynamic" : "quasi-static";
}

std::string usage() {
    Options o;
    CLI::App app("", "reeving-crane");
    defineOptions(app, o);
    return app.help();
}

SimbodyReeving::CraneCycle Options::cycle() const {
    return liftOff() ? SimbodyReeving::CraneCycle::liftOff(parameters)
                     : SimbodyReeving::CraneCycle::liftTraverseLower(lift, traverse);
}

Options parseCommandLine(int argc, char** argv) {
    Options o;
    CLI::App app("", "reeving-crane");
    defineOptions(app, o);
    o.help = parse(app, argc, argv);
    if (o.help) return o;
    // Options of the other scenario.
    for (const char* name : {"--lift", "--traverse"})
        if (o.liftOff() && app.count(name)) throw UsageError(std::string(name) + ": only with --scenario cycle");
    if (!o.liftOff() && app.count("--hoist-speed")) throw UsageError("--hoist-speed: only with --scenario lift-off");
    if (o.liftOff()) {
        if (!app.count("--t-end")) o.tEnd = o.cycle().duration;
        if (!app.count("--report-interval")) o.reportInterval = std::min(0.001, o.tEnd);
    }
    if (o.reportInterval > o.tEnd)
        throw UsageError("--report-interval: " + numberText(o.reportInterval) + " s must not exceed --t-end (" +
                         numberText(o.tEnd) + " s)");
    return o;
}

}  // namespace crane_demo
