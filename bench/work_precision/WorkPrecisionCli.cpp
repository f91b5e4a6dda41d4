#include "WorkPrecisionCli.h"

#include <SimbodyReeving/simbody/Integrators.h>
#include <SimbodyReeving/element/SpanModel.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <sstream>

namespace work_precision {
namespace {

[[noreturn]] void fail(const std::string& option, const std::string& value, const std::string& why) {
    throw UsageError(option + (value.empty() ? "" : " '" + value + "'") + ": " + why);
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

std::string shortText(double v) {
    std::ostringstream o;
    o << v;
    return o.str();
}

std::vector<std::string> splitList(const std::string& option, const std::string& text) {
    std::vector<std::string> items;
    std::stringstream ss(text);
    std::string item;
    while (std::getline(ss, item, ',')) {
        if (item.empty()) fail(option, text, "empty item in the comma list");
        items.push_back(item);
    }
    if (items.empty() || text.back() == ',') fail(option, text, "expected a comma list");
    return items;
}

std::vector<std::string> integratorList(const std::string& option, const std::string& text) {
    std::vector<std::string> out;
    const auto& names = SimbodyReeving::integratorNames();
    for (const std::string& n : splitList(option, text)) {
        if (std::find(names.begin(), names.end(), n) == names.end()) {
            std::string known;
            for (const auto& k : names) known += (known.empty() ? "" : ", ") + k;
            fail(option, n, "unknown integrator (known: " + known + ")");
        }
        if (std::find(out.begin(), out.end(), n) == out.end()) out.push_back(n);
    }
    return out;
}

std::vector<double> numberList(const std::string& option, const std::string& text, double lo, double hi,
                               const std::string& range) {
    std::vector<double> out;
    for (const std::string& item : splitList(option, text)) {
        const double v = toNumber(option, item);
        if (!(v > lo && v < hi)) fail(option, item, "each value must be in " + range);
        if (std::find(out.begin(), out.end(), v) == out.end()) out.push_back(v);
    }
    std::sort(out.begin(), out.end(), std::greater<double>());  // loosest / largest first
    return out;
}

}  // namespace

std::string usage() {
    return R"(Usage: bench-work-precision [options]
Work-precision study on the paper's pendulum (PendulumScene, Table 1 defaults, n_t = 1,
static equilibrium then vx0 = 1 m/s, reports every 0.01 s). For each integrator x accuracy (and
fixed step for --fixed-step-integrators) x n_a: max over the reports of the payload-centre position
error [m] and of the payload-end axial force error [N] against a reference trajectory, median wall
time of the integration, rhs evaluations, steps -- or why the point failed.

  --integrators LIST        comma list (default: all: rk-merson, rk3, rk-feldberg, cpodes, verlet,
                            semi-explicit-euler2, explicit-euler)
  --accuracies LIST         accuracy settings, each in (0,1) (default 1e-3,1e-4,...,1e-10)
  --steps LIST              fixed step sizes [s] (default 1e-3,1e-4,1e-5,1e-6)
  --fixed-step-integrators LIST|none
                            integrators also swept at the fixed --steps (default verlet,explicit-euler:
                            the two with a fixed-step constructor in Simbody; only those in
                            --integrators are run)
  --axial-modes LIST        n_a values, each 0..16 (default 0,1,3)
  --transverse-modes N      n_t, 0..16 (default 1)
  --axial-dynamics KIND     dynamic (default) or quasi-static (AxialDynamics of every span)
  --t-end T                 simulated time [s] (default 20)
  --report-interval DT      report (and error sampling) interval [s] (default 0.01)
  --repeats N               timed runs per point, median reported (default 3)
  --repeat-below S          a run slower than S seconds is not repeated (default 20)
  --cap S                   wall-clock cap per run [s], checked between reports (default 120);
                            a point past it is "too slow" and the integrator's tighter accuracies
                            (smaller steps) at that n_a are recorded as skipped
  --project-cap F           also stop a run as too slow once it has used 10 % of the cap and its
                            wall time projected to t_end (wall x t_end / t) exceeds F x cap,
                            F >= 1 (default: off; only the cap itself)
  --no-cap-skip             measure the tighter settings of an integrator after a too-slow one too
                            (the cost need not grow with the accuracy: CPodes at 1e-3 can be slower
                            than at 1e-6); --project-cap keeps hopeless runs short
  --cap-skips-higher-modes  also skip the same and tighter settings of that integrator at larger n_a
  --reference-integrator NAME  (default rk-feldberg)
  --reference-accuracy TOL  reference accuracy (default 1e-12; if that run fails, 10x looser is
                            tried, up to 3 times)
  --reference-check-factor F  the check reference runs at F x the reference accuracy (default 2:
                            "half the accuracy"), F > 1
  --recompute-reference     ignore cached references in the output folder
  --resume                  keep the points already recorded in DIR/results.csv (same integrator, n_a,
                            kind and setting) and measure only the others; tables and plots cover all
  --reference-only          compute (or load) the references, write reference_check.txt, stop
  --jobs N                  points run concurrently (default 1; timings want one job per idle core)
  --out DIR                 output folder (default out/work-precision)
  --no-plots                no PNG figures
  --quiet                   no progress output
  --help                    this text
Outputs in DIR: results.csv, table.md, reference_check.txt, reference_na<N>.csv (cache),
work_precision_na<N>.png (gnuplot), plots.gp.
)";
}

