#include "BoomCraneCli.h"

#include <SimbodyReeving/simbody/Integrators.h>

#include <map>

namespace boom_crane_demo {
namespace {

using namespace demo_common;

const char* kDescription =
    "A slewing, luffing boom crane: a superstructure slewing on a ring, a 22 m lattice boom at 55\n"
    "degrees held by three falls of a 16 mm luffing rope over A-frame and tip sheaves, a 16 mm hoist\n"
    "rope (rhoA 1 kg/m, EA 1.6e7 N) from a drum over the boom's foot and tip sheaves to a two-fall\n"
    "hook block (150 kg), a 4 t payload on a 2 m sling. Both ropes are spatial: as the crane slews\n"
    "the load swings out of the boom's plane and the ropes leave the grooves at fleet angles.\n"
    "The 40 s cycle, from static equilibrium: rest 1 s, lift 4 m (1-9 s), slew 90 degrees while\n"
    "luffing the boom up 10 degrees (10-26 s), lower 4 m (28-36 s), settle until 40 s.\n";

const char* kFooter =
    "Outputs in DIR: timeseries.csv, snapshots.dat (the machine in 3D: columns x y z, the distance\n"
    "along the boom's plane, ink), rope_bending_luffing.csv and rope_bending_hoist.csv (bending cycles\n"
    "per rope section), summary.json (rope_life: each rope's most bent section) and, with gnuplot,\n"
    "fig_slew_luff.png, fig_swing.png, fig_span_axial_forces.png, fig_fleet_wrap_angles.png,\n"
    "fig_energy.png, fig_snapshots_side.png (in the boom's plane), fig_snapshots_plan.png (from above),\n"
    "fig_rope_bending_luffing.png and fig_rope_bending_hoist.png (cycles along each rope).\n"
    "Exit status: 0 run completed (with --check: the options are valid); 2 bad command line or\n"
    "unusable --out (nothing written); 3 a rope limit ended the run early (a span at\n"
    "minimumSpanLength: two-blocking; or a drum ran out of rope): the outputs up to that instant\n"
    "are written, summary.json says \"limit_reached\"; 1 the simulation failed or reached --max-steps\n"
    "(nothing written); 130 interrupted (SIGINT/SIGTERM, nothing written).";

// The --set keys: every scalar BoomCraneParameters field but boomAngle (--boom-angle, in degrees).
std::map<std::string, double*> parameterKeys(SimbodyReeving::BoomCraneParameters& p) {
    return {{"g", &p.g},
            {"superstructureMass", &p.superstructureMass},
            {"superstructureInertia", &p.superstructureInertia},
            {"boomLength", &p.boomLength},
            {"boomMass", &p.boomMass},
            {"luffSheaveRadius", &p.luffSheaveRadius},
            {"luffSheaveSpacing", &p.luffSheaveSpacing},
            {"footSheaveOffset", &p.footSheaveOffset},
            {"footSheaveHeight", &p.footSheaveHeight},
            {"hoistSheaveRadius", &p.hoistSheaveRadius},
            {"drumRadius", &p.drumRadius},
            {"drumMass", &p.drumMass},
            {"drumInertia", &p.drumInertia},
            {"ropeOnDrum", &p.ropeOnDrum},
            {"drumPitch", &p.drumPitch},
            {"hookMass", &p.hookMass},
            {"hookInertia", &p.hookInertia},
            {"hookComBelow", &p.hookComBelow},
            {"hookPinBelow", &p.hookPinBelow},
            {"initialHookDepth", &p.initialHookDepth},
            {"payloadMass", &p.payloadMass},
            {"payloadInertia", &p.payloadInertia},
            {"slingLength", &p.slingLength},
            {"rhoA", &p.rhoA},
            {"EA", &p.EA},
            {"EI", &p.EI},
            {"minimumSpanLength", &p.minimumSpanLength}};
}

// A --set item: KEY=VALUE with a known key and a finite number.
CLI::Validator setItem() {
    return CLI::Validator(
        [](std::string& text) {
            const auto eq = text.find('=');
            if (eq == std::string::npos) return "'" + text + "' must be KEY=VALUE";
            SimbodyReeving::BoomCraneParameters dummy;
            if (!parameterKeys(dummy).count(text.substr(0, eq))) return "'" + text + "': unknown key (see --help)";
            double v;
            if (!toFiniteNumber(text.substr(eq + 1), v)) return "'" + text + "': the value is not a finite number";
            return std::string();
        },
        "", "KEY=VALUE");
}

// The parameters after a change made by option `name` from `text`: BoomCraneParameters::validate,
// its message after the option and the value.
void validateAfter(const SimbodyReeving::BoomCraneParameters& p, const std::string& name, const std::string& text) {
    try {
        p.validate();
    } catch (const std::invalid_argument& e) {
        throw CLI::ValidationError(name, "'" + text + "': " + e.what());
    }
}

// A physical parameter as its own option: a number > 0 (times `scale` into SI units), checked
// with the others by BoomCraneParameters::validate.
void addParameterOption(CLI::App& app, Options& o, const std::string& name, double& field, double scale,
                        const std::string& typeName, const std::string& help) {
    app.add_option_function<std::string>(
           name,
           [&o, &field, name, scale](const std::string& text) {
               double v = 0;
               toFiniteNumber(text, v);
               field = v * scale;
               validateAfter(o.parameters, name, text);
           },
           help)
        ->type_name(typeName)
        ->check(positiveNumber());
}

// Binds every option to `o`. Callbacks (--sheaves, --axial-dynamics, the parameters, --set) run
// after the whole command line is read, in this order.
void defineOptions(CLI::App& app, Options& o) {
    applyConventions(app);
    app.description(kDescription);
    app.footer(kFooter);
    addSheaveModelOption(app, o.parameters.sheaveModel,
                         "wrapped (default: the ropes leave the sheaves at tangent points\n"
                         "in 3D and lie on their grooves) or point (the paper's point\n"
                         "sheave: the spans end at sheave centres; no fleet angles)");
    app.add_option("--axial-modes", o.axialModes, "n_a of every span, 0..16 (default 1)")
        ->type_name("N")
        ->transform(integerIn(0, SimbodyReeving::kMaxModesPerDirection));
    app.add_option("--transverse-modes", o.transverseModes, "n_t per direction, 0..16 (default 1)")
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
    app.add_option("--lift", o.lift, "hook lift of the cycle [m] (default 4; lowered back by as much)")
        ->type_name("M")
        ->check(positiveNumber());
    app.add_option("--slew-deg", o.slewDeg, "slewing angle of the cycle [deg] (default 90; 0 or negative allowed)")
        ->type_name("DEG")
        ->check(finiteNumber());
    app.add_option("--luff-deg", o.luffDeg,
                   "boom raised during the slew [deg] (default 10; negative lowers it;\n"
                   "the boom must stay within (10, 85) degrees)")
        ->type_name("DEG")
        ->check(finiteNumber());
    addParameterOption(app, o, "--payload-mass", o.parameters.payloadMass, 1.0, "KG", "payload mass [kg] (default 4000)");
    addParameterOption(app, o, "--hook-mass", o.parameters.hookMass, 1.0, "KG", "hook block mass [kg] (default 150)");
    addParameterOption(app, o, "--boom-length", o.parameters.boomLength, 1.0, "M",
                       "boom foot pin to tip sheaves [m], > 2 (default 22)");
    addParameterOption(app, o, "--boom-mass", o.parameters.boomMass, 1.0, "KG", "boom mass [kg] (default 2500)");
    addParameterOption(app, o, "--boom-angle", o.parameters.boomAngle, SimTK::Pi / 180.0, "DEG",
                       "boom angle above horizontal at rest [deg], in (10, 85) (default 55)");
    addParameterOption(app, o, "--hook-depth", o.parameters.initialHookDepth, 1.0, "M",
                       "hook sheave below the boom tip at rest [m], > 2 (default 14)");
    addParameterOption(app, o, "--ea", o.parameters.EA, 1.0, "N", "axial stiffness EA of both ropes [N] (default 1.6e7)");
    addParameterOption(app, o, "--rho-a", o.parameters.rhoA, 1.0, "KG_PER_M",
                       "mass per length rhoA of both ropes [kg/m] (default 1)");
    app.add_option_function<std::vector<std::string>>(
           "--set",
           [&o](const std::vector<std::string>& items) {
               for (const std::string& item : items) {
                   const auto eq = item.find('=');
                   double v = 0;
                   toFiniteNumber(item.substr(eq + 1), v);
                   *parameterKeys(o.parameters).at(item.substr(0, eq)) = v;
                   validateAfter(o.parameters, "--set", item);
               }
           },
           "crane parameter, repeatable (SI units): g superstructureMass\n"
           "superstructureInertia boomLength boomMass luffSheaveRadius\n"
           "luffSheaveSpacing footSheaveOffset footSheaveHeight hoistSheaveRadius\n"
           "drumRadius drumMass drumInertia ropeOnDrum drumPitch hookMass hookInertia\n"
           "hookComBelow hookPinBelow initialHookDepth payloadMass payloadInertia\n"
           "slingLength rhoA EA EI minimumSpanLength (see BoomCraneScene.h)")
        ->type_name("KEY=VALUE")
        ->allow_extra_args(false)
        ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll)
        ->check(setItem());
    app.add_option("--t-end", o.tEnd, "end time [s] (default: the whole cycle, 40 s)")->type_name("T")->check(positiveNumber());
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
    app.add_option("--report-interval", o.reportInterval, "output interval [s] (default 0.05)")
        ->type_name("DT")
        ->check(positiveNumber());
    demo_common::addRopeLifeOptions(app, o.ropeLife);
    app.add_option("--max-steps", o.maxSteps,
                   "stop with exit status 1 (nothing written) once the integrator\n"
                   "has taken N steps (default: no limit)")
        ->type_name("N")
        ->transform(integerIn(1, 1000000000L));
    app.add_flag("--check", o.check,
                 "check the options and build the scene, all validation\n"
                 "included, then exit: 0 valid, 2 not (nothing run or written)");
    app.add_option("--snapshots", o.snapshots, "machine snapshots over [0, t_end], 1..12 (default 6)")
        ->type_name("N")
        ->transform(integerIn(1, 12));
    app.add_option("--out", o.outDir, "output folder (default out/boom-crane)")->type_name("DIR")->check(nonEmpty());
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
    CLI::App app("", "reeving-boom-crane");
    defineOptions(app, o);
    return app.help();
}

SimbodyReeving::BoomCraneCycle Options::cycle() const {
    const double rad = SimTK::Pi / 180.0;
    return SimbodyReeving::BoomCraneCycle::liftSlewLower(parameters, lift, slewDeg * rad, luffDeg * rad);
}

Options parseCommandLine(int argc, char** argv) {
    Options o;
    CLI::App app("", "reeving-boom-crane");
    defineOptions(app, o);
    o.help = parse(app, argc, argv);
    if (o.help) return o;
    if (o.reportInterval > o.tEnd)
        throw UsageError("--report-interval: " + numberText(o.reportInterval) + " s must not exceed --t-end (" +
                         numberText(o.tEnd) + " s)");
    // The cycle's own checks (the parameters passed theirs above): the luff must keep the boom in range.
    try {
        o.cycle();
    } catch (const std::invalid_argument& e) {
        throw UsageError("--luff-deg: '" + numberText(o.luffDeg) + "': " + e.what());
    }
    return o;
}

}  // namespace boom_crane_demo
