// Numerical-stability stress suite (ctest label `stress`, excluded from ./scripts/test.sh; run it with
// `ctest --test-dir build -L stress --output-on-failure`, results in docs/stability.md).
//
// The paper's pendulum (PendulumScene, Table 1) pushed one parameter at a time: stiffer rope, a
// short horizontal span, fast pushes, a long run, many modes, a heavy rope, a light payload. Every
// case runs with RK-Merson and with CPodes at accuracy 1e-6, reporting every 0.1 s. A run passes if
// every reported state is finite, the mechanical energy drift stays within 100 times the drift
// recorded for that run in docs/stability.md, at most 1e-3 of the initial kinetic energy (the system
// is conservative), and the sheave tension-equality residual stays <= 1e-9 of the
// payload weight. Otherwise it fails with a message naming the case, the integrator and the cause:
// an exception from the simulation (Simbody's step-size underflow, the sheave Newton solver's
// std::runtime_error, std::domain_error, ...), an integrator that ended the simulation, non-finite
// numbers, drift, constraint residual, or the wall-clock cap (600 s of integration per run).
//
// Each run prints one line: case, integrator, steps, wall s, drift/KE0, constraint/weight, status,
// followed by diagnostics (minimum axial force in the rope, highest payload point relative to the
// sheave, simulated time reached). The status carries WARNINGs, not failures, when the run left the
// model's physical validity while staying numerically sound: the rope in compression (a rope cannot
// push; the spans treat compression elastically) or the attachment above the sheave.
#include "SimbodyReeving/simbody/Integrators.h"
#include "SimbodyReeving/scenes/PendulumScene.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <exception>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

using SimTK::Stage;
using SimTK::State;
using SimTK::Vec3;
using namespace SimbodyReeving;

