#include "CraneCli.h"

#include <SimbodyReeving/Integrators.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <map>
#include <sstream>

namespace crane_demo {
namespace {

[[noreturn]] void fail(const std::string& option, const std::string& value, const std::string& why) {
    throw UsageError(option + " '" + value + "': " + why);
}

double toNumber(const std::string& option, const std::string& text) {
    char* end = nullptr;
    const double v = std::strtod(text.c_str(), &end);
    if (text.empty() || end != text.c_str() + text.size() || !std::isfinite(v)) fail(option, text, "not a finite number");
    return v;
}

int toInteger(const std::string& option, const std::string& text) {
    char* end = nullptr;
    const long v = std::strtol(text.c_str(), &end, 10);
    if (text.empty() || end != text.c_str() + text.size() || v < -1000000 || v > 1000000)
        fail(option, text, "not an integer");
    return static_cast<int>(v);
}

double positive(const std::string& option, const std::string& text) {
    const double v = toNumber(option, text);
    if (!(v > 0)) fail(option, text, "must be > 0");
    return v;
}

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
            {"minimumSpanLength", &p.minimumSpanLength}};
}

}  // namespace

std::string axialDynamicsName(SimbodyReeving::AxialDynamics a) {
    return a == SimbodyReeving::AxialDynamics::Dynamic ? "dynamic" : "quasi-static";
}

std::string usage() {
    return R"(Usage: reeving-crane [options]
An overhead (gantry) crane: a trolley on a rail 15 m up with a prescribed traverse, a winch drum
(radius 0.3 m) with a prescribed hoist profile, a 20 mm wire rope (rhoA 1.6 kg/m, EA 2.5e7 N)
reeved in n falls between trolley sheaves and a 200 kg hook block, a 5 t payload on a 2 m sling.
From static equilibrium, the cycle: rest 1 s, lift 5 m (1-10 s), traverse 10 m (10.5-22.5 s),
lower 5 m (23.5-32.5 s), settle until 36 s.

  --falls N                rope parts between trolley and hook block, 1..12 (default 4)
  --axial-modes N          n_a of every fall, 0..16 (default 1)
  --transverse-modes N     n_t, 0..16 (default 1)
  --axial-dynamics KIND    quasi-static (default: axial modes condensed, no axial waves) or
                           dynamic (axial modes as states: axial waves, much slower)
  --axial-law LAW          tension-only (default: a rope cannot push; slack spans carry no
                           axial force) or linear (the paper's law: P = EA eps, may push)
  --lift M                 hook lift of the cycle [m] (default 5; lowered back by as much);
                           about 10.8 m or more two-blocks the hook (see exit status 3)
  --traverse M             trolley travel of the cycle [m] (default 10; 0 or negative allowed)
  --t-end T                end time [s] (default 36, the whole cycle)
  --integrator NAME        rk-merson (default), rk3, rk-feldberg, cpodes, verlet,
                           semi-explicit-euler2, explicit-euler
  --accuracy TOL           integrator accuracy, 0 < TOL < 1 (default 1e-6)
  --step H                 fixed step size [s] (fixed-step use of the integrator)
  --set KEY=VALUE          crane parameter, repeatable (SI units): g railHeight trolleyX0
                           trolleyMass sheavePitch sheaveRadius drumRadius drumHeight drumMass
                           drumInertia ropeOnDrum hookMass hookInertia hookComBelow hookPinBelow
                           initialHookDepth payloadMass payloadInertia slingLength payloadWidth
                           payloadHeight rhoA EA EI minimumSpanLength
  --report-interval DT     output interval [s] (default 0.02)
  --snapshots N            rope-geometry snapshots over [0, t_end], 1..12 (default 6)
  --out DIR                output folder (default out/crane)
  --no-plots               do not make PNG figures
  --quiet                  no progress output
  --visualize              show the run in Simbody's Visualizer (paced to real time)
  --help                   this text
Outputs in DIR: timeseries.csv, snapshots.dat (rope geometry), summary.json and, with gnuplot,
fig_hook_height_sway.png, fig_fall_tensions.png, fig_energy.png, fig_snapshots.png.
Exit status: 0 cycle completed; 2 bad command line or unusable --out (nothing written);
3 a rope limit ended the run early (a span at minimumSpanLength: two-blocking; or the drum ran
out of rope): the outputs up to that instant are written, summary.json says "limit_reached";
1 the simulation failed; 130 interrupted (SIGINT/SIGTERM, nothing written).
)";
}