Options parseCommandLine(int argc, char** argv) {
    Options o;
    o.integrators = SimbodyReeving::integratorNames();
    std::vector<std::string> args(argv + 1, argv + argc);
    for (size_t i = 0; i < args.size(); ++i) {
        const std::string& opt = args[i];
        auto value = [&]() -> std::string {
            if (i + 1 >= args.size()) fail(opt, "", "missing value");
            return args[++i];
        };
        if (opt == "--help" || opt == "-h") {
            o.help = true;
        } else if (opt == "--integrators") {
            o.integrators = integratorList(opt, value());
        } else if (opt == "--fixed-step-integrators") {
            const std::string v = value();
            o.fixedStepIntegrators = v == "none" ? std::vector<std::string>{} : integratorList(opt, v);
        } else if (opt == "--accuracies") {
            o.accuracies = numberList(opt, value(), 0, 1, "(0, 1)");
        } else if (opt == "--steps") {
            o.steps = numberList(opt, value(), 0, 1, "(0, 1) s");
        } else if (opt == "--axial-modes") {
            const std::string v = value();
            o.axialModes.clear();
            for (const std::string& item : splitList(opt, v)) {
                const int n = toInteger(opt, item);
                if (n < 0 || n > SimbodyReeving::kMaxModesPerDirection) fail(opt, item, "each value must be in 0..16");
                if (std::find(o.axialModes.begin(), o.axialModes.end(), n) == o.axialModes.end())
                    o.axialModes.push_back(n);
            }
            std::sort(o.axialModes.begin(), o.axialModes.end());
        } else if (opt == "--transverse-modes") {
            const std::string v = value();
            o.transverseModes = toInteger(opt, v);
            if (o.transverseModes < 0 || o.transverseModes > SimbodyReeving::kMaxModesPerDirection)
                fail(opt, v, "must be in 0..16");
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
        } else if (opt == "--report-interval") {
            o.reportInterval = positive(opt, value());
        } else if (opt == "--repeats") {
            const std::string v = value();
            o.repeats = toInteger(opt, v);
            if (o.repeats < 1 || o.repeats > 99) fail(opt, v, "must be in 1..99");
        } else if (opt == "--repeat-below") {
            o.repeatBelow = positive(opt, value());
        } else if (opt == "--cap") {
            o.cap = positive(opt, value());
        } else if (opt == "--project-cap") {
            const std::string v = value();
            o.projectCap = positive(opt, v);
            if (o.projectCap < 1) fail(opt, v, "must be >= 1");
        } else if (opt == "--no-cap-skip") {
            o.capSkips = false;
        } else if (opt == "--cap-skips-higher-modes") {
            o.capSkipsHigherModes = true;
        } else if (opt == "--reference-integrator") {
            const auto list = integratorList(opt, value());
            if (list.size() != 1) fail(opt, args[i], "expected one integrator");
            o.referenceIntegrator = list.front();
        } else if (opt == "--reference-accuracy") {
            const std::string v = value();
            o.referenceAccuracy = positive(opt, v);
            if (!(o.referenceAccuracy < 1e-3)) fail(opt, v, "must be in (0, 1e-3)");
        } else if (opt == "--reference-check-factor") {
            const std::string v = value();
            o.referenceCheckFactor = positive(opt, v);
            if (!(o.referenceCheckFactor > 1 && o.referenceCheckFactor <= 100)) fail(opt, v, "must be in (1, 100]");
        } else if (opt == "--resume") {
            o.resume = true;
        } else if (opt == "--recompute-reference") {
            o.recomputeReference = true;
        } else if (opt == "--reference-only") {
            o.referenceOnly = true;
        } else if (opt == "--jobs" || opt == "-j") {
            const std::string v = value();
            o.jobs = toInteger(opt, v);
            if (o.jobs < 1 || o.jobs > 256) fail(opt, v, "must be in 1..256");
        } else if (opt == "--out") {
            o.outDir = value();
            if (o.outDir.empty()) fail(opt, o.outDir, "empty folder name");
        } else if (opt == "--no-plots") {
            o.plots = false;
        } else if (opt == "--quiet") {
            o.quiet = true;
        } else {
            fail(opt, "", "unknown option");
        }
    }
    if (o.reportInterval > o.tEnd) fail("--report-interval", shortText(o.reportInterval), "must not exceed --t-end");
    for (double h : o.steps)
        if (h > o.reportInterval)
            fail("--steps", shortText(h), "a fixed step must not exceed the report interval");
    return o;
}

}  // namespace work_precision