namespace {

constexpr double kAccuracy = 1e-6;
constexpr double kReportInterval = 0.1;          // [s]
constexpr double kWallCapSeconds = 600.0;        // integration wall time per run
constexpr double kMaxRelativeDrift = 1e-3;       // max |E - E0| / KE0, the ceiling of every case's limit
constexpr double kMaxRelativeConstraint = 1e-9;  // max |F_a - F_b| / (M g)
constexpr int kStepsBetweenWallChecks = 200;     // internal steps per Integrator::stepTo call at most

/// The paper's Table 1 pendulum with its linear axial law (the stress cases were measured with it;
/// the tension-only law, the library's default, is its own case below).
PendulumParameters paperParameters() {
    PendulumParameters p;
    p.tensionOnly = false;
    return p;
}

struct StressCase {
    std::string name;         // gtest-safe identifier
    std::string description;  // what is changed from the base scene
    PendulumParameters params = paperParameters();
    int na = 3;
    int nt = 1;
    double vx0 = 1.0;   // [m/s]
    double tEnd = 20.0; // [s]
    AxialDynamics axialDynamics = AxialDynamics::Dynamic;
};

std::vector<StressCase> stressCases() {
    std::vector<StressCase> c;
    auto add = [&c](const std::string& name, const std::string& description) -> StressCase& {
        c.push_back(StressCase{});
        c.back().name = name;
        c.back().description = description;
        return c.back();
    };
    add("Baseline", "Table 1, n_a=3, n_t=1, vx0=1 m/s, 20 s (reference)");
    add("EAx10", "EA x10 (165e6 N)").params.EA *= 10.0;
    add("EAx100", "EA x100 (1.65e9 N)").params.EA *= 100.0;
    add("ShortSpan", "horizontal span a = 0.2 m").params.a = 0.2;
    add("Push5", "vx0 = 5 m/s").vx0 = 5.0;
    add("Push20", "vx0 = 20 m/s").vx0 = 20.0;
    add("Long200s", "t_end = 200 s (n_a = 3)").tEnd = 200.0;
    add("Na8", "n_a = 8 (n_t = 1)").na = 8;
    add("Nt4", "n_t = 4 (n_a = 3)").nt = 4;
    add("HeavyRope", "rhoA x100 (62.05 kg/m)").params.rhoA *= 100.0;
    {
        StressCase& light = add("LightPayload", "payload /100 (M = 10 kg, J = 0.36 kg m^2)");
        light.params.M = 10.0;
        light.params.J = 0.36;
    }
    // The over-the-top push with a tension-only rope: slack instead of compression.
    {
        StressCase& c20 = add("Push20TensionOnly", "vx0 = 20 m/s, tension-only rope");
        c20.vx0 = 20.0;
        c20.params.tensionOnly = true;
    }
    // The same scenes with quasi-static axial modes: a stiffer rope should cost no more.
    const size_t dynamicCases = c.size();
    for (size_t i = 0; i < dynamicCases; ++i) {
        StressCase q = c[i];
        q.name += "QS";
        q.description += ", quasi-static axial modes";
        q.axialDynamics = AxialDynamics::QuasiStatic;
        c.push_back(q);
    }
    return c;
}

struct StressRun {
    StressCase stressCase;
    std::string integrator;
};

/// The drift / KE0 each run was measured at (docs/stability.md; where a case was measured twice, the
/// larger figure): the Dynamic table at commit 80c4aec (EA x100 at cd59813; Baseline also at
/// cd59813: 1.6e-11 and 2.4e-8, CPodes' drift moved 3.4x with a round-off change), the QS table at
/// b83cc56, Push20TensionOnly at 814a40b and 26f4909. Returns {rk-merson, cpodes}.
std::pair<double, double> recordedDrift(const std::string& name) {
    static const struct {
        const char* name;
        double rkMerson, cpodes;
    } table[] = {
        {"Baseline", 1.7e-11, 8.1e-08},   {"EAx10", 1.5e-10, 4.3e-08},        {"EAx100", 1.2e-09, 1.9e-06},
        {"ShortSpan", 9.4e-10, 1.6e-08},  {"Push5", 1.7e-11, 3.1e-10},        {"Push20", 2.5e-07, 1.8e-06},
        {"Long200s", 2.7e-11, 1.1e-07},   {"Na8", 7.8e-11, 2.4e-08},          {"Nt4", 2.7e-11, 1.7e-08},
        {"HeavyRope", 4.3e-09, 1.9e-08},  {"LightPayload", 1.2e-09, 9.2e-08}, {"Push20TensionOnly", 6.9e-06, 3.1e-04},
        {"BaselineQS", 3.9e-08, 8.5e-08}, {"EAx10QS", 2.0e-07, 4.7e-07},      {"EAx100QS", 3.5e-08, 1.2e-07},
        {"ShortSpanQS", 2.1e-11, 1.9e-06}, {"Push5QS", 2.6e-08, 2.2e-07},     {"Push20QS", 3.9e-07, 1.5e-04},
        {"Long200sQS", 2.9e-07, 8.5e-08}, {"Na8QS", 2.8e-08, 9.8e-08},        {"Nt4QS", 8.0e-10, 9.4e-08},
        {"HeavyRopeQS", 3.0e-07, 1.1e-06}, {"LightPayloadQS", 4.7e-08, 8.6e-06},
        {"Push20TensionOnlyQS", 4.8e-07, 2.0e-05},
    };
    for (const auto& row : table)
        if (name == row.name) return {row.rkMerson, row.cpodes};
    throw std::logic_error("no recorded drift for stress case " + name);
}

/// A run's drift limit: 100 x its recorded drift (the margin covers round-off changes of the step
/// sequence, which moved the Baseline CPodes figure 3.4x), capped at kMaxRelativeDrift (never
/// looser than before). The cap binds for three CPodes runs, with smaller margins: Push20QS (1.5e-4,
/// 6.7x), Push20TensionOnly (3.1e-4, 3.2x) and Push20TensionOnlyQS (2.0e-5, 50x).
double driftLimit(const StressRun& run) {
    const auto recorded = recordedDrift(run.stressCase.name);
    const double measured = run.integrator == "cpodes" ? recorded.second : recorded.first;
    return std::min(kMaxRelativeDrift, 100.0 * measured);
}

// gtest prints this instead of the parameter's bytes.
void PrintTo(const StressRun& run, std::ostream* os) { *os << run.stressCase.name << " / " << run.integrator; }

struct Measurement {
    int steps = 0;
    double wallSeconds = 0;       // integration only
    double setupSeconds = 0;      // scene + static equilibrium
    double ke0 = 0;
    double weight = 0;
    double relDrift = 0;          // max |E - E0| / KE0 over reports
    double relConstraint = 0;     // max constraint error / weight over reports
    bool finite = true;
    double tReached = 0;          // simulated time of the last report
    double minAxialForce = std::numeric_limits<double>::infinity();  // over sampled rope points [N]
    double firstCompressionTime = -1;  // first report with a negative axial force [s], -1: none
    double maxPayloadHeight = -std::numeric_limits<double>::infinity();  // payload centre y [m], sheave at 0
    std::string failure;          // empty: ran to the end
};

std::string describe(double v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.3e", v);
    return buf;
}

// Smallest axial force over 5 equally spaced material points of each span.
double minAxialForce(const ReevingSubsystem& rv, const State& s) {
    double m = std::numeric_limits<double>::infinity();
    for (int span = 0; span < rv.getNumSpans(0); ++span) {
        const auto range = rv.getSpanMaterialRange(s, 0, span);
        for (int k = 0; k <= 4; ++k) {
            // Exact ends: range.first + (range.second - range.first) can round past range.second.
            const double sk = k == 4 ? range.second
                                     : std::min(range.second, range.first + (range.second - range.first) * k / 4.0);
            m = std::min(m, rv.getAxialForce(s, 0, span, sk));
        }
    }
    return m;
}

Measurement runCase(const StressRun& run) {
    Measurement r;
    const StressCase& c = run.stressCase;
    const auto setupStart = std::chrono::steady_clock::now();
    SpanOptions spans;
    spans.axialModes = c.na;
    spans.transverseModes = c.nt;
    spans.axialDynamics = c.axialDynamics;
    spans.velocityModel = VelocityModel::Simplified;  // not the default: the setting these bounds were measured with
    try {
        const PendulumScene scene(c.params, spans);
        const ReevingSubsystem& rv = scene.reeving();
        State s = scene.makeInitialState(c.vx0, 0.0);
        r.ke0 = scene.system().calcKineticEnergy(s) + rv.calcRopeKineticEnergy(s);
        r.weight = c.params.M * c.params.g;
        const double e0 = rv.calcMechanicalEnergy(s);
        r.setupSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - setupStart).count();

        auto integ = makeIntegrator(run.integrator, scene.system());
        integ->setAccuracy(kAccuracy);
        integ->setInternalStepLimit(kStepsBetweenWallChecks);
        integ->initialize(s);
        const auto start = std::chrono::steady_clock::now();
        auto wall = [&start] { return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(); };
        const int numReports = static_cast<int>(std::lround(c.tEnd / kReportInterval));
        const char* phase = "integrating";
        try {
            for (int n = 1; n <= numReports && r.failure.empty(); ++n) {
                const double tReport = n * kReportInterval;
                phase = "integrating";
                for (;;) {
                    const auto status = integ->stepTo(tReport);
                    if (status == SimTK::Integrator::ReachedReportTime) break;
                    if (status == SimTK::Integrator::EndOfSimulation) {
                        r.failure = "integrator ended the simulation at t = " + describe(integ->getTime()) +
                                    " s: " + SimTK::Integrator::getTerminationReasonString(integ->getTerminationReason());
                        break;
                    }
                    if (status != SimTK::Integrator::ReachedStepLimit && status != SimTK::Integrator::TimeHasAdvanced &&
                        status != SimTK::Integrator::StartOfContinuousInterval) {
                        r.failure = std::string("unexpected integrator status '") +
                                    SimTK::Integrator::getSuccessfulStepStatusString(status) + "' at t = " +
                                    describe(integ->getTime()) + " s";
                        break;
                    }
                    if (wall() > kWallCapSeconds) {
                        r.failure = "too slow: wall-clock cap of " + describe(kWallCapSeconds) +
                                    " s reached at simulated t = " + describe(integ->getTime()) + " s of " +
                                    describe(c.tEnd) + " s (" + std::to_string(integ->getNumStepsTaken()) + " steps)";
                        break;
                    }
                }
                if (!r.failure.empty()) break;
                phase = "evaluating the reported state";
                const State& st = integ->getState();
                scene.system().realize(st, Stage::Velocity);
                const double e = rv.calcMechanicalEnergy(st);
                const double ce = rv.getMaxConstraintError(st);
                const Vec3 x = scene.payloadPosition(st);
                r.tReached = st.getTime();
                if (!std::isfinite(e) || !std::isfinite(ce) || !x.isFinite()) {
                    r.finite = false;
                    r.failure = "non-finite numbers at t = " + describe(st.getTime()) + " s (energy " + describe(e) +
                                ", constraint " + describe(ce) + ", payload x " + describe(x[0]) + ")";
                    break;
                }
                r.relDrift = std::max(r.relDrift, std::abs(e - e0) / r.ke0);
                r.relConstraint = std::max(r.relConstraint, ce / r.weight);
                const double fmin = minAxialForce(rv, st);
                if (fmin < 0 && r.firstCompressionTime < 0) r.firstCompressionTime = st.getTime();
                r.minAxialForce = std::min(r.minAxialForce, fmin);
                r.maxPayloadHeight = std::max(r.maxPayloadHeight, x[1]);
                if (r.failure.empty() && wall() > kWallCapSeconds && n < numReports)
                    r.failure = "too slow: wall-clock cap of " + describe(kWallCapSeconds) +
                                " s reached at simulated t = " + describe(st.getTime()) + " s of " + describe(c.tEnd) +
                                " s";
            }
        } catch (const std::exception& e) {
            r.failure = std::string("exception while ") + phase + " at t = " + describe(integ->getTime()) +
                        " s: " + e.what();
        }
        r.wallSeconds = wall();
        r.steps = integ->getNumStepsTaken();
    } catch (const std::exception& e) {
        r.setupSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - setupStart).count();
        r.failure = std::string("exception while building the scene / static equilibrium: ") + e.what();
    }
    return r;
}

