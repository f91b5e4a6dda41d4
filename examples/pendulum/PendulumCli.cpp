#include "PendulumCli.h"

#include <SimbodyReeving/simbody/Integrators.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <sstream>

namespace pendulum_demo {
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
    if (text.empty() || end != text.c_str() + text.size()) fail(option, text, "not an integer");
    return static_cast<int>(v);
}

double positive(const std::string& option, const std::string& text) {
    const double v = toNumber(option, text);
    if (!(v > 0)) fail(option, text, "must be > 0");
    return v;
}

}  // namespace

std::string axialDynamicsName(SimbodyReeving::AxialDynamics a) {
    return a == SimbodyReeving::AxialDynamics::Dynamic ? "dynamic" : "quasi-static";
}

std::string usage() {
    return R"(Usage: reeving-pendulum [options]
The two-branch pendulum of Mohammadi & Escalona (Table 1): rope anchored at the first sheave, a
horizontal span a to a fixed deviation sheave, a vertical span L down to a 1000 kg payload; started
from static equilibrium with a horizontal payload velocity.

  --axial-modes LIST       comma list of n_a values, each 0..16 (default 0,1,2,3)
  --transverse-modes N     n_t, 0..16 (default 1)
  --axial-dynamics KIND    quasi-static (default: axial modes condensed, no axial waves; same
                           swing and slow axial force as the paper's model, about 60x faster at
                           n_a = 3) or dynamic (the paper's model: axial modes as states)
  --axial-law LAW          tension-only (default: a rope cannot push; slack spans carry no
                           axial force) or linear (the paper's law: P = EA eps, may push)
  --t-end T                end time [s] (default 20)
  --vx0 V                  initial horizontal payload velocity [m/s] (default 1)
  --vy0 V                  initial vertical payload velocity [m/s] (default 0)
  --integrator NAME        rk-merson (default), rk3, rk-feldberg, cpodes, verlet,
                           semi-explicit-euler2, explicit-euler
  --accuracy TOL           integrator accuracy, 0 < TOL < 1 (default 1e-6)
  --step H                 fixed step size [s] (fixed-step use of the integrator)
  --set KEY=VALUE          Table 1 parameter, repeatable: a L d r g rhoA EA EI M J (SI units)
  --report-interval DT     output interval [s] (default 0.01)
  --out DIR                output folder (default out/pendulum)
  --no-plots               do not make PNG figures
  --quiet                  no progress output
  --visualize              show the run in Simbody's Visualizer
  --help                   this text
Outputs: timeseries.csv, static_axial_force.csv, summary.json (in DIR, or DIR/modes-N/ for several
n_a) and fig2..fig5 PNG figures in DIR (gnuplot).
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
        } else if (opt == "--axial-modes") {
            const std::string v = value();
            o.axialModes.clear();
            std::stringstream ss(v);
            std::string item;
            while (std::getline(ss, item, ',')) {
                const int n = toInteger(opt, item);
                if (n < 0 || n > SimbodyReeving::kMaxModesPerDirection) fail(opt, v, "each value must be in 0..16");
                if (std::find(o.axialModes.begin(), o.axialModes.end(), n) == o.axialModes.end())
                    o.axialModes.push_back(n);
            }
            if (o.axialModes.empty() || v.back() == ',') fail(opt, v, "expected a comma list such as 0,1,3");
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
        } else if (opt == "--t-end") {
            o.tEnd = positive(opt, value());
        } else if (opt == "--vx0") {
            o.vx0 = toNumber(opt, value());
        } else if (opt == "--vy0") {
            o.vy0 = toNumber(opt, value());
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
            auto& p = o.parameters;
            double* target = key == "a" ? &p.a : key == "L" ? &p.L : key == "d" ? &p.d : key == "r" ? &p.r
                           : key == "g" ? &p.g : key == "rhoA" ? &p.rhoA : key == "EA" ? &p.EA
                           : key == "EI" ? &p.EI : key == "M" ? &p.M : key == "J" ? &p.J : nullptr;
            if (!target) fail(opt, v, "unknown key (a L d r g rhoA EA EI M J)");
            *target = x;
            try {
                p.validate();
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

}  // namespace pendulum_demo
