#include "PendulumCli.h"

#include <SimbodyReeving/simbody/Integrators.h>

#include <map>

namespace pendulum_demo {
namespace {

using namespace demo_common;

const char* kDescription =
    "The two-branch pendulum of Mohammadi & Escalona (Table 1): rope anchored at the first sheave, a\n"
    "horizontal span a to a fixed deviation sheave, a vertical span L down to a 1000 kg payload; started\n"
    "from static equilibrium with a horizontal payload velocity.\n";

const char* kFooter =
    "Outputs: timeseries.csv, static_axial_force.csv, summary.json (in DIR, or DIR/modes-N/ for several\n"
    "n_a) and fig2..fig5 PNG figures in DIR (gnuplot).\n"
    "Exit status: 0 done (with --check: the options are valid); 2 bad command line or unusable --out\n"
    "(nothing written); 3 a rope limit ended a case early (a span at minimumSpanLength; with\n"
    "--sheaves wrapped, the wrap angle at 0: the rope leaving the groove): the outputs up to that\n"
    "instant are written, summary.json says \"limit_reached\"; 1 the simulation failed or reached\n"
    "--max-steps (nothing written); 130 interrupted (SIGINT/SIGTERM, nothing written).";

// The --set keys: the Table 1 parameters.
std::map<std::string, double*> parameterKeys(SimbodyReeving::PendulumParameters& p) {
    return {{"a", &p.a},   {"L", &p.L},       {"d", &p.d},   {"r", &p.r},   {"g", &p.g},
            {"rhoA", &p.rhoA}, {"EA", &p.EA}, {"EI", &p.EI}, {"M", &p.M}, {"J", &p.J}};
}

// A --set item: KEY=VALUE with a known key and a finite number.
CLI::Validator setItem() {
    return CLI::Validator(
        [](std::string& text) {
            const auto eq = text.find('=');
            if (eq == std::string::npos) return "'" + text + "' must be KEY=VALUE";
            SimbodyReeving::PendulumParameters dummy;
            if (!parameterKeys(dummy).count(text.substr(0, eq)))
                return "'" + text + "': unknown key (a L d r g rhoA EA EI M J)";
            double v;
            if (!toFiniteNumber(text.substr(eq + 1), v)) return "'" + text + "': the value is not a finite number";
            return std::string();
        },
        "", "KEY=VALUE");
}

// Binds every option to `o`. Callbacks (axial modes, --axial-law, --axial-dynamics, --set) run
// after the whole command line is read, in this order.
void defineOptions(CLI::App& app, Options& o) {
    applyConventions(app);
    app.description(kDescription);
    app.footer(kFooter);
    app.add_option_function<std::string>(
           "--axial-modes", [&o](const std::string& v) { o.axialModes = parseIntegerList(v); },
           "comma list of n_a values, each 0..16 (default 0,1,2,3)")
        ->type_name("LIST")
        ->check(integerListIn(0, SimbodyReeving::kMaxModesPerDirection));
    app.add_option("--transverse-modes", o.transverseModes, "n_t, 0..16 (default 1)")
        ->type_name("N")
        ->transform(integerIn(0, SimbodyReeving::kMaxModesPerDirection));
    app.add_option_function<std::string>(
           "--axial-dynamics",
           [&o](const std::string& v) {
               o.axialDynamics = v == "dynamic" ? SimbodyReeving::AxialDynamics::Dynamic
                                                : SimbodyReeving::AxialDynamics::QuasiStatic;
           },
           "quasi-static (default: axial modes condensed, no axial waves; same\n"
           "swing and slow axial force as the paper's model, about 60x faster at\n"
           "n_a = 3) or dynamic (the paper's model: axial modes as states)")
        ->type_name("KIND")
        ->check(oneOf({"quasi-static", "dynamic"}));
    app.add_option_function<std::string>(
           "--quasi-static-transverse",
           [&o](const std::string& v) {
               o.quasiStaticTransverse = v == "all"          ? Options::QuasiStaticTransverse::All
                                         : v == "horizontal" ? Options::QuasiStaticTransverse::Horizontal
                                                             : Options::QuasiStaticTransverse::None;
           },
           "none (default: transverse modes are states, the spans vibrate as\n"
           "strings), horizontal (the 3 m span's transverse modes condensed: its\n"
           "static sag without its 21 Hz string mode) or all")
        ->type_name("SPANS")
        ->check(oneOf({"none", "horizontal", "all"}));
    app.add_option_function<std::string>(
           "--axial-law", [&o](const std::string& v) { o.parameters.tensionOnly = v == "tension-only"; },
           "tension-only (default: a rope cannot push; slack spans carry no\n"
           "axial force) or linear (the paper's law: P = EA eps, may push)")
        ->type_name("LAW")
        ->check(oneOf({"tension-only", "linear"}));
    addSheaveModelOption(app, o.parameters.sheaveModel,
                         "point (default: the paper's point sheave) or wrapped (the rope over\n"
                         "the groove of radius r, the vertical span leaving at its tangent point)");
    app.add_option("--t-end", o.tEnd, "end time [s] (default 20)")->type_name("T")->check(positiveNumber());
    app.add_option("--vx0", o.vx0, "initial horizontal payload velocity [m/s] (default 1)")
        ->type_name("V")
        ->check(finiteNumber());
    app.add_option("--vy0", o.vy0, "initial vertical payload velocity [m/s] (default 0)")
        ->type_name("V")
        ->check(finiteNumber());
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
           "Table 1 parameter, repeatable: a L d r g rhoA EA EI M J (SI units)")
        ->type_name("KEY=VALUE")
        ->allow_extra_args(false)
        ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll)
        ->check(setItem());
    app.add_option("--report-interval", o.reportInterval, "output interval [s] (default 0.01)")
        ->type_name("DT")
        ->check(positiveNumber());
    app.add_option("--max-steps", o.maxSteps,
                   "stop with exit status 1 (nothing written) once a case's integrator\n"
                   "has taken N steps (default: no limit)")
        ->type_name("N")
        ->transform(integerIn(1, 1000000000L));
    app.add_flag("--check", o.check,
                 "check the options and build every case's scene, all validation\n"
                 "included, then exit: 0 valid, 2 not (nothing run or written)");
    app.add_option("--out", o.outDir, "output folder (default out/pendulum)")->type_name("DIR")->check(nonEmpty());
    app.add_flag_callback("--no-plots", [&o] { o.plots = false; }, "do not make PNG figures");
    app.add_flag("--quiet", o.quiet, "no progress output");
    app.add_flag("--visualize", o.visualize, "show the run in Simbody's Visualizer");
}

}  // namespace