class StressSuite : public ::testing::TestWithParam<StressRun> {};

TEST_P(StressSuite, RunsStably) {
    const StressRun& run = GetParam();
    const StressCase& c = run.stressCase;
    const std::string who = "case " + c.name + " (" + c.description + "), integrator " + run.integrator;
    const Measurement r = runCase(run);

    std::vector<std::string> causes;
    if (!r.failure.empty()) causes.push_back(r.failure);
    if (r.finite) {
        if (r.relDrift > driftLimit(run))
            causes.push_back("energy drift " + describe(r.relDrift) + " of KE0 > " + describe(driftLimit(run)) +
                             " (100 x the drift recorded in docs/stability.md, at most " +
                             describe(kMaxRelativeDrift) + ")");
        if (r.relConstraint > kMaxRelativeConstraint)
            causes.push_back("constraint residual " + describe(r.relConstraint) + " of the payload weight > " +
                             describe(kMaxRelativeConstraint));
    }
    std::string status = "PASS";
    if (!causes.empty()) {
        status = "FAIL:";
        for (const auto& cause : causes) status += " " + cause + ";";
    }
    // Not pass criteria (the suite checks numerical stability), but the model's validity: a rope
    // cannot push, and the spans treat compression elastically like a rod.
    if (r.firstCompressionTime >= 0)
        status += " WARNING: rope in compression from t = " + describe(r.firstCompressionTime) +
                  " s (min axial force " + describe(r.minAxialForce) + " N);";
    if (r.maxPayloadHeight + c.params.d > 0)
        status += " WARNING: rope attachment rose above the sheave (vertical span's chord pointed up);";
    std::printf("[ stress ] %-12s | %-9s | steps %9d | wall %8.1f s | drift/KE0 %.3e | constraint/weight %.3e | %s\n",
                c.name.c_str(), run.integrator.c_str(), r.steps, r.wallSeconds, r.relDrift, r.relConstraint,
                status.c_str());
    std::printf("[ stress ]    %s: KE0 %.4g J, weight %.4g N, t reached %.1f s of %.1f s, setup %.2f s, "
                "min axial force %.4g N, max payload centre height %.3f m (sheave at 0)\n",
                c.description.c_str(), r.ke0, r.weight, r.tReached, c.tEnd, r.setupSeconds, r.minAxialForce,
                r.maxPayloadHeight);
    std::fflush(stdout);

    for (const auto& cause : causes) ADD_FAILURE() << who << ": " << cause;
}

