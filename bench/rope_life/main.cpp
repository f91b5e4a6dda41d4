// What RopeLifeMonitor adds to a crane run: the gantry crane's default cycle (reeving-crane's
// defaults: 4 falls, wrapped sheaves, n_a = 1 quasi-static, RK-Merson at 1e-6, a report every
// 0.02 s, 36 s) integrated with and without the monitor recording every report, in alternating
// pairs in one process, so that the machine's load affects both alike. Prints each pair's walls and
// ratio, then the medians: the monitor's share is (with / without - 1).
//
// usage: bench-rope-life [PAIRS]            (default 7)
//        bench-rope-life --once with|without  one run, for instruction counts (bench/rope_life_cost.sh)
#include <SimbodyReeving/scenes/CraneScene.h>
#include <SimbodyReeving/simbody/Integrators.h>
#include <SimbodyReeving/simbody/InterpolatingTimeStepper.h>
#include <SimbodyReeving/simbody/RopeLifeMonitor.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

using namespace SimbodyReeving;

namespace {

struct Run {
    double wall = 0;  // [s], the integration and the monitor's records
    long steps = 0;
    int events = 0;   // the monitor's bend events (0 without it)
};

Run runCycle(bool withMonitor) {
    SpanOptions spans;
    spans.axialModes = 1;
    spans.transverseModes = 1;
    CraneScene scene(CraneParameters{}, CraneCycle::liftTraverseLower(5.0, 10.0), spans);
    RopeLifeOptions o;
    o.ropeDiameter = 0.02;
    o.reverseBendFactor = 1.0;
    RopeLifeMonitor life(scene.reeving(), 0, o);
    SimTK::State s0 = scene.makeInitialState();
    auto integ = makeIntegrator("rk-merson", scene.system());
    integ->setAccuracy(1e-6);
    InterpolatingTimeStepper ts(scene.system(), *integ);
    ts.initialize(s0);
    const double interval = 0.02, tEnd = 36.0;
    const int reports = static_cast<int>(std::floor(tEnd / interval + 1e-9));
    const auto start = std::chrono::steady_clock::now();
    if (withMonitor) life.record(ts.getState());
    for (int n = 1; n <= reports; ++n) {
        ts.stepTo(n * interval);
        if (withMonitor) life.record(ts.getState());
    }
    Run r;
    r.wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    r.steps = integ->getNumStepsTaken();
    r.events = static_cast<int>(life.events().size());
    return r;
}

double median(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    const size_t n = v.size();
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

}  // namespace

int main(int argc, char** argv) {
    if (argc == 3 && std::string(argv[1]) == "--once") {
        const std::string which = argv[2];
        if (which != "with" && which != "without") {
            std::fprintf(stderr, "usage: bench-rope-life --once with|without\n");
            return 2;
        }
        const Run r = runCycle(which == "with");
        std::printf("%s: %ld steps, %d bend events, %.4f s\n", which.c_str(), r.steps, r.events, r.wall);
        return 0;
    }
    const int pairs = argc > 1 ? std::atoi(argv[1]) : 7;
    if (pairs < 1) {
        std::fprintf(stderr, "usage: bench-rope-life [PAIRS >= 1]\n");
        return 2;
    }
    std::vector<double> without, with, ratios;
    for (int i = 0; i < pairs; ++i) {
        // Alternate which goes first, so that a drift of the load does not favour one.
        const bool monitorFirst = i % 2 == 1;
        const Run a = runCycle(monitorFirst), b = runCycle(!monitorFirst);
        const Run& w = monitorFirst ? a : b;
        const Run& wo = monitorFirst ? b : a;
        if (w.steps != wo.steps) {
            std::fprintf(stderr, "bench-rope-life: the runs differ (%ld and %ld steps)\n", w.steps, wo.steps);
            return 1;
        }
        with.push_back(w.wall);
        without.push_back(wo.wall);
        ratios.push_back(w.wall / wo.wall);
        std::printf("pair %d: without %.4f s, with %.4f s (%d bend events, %ld steps), ratio %.4f\n", i + 1, wo.wall,
                    w.wall, w.events, w.steps, w.wall / wo.wall);
    }
    std::printf("median: without %.4f s, with %.4f s; median of the pairs' ratios %.4f (monitor share %+.1f %%)\n",
                median(without), median(with), median(ratios), 100.0 * (median(ratios) - 1.0));
    return 0;
}