Options parseCommandLine(int argc, char** argv) {
    Options o;
    std::vector<std::string> args(argv + 1, argv + argc);
    for (size_t i = 0; i < args.size(); ++i) {
        const std::string& opt = args[i];
        auto value = [&]() -> std::string {
            if (i + 1 >= args.size()) fail(opt, "", "missing value");
            return args[++i];
        };
        if (opt == "--help" || opt == "-h") {
            o.help = true;
        } else if (opt == "--falls") {
            const std::string v = value();
            o.parameters.falls = toInteger(opt, v);
            if (o.parameters.falls < 1 || o.parameters.falls > 12) fail(opt, v, "must be in 1..12");
        } else if (opt == "--axial-modes") {
            const std::string v = value();
            o.axialModes = toInteger(opt, v);
            if (o.axialModes < 0 || o.axialModes > SimbodyReeving::kMaxModesPerDirection) fail(opt, v, "must be in 0..16");
        } else if (opt == "--transverse-modes") {
            const std::string v = value();
            o.transverseModes = toInteger(opt, v);
            if (o.transverseModes < 0 || o.transverseModes > SimbodyReeving::kMaxModesPerDirection)
                fail(opt, v, "must be in 0..16");
        } else if (opt == "--axial-law") {
            const std::string v = value();
            if (v == "tension-only")
                o.parameters.tensionOnly = true;
            else if (v == "linear")
                o.parameters.tensionOnly = false;
            else
                fail(opt, v, "expected tension-only or linear");
        } else if (opt == "--axial-dynamics") {
            const std::string v = value();
            if (v == "dynamic")
                o.axialDynamics = SimbodyReeving::AxialDynamics::Dynamic;
            else if (v == "quasi-static")
                o.axialDynamics = SimbodyReeving::AxialDynamics::QuasiStatic;
            else
                fail(opt, v, "expected dynamic or quasi-static");
        } else if (opt == "--lift") {
            o.lift = positive(opt, value());
        } else if (opt == "--traverse") {
            o.traverse = toNumber(opt, value());
        } else if (opt == "--t-end") {
            o.tEnd = positive(opt, value());
        } else if (opt == "--integrator") {
            o.integrator = value();
            const auto& names = SimbodyReeving::integratorNames();
            if (std::find(names.begin(), names.end(), o.integrator) == names.end())
                fail(opt, o.integrator, "unknown integrator (see --help)");
        } else if (opt == "--accuracy") {
            const std::string v = value();
            o.accuracy = positive(opt, v);
            if (!(o.accuracy < 1)) fail(opt, v, "must be in (0, 1)");
        } else if (opt == "--step") {
            o.step = positive(opt, value());
        } else if (opt == "--report-interval") {
            o.reportInterval = positive(opt, value());
        } else if (opt == "--snapshots") {
            const std::string v = value();
            o.snapshots = toInteger(opt, v);
            if (o.snapshots < 1 || o.snapshots > 12) fail(opt, v, "must be in 1..12");
        } else if (opt == "--out") {
            o.outDir = value();
            if (o.outDir.empty()) fail(opt, o.outDir, "empty folder name");
        } else if (opt == "--no-plots") {
            o.plots = false;
        } else if (opt == "--quiet") {
            o.quiet = true;
        } else if (opt == "--visualize") {
            o.visualize = true;
        } else if (opt == "--set") {
            const std::string v = value();
            const auto eq = v.find('=');
            if (eq == std::string::npos) fail(opt, v, "expected KEY=VALUE");
            const std::string key = v.substr(0, eq);
            const double x = toNumber(opt, v.substr(eq + 1));
            auto keys = parameterKeys(o.parameters);
            const auto it = keys.find(key);
            if (it == keys.end()) fail(opt, v, "unknown key (see --help)");
            *it->second = x;
            try {
                o.parameters.validate();
            } catch (const std::invalid_argument& e) {
                fail(opt, v, e.what());
            }
        } else {
            fail(opt, "", "unknown option");
        }
    }
    if (o.reportInterval > o.tEnd)
        fail("--report-interval", std::to_string(o.reportInterval), "must not exceed --t-end");
    return o;
}

}  // namespace crane_demo
