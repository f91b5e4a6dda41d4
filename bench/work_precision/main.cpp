// bench-work-precision: the work-precision study on the paper's pendulum.
// Error vs wall time for every Simbody integrator the demo offers, against a cached tight reference.
// See --help, and the comments below for what each recorded number means.
//
// Counters (Simbody 3.7, simmath AbstractIntegratorRep / IntegratorRep):
//  - rhs evaluations = InterpolatingTimeStepper::getNumRealizations() (Integrator::getNumRealizations()
//    plus the step-start realizations the stepper does itself): the number of calls that realize a state
//    through Stage::Acceleration (realizeStateDerivatives: counted only when the state is below
//    Acceleration), i.e. evaluations of the right-hand side qdot, udot, zdot -- including those of
//    rejected steps and, for CPodes, of its finite-difference Jacobians. Projections and the
//    per-report observations (Stage::Position) are not counted.
//  - steps = Integrator::getNumStepsTaken(): accepted steps.
// Wall time is that of TimeStepper::initialize and the stepTo calls only (not building the scene,
// not the static equilibrium, not evaluating the observables at the reports).
#include "WorkPrecisionCli.h"

#include <SimbodyReeving/simbody/Integrators.h>
#include <SimbodyReeving/simbody/InterpolatingTimeStepper.h>
#include <SimbodyReeving/scenes/PendulumScene.h>

#include <Simbody.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iomanip>
#include <iostream>
#include <map>
#include <mutex>
#include <sstream>
#include <thread>

namespace fs = std::filesystem;
using namespace work_precision;

