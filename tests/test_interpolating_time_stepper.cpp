// InterpolatingTimeStepper: the step count does not depend on the report interval, and the
// interpolated reports agree with SimTK::TimeStepper's (which stops at every report).
#include "SimbodyReeving/Integrators.h"
#include "SimbodyReeving/InterpolatingTimeStepper.h"
#include "SimbodyReeving/PendulumScene.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

using namespace SimbodyReeving;

namespace {

struct RunRecord {
    int steps = 0;
    std::vector<SimTK::Vec3> positions;  // payload centre every 0.5 s
};

template <class Stepper>
RunRecord run(double reportInterval, double tEnd = 5.0) {
    SpanOptions o;
    o.axialModes = 0;
    o.transverseModes = 1;
    const PendulumScene scene(PendulumParameters{}, o);
    auto integ = makeIntegrator("rk-merson", scene.system());
    integ->setAccuracy(1e-6);
    Stepper ts(scene.system(), *integ);
    ts.initialize(scene.makeInitialState(1.0, 0.0));
    RunRecord r;
    const int n = static_cast<int>(std::lround(tEnd / reportInterval));
    const int every = static_cast<int>(std::lround(0.5 / reportInterval));
    for (int k = 1; k <= n; ++k) {
        ts.stepTo(k * reportInterval);
        if (k % every == 0) {
            scene.system().realize(ts.getState(), SimTK::Stage::Position);
            r.positions.push_back(scene.payloadPosition(ts.getState()));
        }
    }
    EXPECT_NEAR(ts.getState().getTime(), tEnd, 1e-12);
    r.steps = integ->getNumStepsTaken();
    return r;
}

}  // namespace

TEST(InterpolatingTimeStepper, StepCountIndependentOfReportInterval) {
    const RunRecord fine = run<InterpolatingTimeStepper>(0.01), coarse = run<InterpolatingTimeStepper>(0.5);
    const RunRecord stopping = run<SimTK::TimeStepper>(0.01);
    std::printf("steps: interpolating 0.01 s reports %d, 0.5 s reports %d; SimTK::TimeStepper 0.01 s reports %d\n",
                fine.steps, coarse.steps, stopping.steps);
    EXPECT_EQ(fine.steps, coarse.steps);
    EXPECT_LT(fine.steps, stopping.steps);  // TimeStepper ends a step at every report
    double worst = 0;
    for (size_t k = 0; k < fine.positions.size(); ++k)
        worst = std::max(worst, (fine.positions[k] - stopping.positions[k]).norm());
    std::printf("max |payload position difference| interpolated vs stopping: %.2e m\n", worst);
    EXPECT_LT(worst, 1e-5);  // both within the 1e-6 accuracy setting of the true path
}