std::vector<StressRun> allRuns() {
    std::vector<StressRun> runs;
    for (const auto& c : stressCases())
        for (const char* integrator : {"rk-merson", "cpodes"}) runs.push_back({c, integrator});
    return runs;
}

std::string runName(const ::testing::TestParamInfo<StressRun>& info) {
    std::string integ = info.param.integrator;
    integ.erase(std::remove(integ.begin(), integ.end(), '-'), integ.end());
    return info.param.stressCase.name + "_" + integ;
}

INSTANTIATE_TEST_SUITE_P(Pendulum, StressSuite, ::testing::ValuesIn(allRuns()), runName);

}  // namespace

// One hour of simulated time: the conservative pendulum, n_a = 1 (quasi-static axial
// mode, the demo default; the Dynamic model would need about 5 M steps), RK-Merson at 1e-8.
// Energy drift and sheave residual stay bounded; both are printed every simulated 6 minutes so
// their growth can be read (docs/stability.md).
TEST(LongRun, OneHourConservativePendulum) {
    SpanOptions o;
    o.axialModes = 1;
    o.transverseModes = 1;
    o.axialDynamics = AxialDynamics::QuasiStatic;
    o.velocityModel = VelocityModel::Simplified;  // not the default: the setting these bounds were measured with
    const PendulumScene scene(PendulumParameters{}, o);
    const ReevingSubsystem& rv = scene.reeving();
    const State s0 = scene.makeInitialState(1.0, 0.0);
    scene.system().realize(s0, Stage::Velocity);
    const double e0 = rv.calcMechanicalEnergy(s0);
    const double ke0 = scene.system().calcKineticEnergy(s0) + rv.calcRopeKineticEnergy(s0);
    const double weight = (PendulumParameters{}.M) * PendulumParameters{}.g;
    auto integ = makeIntegrator("rk-merson", scene.system());
    integ->setAccuracy(1e-8);
    SimTK::TimeStepper ts(scene.system(), *integ);
    ts.initialize(s0);
    double drift = 0, residual = 0;
    const auto start = std::chrono::steady_clock::now();
    for (int k = 1; k <= 360; ++k) {  // reports every 10 s
        ts.stepTo(10.0 * k);
        const State& s = integ->getState();
        scene.system().realize(s, Stage::Velocity);
        const double e = rv.calcMechanicalEnergy(s);
        ASSERT_TRUE(std::isfinite(e)) << "t = " << s.getTime();
        drift = std::max(drift, std::abs(e - e0));
        residual = std::max(residual, rv.getMaxConstraintError(s));
        if (k % 36 == 0)
            std::printf("[ long ] t = %6.0f s  max drift / KE0 %.3e  max sheave residual / weight %.3e  steps %d  "
                        "wall %.0f s\n",
                        s.getTime(), drift / ke0, residual / weight, integ->getNumStepsTaken(),
                        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
    }
    // docs/stability.md (tension-only default): drift 3.7e-08 of KE0 at 3 600 s, margin
    // 27x; residual 1.1e-12 of the weight (round-off floor), margin 91x.
    EXPECT_LT(drift, 1e-6 * ke0);
    EXPECT_LT(residual, 1e-10 * weight);
}