namespace {

using Clock = std::chrono::steady_clock;

double secondsSince(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

std::string num(double v, int digits = 17) {
    std::ostringstream o;
    o << std::setprecision(digits) << v;
    return o.str();
}

std::string sci(double v, int digits = 2) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.*e", digits, v);
    return buf;
}

/// One report: time, payload centre, payload-end axial force.
struct Sample {
    double t, x, y, z, P;
};
using Trajectory = std::vector<Sample>;

enum class Kind { Accuracy, FixedStep };
const char* kindName(Kind k) { return k == Kind::Accuracy ? "accuracy" : "fixed_step"; }

struct RunSpec {
    std::string integrator;
    int axialModes = 0;
    Kind kind = Kind::Accuracy;
    double setting = 0;  // accuracy, or fixed step [s]
};

struct RunResult {
    std::string status = "ok";  // ok | failed | blow-up | too slow | skipped
    std::string reason;
    double posErr = 0, forceErr = 0, wall = 0, tReached = 0;
    long rhs = 0, steps = 0;
    bool errorControl = false;
    std::string methodName;
    Trajectory trajectory;  // only when asked for (references)
};

struct Point {
    RunSpec spec;
    RunResult result;  // of the first run; wall replaced by the median
    std::vector<double> walls;
    std::string wallNote;
    bool done = false;
};

int reportCount(const Options& o) { return static_cast<int>(std::floor(o.tEnd / o.reportInterval + 1e-9)); }

Sample observe(const SimbodyReeving::PendulumScene& scene, const SimTK::State& s) {
    scene.system().realize(s, SimTK::Stage::Dynamics);  // QuasiStatic: force with the mode-acceleration correction
    const SimTK::Vec3 p = scene.payloadPosition(s);
    return {s.getTime(), p[0], p[1], p[2], scene.axialForceAtPayload(s)};
}

/// One timed integration. `ref` (may be null) gives the errors; `cap` <= 0: no cap; `progress`
/// (may be null) receives the simulated time.
RunResult runOnce(const Options& o, const RunSpec& spec, const Trajectory* ref, double cap, bool keep,
                  const std::function<void(double)>& progress = {}) {
    RunResult r;
    SimbodyReeving::SpanOptions spans;
    spans.axialModes = spec.axialModes;
    spans.transverseModes = o.transverseModes;
    spans.axialDynamics = o.axialDynamics;
    spans.velocityModel = SimbodyReeving::VelocityModel::Simplified;  // not the default: the setting of the recorded results
    const SimbodyReeving::PendulumParameters params{};
    SimbodyReeving::PendulumScene scene(params, spans);
    const SimTK::State s0 = scene.makeInitialState(o.vx0, o.vy0);
    auto integ = SimbodyReeving::makeIntegrator(spec.integrator, scene.system());
    r.errorControl = integ->methodHasErrorControl();
    r.methodName = integ->getMethodName();
    if (spec.kind == Kind::Accuracy) {
        integ->setAccuracy(spec.setting);
    } else {
        integ->setFixedStepSize(spec.setting);
    }
    const double boxRadius = 2 * (params.a + params.L);           // [m] around the deviation sheave
    const double forceLimit = 1e3 * (params.M + params.rhoA * (params.a + params.L)) * params.g;  // [N]
    const int reports = reportCount(o);
    auto account = [&](const Sample& smp, int n) -> bool {
        r.tReached = smp.t;
        const bool finite = std::isfinite(smp.x) && std::isfinite(smp.y) && std::isfinite(smp.z) && std::isfinite(smp.P);
        if (!finite) {
            r.status = "blow-up";
            r.reason = "non-finite payload position or force at t = " + num(smp.t, 6) + " s";
            return false;
        }
        const double dx = smp.x - params.a, dist = std::sqrt(dx * dx + smp.y * smp.y + smp.z * smp.z);
        if (dist > boxRadius || std::abs(smp.P) > forceLimit) {
            r.status = "blow-up";
            r.reason = "payload left the sanity box (|x - sheave| <= " + num(boxRadius, 4) + " m, |P| <= " +
                       sci(forceLimit, 1) + " N) at t = " + num(smp.t, 6) + " s";
            return false;
        }
        if (keep) r.trajectory.push_back(smp);
        if (ref) {
            const Sample& q = (*ref)[static_cast<size_t>(n)];
            const double ex = smp.x - q.x, ey = smp.y - q.y, ez = smp.z - q.z;
            r.posErr = std::max(r.posErr, std::sqrt(ex * ex + ey * ey + ez * ez));
            r.forceErr = std::max(r.forceErr, std::abs(smp.P - q.P));
        }
        return true;
    };
    double wall = 0;
    // Reports are interpolated (InterpolatingTimeStepper): the steps do not depend on the report
    // interval, as a user asking for smooth output expects.
    SimbodyReeving::InterpolatingTimeStepper ts(scene.system(), *integ);
    try {
        // The cap must also stop a run inside one report interval (e.g. variable-step Verlet
        // creeping with tiny steps): the stepper returns every kStepChunk internal steps
        // (ReachedStepLimit) and stepTo is called again. This does not change the steps taken.
        constexpr int kStepChunk = 2000;
        ts.setStepLimit(kStepChunk);
        auto t0 = Clock::now();
        ts.initialize(s0);
        wall += secondsSince(t0);
        bool alive = account(observe(scene, ts.getState()), 0);
        bool capped = false;
        // The cap (and, with --project-cap, the projection of the wall time to t_end) is checked
        // whenever the integrator returns: at every report and every kStepChunk internal steps.
        auto checkCap = [&](double elapsed) {
            const double t = ts.getState().getTime();
            if (cap <= 0 || t >= o.tEnd) return false;
            if (elapsed > cap) {
                r.reason = "wall-clock cap " + num(cap, 6) + " s reached at t = " + num(t, 6) + " s";
                return true;
            }
            if (o.projectCap > 0 && elapsed > 0.1 * cap && t > 0 && elapsed * o.tEnd / t > o.projectCap * cap) {
                r.reason = "projected wall " + num(elapsed * o.tEnd / t, 3) + " s to t_end > " + num(o.projectCap, 3) +
                           " x cap " + num(cap, 6) + " s (stopped at t = " + num(t, 6) + " s, " + num(elapsed, 3) +
                           " s)";
                return true;
            }
            return false;
        };
        for (int n = 1; alive && n <= reports; ++n) {
            const double target = n * o.reportInterval;
            t0 = Clock::now();
            while (!integ->isSimulationOver()) {
                ts.stepTo(target);
                if (checkCap(wall + secondsSince(t0))) {
                    capped = true;
                    break;
                }
                if (ts.getState().getTime() >= target) break;
            }
            wall += secondsSince(t0);
            if (capped) {
                r.status = "too slow";
                r.tReached = ts.getState().getTime();
                break;
            }
            if (integ->isSimulationOver() &&
                integ->getTerminationReason() != SimTK::Integrator::ReachedFinalTime) {
                r.status = "failed";
                r.reason = "integrator terminated: " +
                           std::string(SimTK::Integrator::getTerminationReasonString(integ->getTerminationReason()));
                r.tReached = ts.getState().getTime();
                break;
            }
            alive = account(observe(scene, ts.getState()), n);
            if (progress) progress(ts.getState().getTime());
        }
    } catch (const std::exception& e) {
        r.status = "failed";
        std::string what = e.what();
        // Simbody's messages span several lines; keep one line for the CSV and tables.
        for (char& c : what)
            if (c == '\n' || c == '\r' || c == '"') c = ' ';
        r.reason = what;
        r.tReached = integ->getState().getTime();
    }
    r.wall = wall;
    r.rhs = ts.getNumRealizations();
    r.steps = integ->getNumStepsTaken();
    return r;
}

double median(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    const size_t n = v.size();
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

// ---- references ---------------------------------------------------------------------------

struct Reference {
    int axialModes = 0;
    double accuracy = 0, checkAccuracy = 0;
    Trajectory main, check;
    double wallMain = 0, wallCheck = 0;
    long stepsMain = 0, stepsCheck = 0, rhsMain = 0, rhsCheck = 0;
    std::vector<std::string> notes;  // e.g. tighter accuracies that failed
    double maxPosDiff = 0, maxForceDiff = 0;
    bool fromCache = false;
};

/// The run parameters a cached reference must match, as key/value text.
std::map<std::string, std::string> referenceKey(const Options& o, int na) {
    const SimbodyReeving::PendulumParameters p{};
    return {{"integrator", o.referenceIntegrator},
            {"requested_accuracy", num(o.referenceAccuracy)},
            {"check_factor", num(o.referenceCheckFactor)},
            {"axial_modes", std::to_string(na)},
            {"transverse_modes", std::to_string(o.transverseModes)},
            {"axial_dynamics", o.axialDynamics == SimbodyReeving::AxialDynamics::Dynamic ? "dynamic" : "quasi-static"},
            {"t_end", num(o.tEnd)},
            {"report_interval", num(o.reportInterval)},
            {"vx0", num(o.vx0)},
            {"vy0", num(o.vy0)},
            {"parameters", num(p.a) + " " + num(p.L) + " " + num(p.d) + " " + num(p.r) + " " + num(p.g) + " " +
                               num(p.rhoA) + " " + num(p.EA) + " " + num(p.EI) + " " + num(p.M) + " " + num(p.J)}};
}

fs::path referencePath(const Options& o, int na) { return fs::path(o.outDir) / ("reference_na" + std::to_string(na) + ".csv"); }

void compareReferences(Reference& ref) {
    ref.maxPosDiff = ref.maxForceDiff = 0;
    for (size_t k = 0; k < ref.main.size(); ++k) {
        const Sample &a = ref.main[k], &b = ref.check[k];
        const double ex = a.x - b.x, ey = a.y - b.y, ez = a.z - b.z;
        ref.maxPosDiff = std::max(ref.maxPosDiff, std::sqrt(ex * ex + ey * ey + ez * ez));
        ref.maxForceDiff = std::max(ref.maxForceDiff, std::abs(a.P - b.P));
    }
}

/// The reference resolves an error only if the error is at least kFloorFactor times the change of
/// the reference itself when its accuracy is halved (the check run). Smaller errors are reported as
/// "below the reference floor", never as numbers, and an error target below the floor is "not
/// verifiable" rather than reached.
constexpr double kFloorFactor = 10;
struct Floors {
    double position = 0, force = 0;  // [m], [N]
};
Floors floorsOf(const Reference& r) { return {kFloorFactor * r.maxPosDiff, kFloorFactor * r.maxForceDiff}; }

/// An error as table text: the number, or "< floor" when the reference cannot resolve it.
std::string errorText(double error, double floor) {
    return error < floor ? "< " + sci(floor, 1) + " (floor)" : sci(error);
}

void saveReference(const Options& o, const Reference& ref) {
    const fs::path path = referencePath(o, ref.axialModes);
    const fs::path tmp = path.string() + ".tmp";
    {
        std::ofstream f(tmp);
        for (const auto& [k, v] : referenceKey(o, ref.axialModes)) f << "# " << k << " = " << v << "\n";
        f << "# used_accuracy = " << num(ref.accuracy) << "\n# check_accuracy = " << num(ref.checkAccuracy) << "\n"
          << "# wall_main = " << num(ref.wallMain) << "\n# wall_check = " << num(ref.wallCheck) << "\n"
          << "# steps_main = " << ref.stepsMain << "\n# steps_check = " << ref.stepsCheck << "\n"
          << "# rhs_main = " << ref.rhsMain << "\n# rhs_check = " << ref.rhsCheck << "\n";
        for (const std::string& note : ref.notes) f << "# note = " << note << "\n";
        f << "t,x,y,z,P,x_check,y_check,z_check,P_check\n" << std::setprecision(17);
        for (size_t k = 0; k < ref.main.size(); ++k) {
            const Sample &a = ref.main[k], &b = ref.check[k];
            f << a.t << ',' << a.x << ',' << a.y << ',' << a.z << ',' << a.P << ',' << b.x << ',' << b.y << ','
              << b.z << ',' << b.P << '\n';
        }
    }
    fs::rename(tmp, path);
}

/// Loads a cached reference if its header matches the run parameters; false otherwise (`why` says).
bool loadReference(const Options& o, int na, Reference& ref, std::string& why) {
    const fs::path path = referencePath(o, na);
    std::ifstream f(path);
    if (!f) {
        why = "no cache file";
        return false;
    }
    std::map<std::string, std::string> header;
    std::vector<std::string> notes;
    std::string line;
    while (std::getline(f, line) && line.rfind("# ", 0) == 0) {
        const auto eq = line.find(" = ");
        if (eq == std::string::npos) continue;
        const std::string k = line.substr(2, eq - 2), v = line.substr(eq + 3);
        if (k == "note")
            notes.push_back(v);
        else
            header[k] = v;
    }
    for (const auto& [k, v] : referenceKey(o, na)) {
        if (header[k] != v) {
            why = "cache parameter " + k + " is '" + header[k] + "', this run has '" + v + "'";
            return false;
        }
    }
    try {
        ref.axialModes = na;
        ref.accuracy = std::stod(header.at("used_accuracy"));
        ref.checkAccuracy = std::stod(header.at("check_accuracy"));
        ref.wallMain = std::stod(header.at("wall_main"));
        ref.wallCheck = std::stod(header.at("wall_check"));
        ref.stepsMain = std::stol(header.at("steps_main"));
        ref.stepsCheck = std::stol(header.at("steps_check"));
        ref.rhsMain = std::stol(header.at("rhs_main"));
        ref.rhsCheck = std::stol(header.at("rhs_check"));
        ref.notes = notes;
        ref.main.clear();
        ref.check.clear();
        while (std::getline(f, line)) {
            double v[9];
            if (std::sscanf(line.c_str(), "%lf,%lf,%lf,%lf,%lf,%lf,%lf,%lf,%lf", &v[0], &v[1], &v[2], &v[3], &v[4], &v[5],
                            &v[6], &v[7], &v[8]) != 9) {
                why = "malformed line in the cache";
                return false;
            }
            ref.main.push_back({v[0], v[1], v[2], v[3], v[4]});
            ref.check.push_back({v[0], v[5], v[6], v[7], v[8]});
        }
    } catch (const std::exception& e) {
        why = std::string("malformed cache header: ") + e.what();
        return false;
    }
    if (ref.main.size() != static_cast<size_t>(reportCount(o) + 1)) {
        why = "cache has " + std::to_string(ref.main.size()) + " reports";
        return false;
    }
    compareReferences(ref);
    ref.fromCache = true;
    return true;
}

std::mutex ioMutex;

void say(const Options& o, const std::string& text) {
    if (o.quiet) return;
    std::lock_guard<std::mutex> lock(ioMutex);
    std::cerr << text << std::flush;
}

/// Computes (or loads) the reference of one n_a. @throws std::runtime_error if no reference
/// accuracy works.
Reference makeReference(const Options& o, int na) {
    Reference ref;
    std::string why;
    if (!o.recomputeReference && loadReference(o, na, ref, why)) {
        say(o, "reference n_a=" + std::to_string(na) + ": loaded " + referencePath(o, na).string() + "\n");
        return ref;
    }
    if (!o.recomputeReference) say(o, "reference n_a=" + std::to_string(na) + ": computing (" + why + ")\n");
    ref.axialModes = na;
    auto run = [&](double acc, const char* label) {
        RunSpec spec{o.referenceIntegrator, na, Kind::Accuracy, acc};
        auto last = Clock::now();
        const auto start = Clock::now();
        auto progress = [&](double t) {
            if (secondsSince(last) > 10) {
                last = Clock::now();
                say(o, "  reference n_a=" + std::to_string(na) + " " + label + " accuracy " + sci(acc, 1) + ": t = " +
                           num(t, 4) + " s, wall " + num(secondsSince(start), 4) + " s\n");
            }
        };
        return runOnce(o, spec, nullptr, 0, true, progress);
    };
    double acc = o.referenceAccuracy;
    for (int attempt = 0;; ++attempt, acc *= 10) {
        if (attempt == 4)
            throw std::runtime_error("no reference for n_a = " + std::to_string(na) + ": every accuracy from " +
                                     sci(o.referenceAccuracy, 1) + " to " + sci(acc / 10, 1) + " failed");
        RunResult m = run(acc, "main");
        if (m.status != "ok") {
            ref.notes.push_back("accuracy " + sci(acc, 1) + " did not converge: " + m.status + ": " + m.reason);
            say(o, "reference n_a=" + std::to_string(na) + ": " + ref.notes.back() + "\n");
            continue;
        }
        RunResult c = run(acc * o.referenceCheckFactor, "check");
        if (c.status != "ok") {
            ref.notes.push_back("check accuracy " + sci(acc * o.referenceCheckFactor, 1) + " failed: " + c.status +
                                ": " + c.reason);
            say(o, "reference n_a=" + std::to_string(na) + ": " + ref.notes.back() + "\n");
            continue;
        }
        ref.accuracy = acc;
        ref.checkAccuracy = acc * o.referenceCheckFactor;
        ref.main = std::move(m.trajectory);
        ref.check = std::move(c.trajectory);
        ref.wallMain = m.wall;
        ref.wallCheck = c.wall;
        ref.stepsMain = m.steps;
        ref.stepsCheck = c.steps;
        ref.rhsMain = m.rhs;
        ref.rhsCheck = c.rhs;
        break;
    }
    compareReferences(ref);
    fs::create_directories(o.outDir);
    saveReference(o, ref);
    say(o, "reference n_a=" + std::to_string(na) + ": accuracy " + sci(ref.accuracy, 1) + " (" +
               num(ref.wallMain, 4) + " s, " + std::to_string(ref.stepsMain) + " steps), check at " +
               sci(ref.checkAccuracy, 1) + " (" + num(ref.wallCheck, 4) + " s): max |dx| " + sci(ref.maxPosDiff) +
               " m, max |dP| " + sci(ref.maxForceDiff) + " N\n");
    return ref;
}

// ---- the sweep ----------------------------------------------------------------------------

std::string settingText(const RunSpec& s) {
    return s.kind == Kind::Accuracy ? "acc " + sci(s.setting, 0) : "h " + sci(s.setting, 0) + " s";
}

/// Shared record of "too slow" points for --cap-skips-higher-modes.
struct SlowBook {
    std::mutex m;
    std::vector<RunSpec> slow;
    /// The too-slow point that makes `s` skippable, if any.
    bool find(const RunSpec& s, RunSpec& hit) {
        std::lock_guard<std::mutex> lock(m);
        for (const RunSpec& t : slow)
            if (t.integrator == s.integrator && t.kind == s.kind && t.axialModes < s.axialModes && s.setting <= t.setting) {
                hit = t;
                return true;
            }
        return false;
    }
    void add(const RunSpec& s) {
        std::lock_guard<std::mutex> lock(m);
        slow.push_back(s);
    }
};

std::vector<std::string> splitCsvLine(const std::string& line) {
    std::vector<std::string> fields(1);
    bool quoted = false;
    for (size_t i = 0; i < line.size(); ++i) {
        const char c = line[i];
        if (quoted) {
            if (c == '"' && i + 1 < line.size() && line[i + 1] == '"') {
                fields.back() += '"';
                ++i;
            } else if (c == '"') {
                quoted = false;
            } else {
                fields.back() += c;
            }
        } else if (c == '"') {
            quoted = true;
        } else if (c == ',') {
            fields.emplace_back();
        } else {
            fields.back() += c;
        }
    }
    return fields;
}

/// --resume: marks the points recorded in DIR/results.csv as done, with their recorded results
/// (the median wall stands for each of its runs). Returns how many points were taken over.
int loadRecordedPoints(const Options& o, std::vector<Point>& points) {
    std::ifstream f(fs::path(o.outDir) / "results.csv");
    if (!f) return 0;
    std::string line;
    std::getline(f, line);  // header
    int taken = 0;
    auto toD = [](const std::string& s) { return s.empty() ? 0.0 : std::stod(s); };
    auto toL = [](const std::string& s) { return s.empty() ? 0L : std::stol(s); };
    while (std::getline(f, line)) {
        const std::vector<std::string> c = splitCsvLine(line);
        if (c.size() != 15) throw std::runtime_error("results.csv: malformed line: " + line);
        for (Point& p : points) {
            const double setting = std::stod(c[3]);
            if (p.done || p.spec.integrator != c[0] || p.spec.axialModes != std::stoi(c[1]) || kindName(p.spec.kind) != c[2] ||
                std::abs(p.spec.setting - setting) > 1e-9 * p.spec.setting)
                continue;
            RunResult& r = p.result;
            r.status = c[4];
            r.reason = c[5];
            r.posErr = toD(c[6]);
            r.forceErr = toD(c[7]);
            r.wall = toD(c[8]);
            p.walls.assign(static_cast<size_t>(toL(c[9])), r.wall);
            p.wallNote = c[10];
            r.rhs = toL(c[11]);
            r.steps = toL(c[12]);
            r.tReached = toD(c[13]);
            r.errorControl = c[14] == "yes";
            p.done = true;
            ++taken;
            break;
        }
    }
    return taken;
}

void measurePoint(const Options& o, Point& p, const Trajectory& ref) {
    RunResult first = runOnce(o, p.spec, &ref, o.cap, false);
    p.walls.push_back(first.wall);
    if (first.status == "ok") {
        if (first.wall > o.repeatBelow) {
            if (o.repeats > 1) p.wallNote = "single run (> " + num(o.repeatBelow, 4) + " s)";
        } else {
            for (int k = 1; k < o.repeats; ++k) {
                RunResult again = runOnce(o, p.spec, &ref, o.cap, false);
                if (again.status != "ok") {  // e.g. the cap hit on a loaded machine: keep what we have
                    p.wallNote = "repeat " + std::to_string(k + 1) + " " + again.status + ": " + again.reason;
                    break;
                }
                p.walls.push_back(again.wall);
            }
        }
        first.wall = median(p.walls);
    }
    p.result = first;
    p.done = true;
}

std::string csvField(const std::string& s) {
    if (s.find_first_of(",\"") == std::string::npos) return s;
    std::string q = "\"";
    for (char c : s) q += c == '"' ? std::string("\"\"") : std::string(1, c);
    return q + "\"";
}

bool hasNumbers(const Point& p) { return p.done && p.result.status == "ok"; }

void writeResultsCsv(const Options& o, const std::vector<Point>& points) {
    const fs::path path = fs::path(o.outDir) / "results.csv";
    std::ofstream f(path.string() + ".tmp");
    f << "integrator,axial_modes,kind,setting,status,reason,position_error_m,force_error_N,wall_s,wall_runs,wall_note,"
         "rhs_evaluations,steps,t_reached_s,error_control\n";
    for (const Point& p : points) {
        if (!p.done) continue;
        const RunResult& r = p.result;
        const bool ran = r.status != "skipped";
        f << p.spec.integrator << ',' << p.spec.axialModes << ',' << kindName(p.spec.kind) << ',' << num(p.spec.setting, 6)
          << ',' << r.status << ',' << csvField(r.reason) << ',' << (hasNumbers(p) ? num(r.posErr, 6) : "") << ','
          << (hasNumbers(p) ? num(r.forceErr, 6) : "") << ',' << (ran ? num(r.wall, 6) : "") << ','
          << (ran ? std::to_string(p.walls.size()) : "") << ',' << csvField(p.wallNote) << ','
          << (ran ? std::to_string(r.rhs) : "") << ',' << (ran ? std::to_string(r.steps) : "") << ','
          << (ran ? num(r.tReached, 8) : "") << ',' << (ran ? (r.errorControl ? "yes" : "no") : "") << '\n';
    }
    f.close();
    fs::rename(path.string() + ".tmp", path);
}

void writeReferenceCheck(const Options& o, const std::vector<Reference>& refs, const std::vector<Point>& points) {
    std::ofstream f(fs::path(o.outDir) / "reference_check.txt");
    f << "Reference trajectories of the work-precision study (bench-work-precision)\n"
      << "Integrator " << o.referenceIntegrator << ", t_end " << o.tEnd << " s, reports every " << o.reportInterval
      << " s, n_t = " << o.transverseModes << ", vx0 = " << o.vx0 << " m/s, vy0 = " << o.vy0 << " m/s.\n"
      << "Check: the same run at " << o.referenceCheckFactor
      << " x the reference accuracy; max over the reports of the differences.\n\n";
    for (const Reference& r : refs) {
        double minPos = INFINITY, minForce = INFINITY;
        for (const Point& p : points)
            if (p.spec.axialModes == r.axialModes && hasNumbers(p)) {
                minPos = std::min(minPos, p.result.posErr);
                minForce = std::min(minForce, p.result.forceErr);
            }
        f << "n_a = " << r.axialModes << (r.fromCache ? " (loaded from cache)" : "") << "\n"
          << "  reference accuracy " << sci(r.accuracy, 1) << ": " << r.stepsMain << " steps, " << r.rhsMain
          << " rhs evaluations, " << num(r.wallMain, 4) << " s wall\n"
          << "  check accuracy     " << sci(r.checkAccuracy, 1) << ": " << r.stepsCheck << " steps, " << r.rhsCheck
          << " rhs evaluations, " << num(r.wallCheck, 4) << " s wall\n"
          << "  max |x_ref - x_check| = " << sci(r.maxPosDiff) << " m\n"
          << "  max |P_ref - P_check| = " << sci(r.maxForceDiff) << " N\n";
        const Floors fl = floorsOf(r);
        f << "  reference floor (" << kFloorFactor << " x the check difference): position " << sci(fl.position, 1)
          << " m, force " << sci(fl.force, 1) << " N; smaller errors are reported as below the floor\n";
        if (std::isfinite(minPos)) {
            double minPosResolved = INFINITY, minForceResolved = INFINITY;
            int belowPos = 0, belowForce = 0;
            for (const Point& p : points)
                if (p.spec.axialModes == r.axialModes && hasNumbers(p)) {
                    if (p.result.posErr >= fl.position) minPosResolved = std::min(minPosResolved, p.result.posErr);
                    else ++belowPos;
                    if (p.result.forceErr >= fl.force) minForceResolved = std::min(minForceResolved, p.result.forceErr);
                    else ++belowForce;
                }
            f << "  smallest errors reported as numbers: position " << sci(minPosResolved) << " m (check difference / error = "
              << sci(r.maxPosDiff / minPosResolved, 1) << "), force " << sci(minForceResolved)
              << " N (check difference / error = " << sci(r.maxForceDiff / minForceResolved, 1) << ")\n"
              << "  points below the floor: " << belowPos << " (position), " << belowForce
              << " (force); raw smallest measured differences: position " << sci(minPos) << " m, force " << sci(minForce)
              << " N (results.csv keeps the raw values)\n";
        }
        for (const std::string& note : r.notes) f << "  note: " << note << "\n";
        f << "\n";
    }
}

void writeTable(const Options& o, const std::vector<Point>& points, const std::vector<Reference>& refs,
                const std::map<std::string, std::pair<std::string, bool>>& methods) {
    std::map<int, Floors> floors;
    for (const Reference& r : refs) floors[r.axialModes] = floorsOf(r);
    std::ofstream f(fs::path(o.outDir) / "table.md");
    f << "# Work-precision study: the paper's pendulum\n\n"
      << "Axial modes " << (o.axialDynamics == SimbodyReeving::AxialDynamics::Dynamic ? "dynamic (states)" : "quasi-static (condensed)")
      << ", t_end " << o.tEnd << " s, reports every " << o.reportInterval << " s, n_t = " << o.transverseModes
      << ", vx0 = " << o.vx0 << " m/s. Errors: max over the reports of |x - x_ref| (payload centre, Euclidean) "
      << "and |P - P_ref| (payload-end axial force). Wall: median of up to " << o.repeats
      << " runs of the integration alone (runs slower than " << o.repeatBelow << " s: one run); cap " << o.cap
      << " s per run" << (o.projectCap > 0 ? " (also stopped when the wall projected to t_end exceeds " + num(o.projectCap, 3) + " x cap)" : "")
      << (o.capSkips ? std::string("; after a too-slow point the tighter settings of that integrator are skipped") +
                           (o.capSkipsHigherModes ? " at that n_a and at every larger n_a" : " at that n_a")
                     : std::string("; every setting measured, also after a too-slow one"))
      << ". rhs = InterpolatingTimeStepper::getNumRealizations() "
      << "(realizations through Stage::Acceleration, reports not counted). Errors smaller than " << kFloorFactor
      << " x the reference's own change at half its accuracy are shown as \"< floor\" (see reference_check.txt).\n\n";
    f << "## Integrators\n\n| name | Simbody method | error control (methodHasErrorControl) | swept over |\n|---|---|---|---|\n";
    for (const std::string& n : o.integrators) {
        const auto it = methods.find(n);
        const bool fixed = std::find(o.fixedStepIntegrators.begin(), o.fixedStepIntegrators.end(), n) !=
                           o.fixedStepIntegrators.end();
        f << "| " << n << " | " << (it != methods.end() ? it->second.first : "?") << " | "
          << (it != methods.end() ? (it->second.second ? "yes" : "no") : "?") << " | accuracies"
          << (fixed ? " and fixed steps" : "") << " |\n";
    }
    for (int na : o.axialModes) {
        const Floors fl = floors[na];
        f << "\n## n_a = " << na << "\n\n"
          << "Reference floor: position " << sci(fl.position, 1) << " m, force " << sci(fl.force, 1) << " N.\n\n"
          << "| integrator | setting | status | position error [m] | force error [N] | wall [s] | runs | rhs "
             "evaluations | steps | t reached [s] | note |\n|---|---|---|---|---|---|---|---|---|---|---|\n";
        for (const Point& p : points) {
            if (p.spec.axialModes != na || !p.done) continue;
            const RunResult& r = p.result;
            const bool ran = r.status != "skipped";
            std::string note = r.reason;
            if (!p.wallNote.empty()) note += (note.empty() ? "" : "; ") + p.wallNote;
            for (char& c : note)
                if (c == '|') c = '/';
            f << "| " << p.spec.integrator << " | " << settingText(p.spec) << " | " << r.status << " | "
              << (hasNumbers(p) ? errorText(r.posErr, fl.position) : "") << " | "
              << (hasNumbers(p) ? errorText(r.forceErr, fl.force) : "") << " | "
              << (ran ? num(r.wall, 3) : "") << " | " << (ran ? std::to_string(p.walls.size()) : "") << " | "
              << (ran ? std::to_string(r.rhs) : "") << " | " << (ran ? std::to_string(r.steps) : "") << " | "
              << (ran ? num(r.tReached, 6) : "") << " | " << note << " |\n";
        }
    }
    // Fastest point per error target: position targets 1e-3, 1e-6, 1e-9 m; the force
    // errors live on another scale (the axial modes' integration noise is newtons), so their targets are
    // 10, 1, 0.1 and 0.01 N.
    auto best = [&](int na, double target, bool position) {
        const double floor = position ? floors[na].position : floors[na].force;
        if (target < floor) return "not verifiable (reference floor " + sci(floor, 1) + ")";
        const Point* b = nullptr;
        for (const Point& p : points) {
            if (p.spec.axialModes != na || !hasNumbers(p)) continue;
            const double e = position ? p.result.posErr : p.result.forceErr;
            if (e <= target && (!b || p.result.wall < b->result.wall)) b = &p;
        }
        if (!b) return std::string("none reached");
        return b->spec.integrator + " (" + settingText(b->spec) + ", " + num(b->result.wall, 3) + " s, error " +
               errorText(position ? b->result.posErr : b->result.forceErr, floor) + ")";
    };
    f << "\n## Fastest integrator per error target (lowest median wall among the points reaching it)\n\n"
      << "Payload position error:\n\n| n_a | 1e-3 m | 1e-6 m | 1e-9 m |\n|---|---|---|---|\n";
    for (int na : o.axialModes)
        f << "| " << na << " | " << best(na, 1e-3, true) << " | " << best(na, 1e-6, true) << " | " << best(na, 1e-9, true)
          << " |\n";
    f << "\nPayload-end axial force error:\n\n| n_a | 10 N | 1 N | 0.1 N | 0.01 N |\n|---|---|---|---|---|\n";
    for (int na : o.axialModes)
        f << "| " << na << " | " << best(na, 10, false) << " | " << best(na, 1, false) << " | " << best(na, 0.1, false)
          << " | " << best(na, 0.01, false) << " |\n";
}

bool makePlots(const Options& o, const std::vector<Point>& points, const std::vector<Reference>& refs) {
    if (std::system("command -v gnuplot > /dev/null 2>&1") != 0) {
        std::cerr << "bench-work-precision: gnuplot not found, figures skipped (apt-get install gnuplot-nox)\n";
        return false;
    }
    const fs::path dir(o.outDir);
    std::ofstream gp(dir / "plots.gp");
    gp << "set terminal pngcairo size 1700,620 font 'DejaVu Sans,11'\nset grid\nset logscale xy\n"
       << "set format x '10^{%L}'\nset format y '10^{%L}'\nset key outside right top font ',9' box\n";
    bool any = false;
    for (int na : o.axialModes) {
        // One data block per series (integrator x kind), ok points only, loosest setting first.
        struct Series {
            std::string title;
            std::vector<const Point*> pts;
        };
        std::vector<Series> series;
        for (const std::string& integ : o.integrators)
            for (Kind kind : {Kind::Accuracy, Kind::FixedStep}) {
                Series s{integ + (kind == Kind::FixedStep ? " (fixed h)" : ""), {}};
                for (const Point& p : points)
                    if (p.spec.axialModes == na && p.spec.integrator == integ && p.spec.kind == kind && hasNumbers(p) &&
                        p.result.wall > 0 && p.result.posErr > 0 && p.result.forceErr > 0)
                        s.pts.push_back(&p);
                if (s.pts.empty()) continue;
                std::sort(s.pts.begin(), s.pts.end(),
                          [](const Point* a, const Point* b) { return a->spec.setting > b->spec.setting; });
                series.push_back(std::move(s));
            }
        const std::string data = "work_precision_na" + std::to_string(na) + ".dat";
        std::ofstream d(dir / data);
        d << "# wall_s position_error_m force_error_N setting; one block per series\n" << std::setprecision(9);
        for (const Series& s : series) {
            d << "# " << s.title << "\n";
            for (const Point* p : s.pts)
                d << p->result.wall << ' ' << p->result.posErr << ' ' << p->result.forceErr << ' ' << p->spec.setting << '\n';
            d << "\n\n";
        }
        if (series.empty()) {
            std::cerr << "bench-work-precision: n_a = " << na << ": no successful point, no plot\n";
            continue;
        }
        any = true;
        gp << "set output 'work_precision_na" << na << ".png'\nset multiplot layout 1,2 title 'Work-precision, pendulum, n_a = "
           << na << ", " << o.tEnd << " s'\n";
        Floors fl;
        for (const Reference& r : refs)
            if (r.axialModes == na) fl = floorsOf(r);
        for (int panel = 0; panel < 2; ++panel) {
            // Below the dashed line the reference cannot resolve the error (see kFloorFactor).
            const double floor = panel == 0 ? fl.position : fl.force;
            gp << "set xlabel 'wall time of the integration [s]'\nset ylabel '"
               << (panel == 0 ? "max payload position error [m]" : "max payload-end axial force error [N]") << "'\nplot ";
            for (size_t i = 0; i < series.size(); ++i)
                gp << (i ? ", " : "") << "'" << data << "' index " << i << " using 1:" << (panel == 0 ? 2 : 3)
                   << " with linespoints lw 2 pt " << (i % 13) + 1 << " title '" << series[i].title << "'";
            if (floor > 0) gp << ", " << num(floor, 6) << " with lines dt 2 lw 2 lc rgb 'black' title 'reference floor'";
            gp << "\n";
        }
        gp << "unset multiplot\n";
    }
    gp.close();
    if (!any) return false;
    const std::string cmd = "cd '" + dir.string() + "' && gnuplot plots.gp";
    if (std::system(cmd.c_str()) != 0) {
        std::cerr << "bench-work-precision: gnuplot failed; see " << (dir / "plots.gp").string() << "\n";
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
        std::cerr << "bench-work-precision: " << e.what() << "\nTry 'bench-work-precision --help'.\n";
        return 2;
    }
    if (o.help) {
        std::cout << usage();
        return 0;
    }
    const auto start = Clock::now();
    try {
        fs::create_directories(o.outDir);
    } catch (const std::exception& e) {
        std::cerr << "bench-work-precision: cannot create " << o.outDir << ": " << e.what() << "\n";
        return 1;
    }

    // What each integrator is, as Simbody reports it.
    std::map<std::string, std::pair<std::string, bool>> methods;
    {
        SimbodyReeving::SpanOptions spans;
        SimbodyReeving::PendulumScene scene(SimbodyReeving::PendulumParameters{}, spans);
        scene.system().realizeTopology();
        for (const std::string& n : SimbodyReeving::integratorNames()) {
            auto integ = SimbodyReeving::makeIntegrator(n, scene.system());
            methods[n] = {integ->getMethodName(), integ->methodHasErrorControl()};
            say(o, "integrator " + n + ": Simbody method " + integ->getMethodName() + ", order " +
                       std::to_string(integ->getMethodMinOrder()) + ".." + std::to_string(integ->getMethodMaxOrder()) +
                       ", error control " + (integ->methodHasErrorControl() ? "yes" : "no") + "\n");
        }
    }

    // References first (they are the expensive part, and cached).
    std::vector<Reference> refs;
    try {
        for (int na : o.axialModes) refs.push_back(makeReference(o, na));
    } catch (const std::exception& e) {
        std::cerr << "bench-work-precision: reference failed: " << e.what() << "\n";
        return 1;
    }
    if (o.referenceOnly) {
        writeReferenceCheck(o, refs, {});
        std::printf("bench-work-precision: references done in %.1f s; see %s\n", secondsSince(start),
                    (fs::path(o.outDir) / "reference_check.txt").string().c_str());
        return 0;
    }

    // Points, grouped in chains (integrator x kind x n_a, loosest setting first); a chain stops
    // measuring once a point is too slow. Chains ordered by n_a, so smaller n_a run first.
    std::vector<Point> points;
    std::vector<std::vector<size_t>> chains;
    for (int na : o.axialModes)
        for (const std::string& integ : o.integrators)
            for (Kind kind : {Kind::Accuracy, Kind::FixedStep}) {
                if (kind == Kind::FixedStep && std::find(o.fixedStepIntegrators.begin(), o.fixedStepIntegrators.end(),
                                                         integ) == o.fixedStepIntegrators.end())
                    continue;
                std::vector<size_t> chain;
                for (double v : kind == Kind::Accuracy ? o.accuracies : o.steps) {
                    chain.push_back(points.size());
                    points.push_back({{integ, na, kind, v}, {}, {}, {}, false});
                }
                chains.push_back(chain);
            }
    std::map<int, const Trajectory*> refOf;
    for (const Reference& r : refs) refOf[r.axialModes] = &r.main;

    SlowBook slowBook;
    if (o.resume) {
        const int taken = loadRecordedPoints(o, points);
        for (const Point& p : points)
            if (p.done && p.result.status == "too slow") slowBook.add(p.spec);
        say(o, "resume: " + std::to_string(taken) + " points taken from " + (fs::path(o.outDir) / "results.csv").string() +
                   "\n");
    }
    std::atomic<size_t> nextChain{0};
    std::atomic<int> finished{0};
    std::mutex resultsMutex;
    const int total = static_cast<int>(points.size());
    auto worker = [&]() {
        for (size_t c = nextChain++; c < chains.size(); c = nextChain++) {
            std::string skipReason;
            for (size_t idx : chains[c]) {
                Point& p = points[idx];
                if (p.done) {  // recorded (--resume)
                    if (p.result.status == "too slow" && o.capSkips) skipReason = "too slow at " + settingText(p.spec);
                    ++finished;
                    continue;
                }
                RunSpec hit;
                if (skipReason.empty() && o.capSkipsHigherModes && slowBook.find(p.spec, hit))
                    skipReason = "too slow at n_a = " + std::to_string(hit.axialModes) + ", " + settingText(hit);
                if (!skipReason.empty()) {
                    p.result.status = "skipped";
                    p.result.reason = skipReason;
                    p.done = true;
                } else {
                    try {
                        measurePoint(o, p, *refOf.at(p.spec.axialModes));
                    } catch (const std::exception& e) {  // scene construction etc.; never abort the sweep
                        p.result.status = "failed";
                        p.result.reason = e.what();
                        p.done = true;
                    }
                    if (p.result.status == "too slow") {
                        if (o.capSkips) skipReason = "too slow at " + settingText(p.spec);
                        slowBook.add(p.spec);
                    }
                }
                const int k = ++finished;
                {
                    std::lock_guard<std::mutex> lock(resultsMutex);
                    writeResultsCsv(o, points);
                }
                const RunResult& r = p.result;
                std::ostringstream line;
                line << "[" << k << "/" << total << "] " << p.spec.integrator << " n_a=" << p.spec.axialModes << " "
                     << settingText(p.spec) << ": " << r.status;
                if (r.status == "ok")
                    line << "  pos " << sci(r.posErr) << " m  force " << sci(r.forceErr) << " N  wall "
                         << num(r.wall, 3) << " s (" << p.walls.size() << " runs)  rhs " << r.rhs << "  steps " << r.steps;
                else
                    line << " (" << r.reason << ")" << (r.status != "skipped" ? "  wall " + num(r.wall, 3) + " s" : "");
                say(o, line.str() + "\n");
            }
        }
    };
    const int jobs = std::min<int>(o.jobs, static_cast<int>(chains.size()));
    std::vector<std::thread> threads;
    for (int j = 1; j < jobs; ++j) threads.emplace_back(worker);
    worker();
    for (auto& t : threads) t.join();

    writeResultsCsv(o, points);
    writeReferenceCheck(o, refs, points);
    writeTable(o, points, refs, methods);
    if (o.plots) makePlots(o, points, refs);
    int ok = 0;
    for (const Point& p : points) ok += hasNumbers(p) ? 1 : 0;
    std::printf("bench-work-precision: %d points (%d ok), wall %.1f s, outputs in %s\n", total, ok, secondsSince(start),
                o.outDir.c_str());
    return 0;
}