std::string quasiStaticTransverseName(Options::QuasiStaticTransverse q) {
    switch (q) {
        case Options::QuasiStaticTransverse::All: return "all";
        case Options::QuasiStaticTransverse::Horizontal: return "horizontal";
        case Options::QuasiStaticTransverse::None: break;
    }
    return "none";
}

std::string axialDynamicsName(SimbodyReeving::AxialDynamics a) {
    return a == SimbodyReeving::AxialDynamics::Dynamic ? "dynamic" : "quasi-static";
}

std::string usage() {
    Options o;
    CLI::App app("", "reeving-pendulum");
    defineOptions(app, o);
    return app.help();
}

Options parseCommandLine(int argc, char** argv) {
    Options o;
    CLI::App app("", "reeving-pendulum");
    defineOptions(app, o);
    o.help = parse(app, argc, argv);
    if (!o.help && o.reportInterval > o.tEnd)
        throw UsageError("--report-interval: " + numberText(o.reportInterval) + " s must not exceed --t-end (" +
                         numberText(o.tEnd) + " s)");
    if (!o.help && o.quasiStaticTransverse != Options::QuasiStaticTransverse::None &&
        o.axialDynamics == SimbodyReeving::AxialDynamics::Dynamic)
        for (int na : o.axialModes)
            if (na > 0)
                throw UsageError("--quasi-static-transverse " + quasiStaticTransverseName(o.quasiStaticTransverse) +
                                 " requires --axial-dynamics quasi-static when n_a > 0 (got n_a = " +
                                 std::to_string(na) + ")");
    return o;
}

}  // namespace pendulum_demo
