// crane-animation-frames: the reeving-crane demo's default cycle (same scene, integrator and
// settings: 4 falls, n_a = n_t = 1, quasi-static axial modes, RK-Merson at 1e-6) with its
// drawing (drawCrane) written every FRAME_INTERVAL seconds, for scripts/crane-animation.sh.
//   crane-animation-frames OUT.dat [FRAME_INTERVAL]     (default 0.5 s; 0 < FRAME_INTERVAL <= 36)
// OUT.dat: gnuplot data sets as reeving-crane's snapshots.dat (columns x y ink).
#include "CraneFigures.h"

#include <SimbodyReeving/scenes/CraneScene.h>
#include <SimbodyReeving/simbody/Integrators.h>
#include <SimbodyReeving/simbody/InterpolatingTimeStepper.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <fstream>
#include <vector>

using namespace SimbodyReeving;

int main(int argc, char** argv) {
    if (argc < 2 || argc > 3) {
        std::fprintf(stderr, "usage: crane-animation-frames OUT.dat [FRAME_INTERVAL]\n");
        return 2;
    }
    const double interval = argc == 3 ? std::atof(argv[2]) : 0.5;
    if (!(interval > 0 && interval <= 36)) {
        std::fprintf(stderr, "crane-animation-frames: FRAME_INTERVAL = %s must be in (0, 36] s\n", argc == 3 ? argv[2] : "");
        return 2;
    }
    try {
        SpanOptions spans;
        spans.axialModes = 1;
        spans.transverseModes = 1;
        spans.axialDynamics = AxialDynamics::QuasiStatic;
        const CraneCycle cycle = CraneCycle::liftTraverseLower();
        CraneScene scene(CraneParameters{}, cycle, spans);
        auto integ = makeIntegrator("rk-merson", scene.system());
        integ->setAccuracy(1e-6);
        InterpolatingTimeStepper ts(scene.system(), *integ);
        ts.initialize(scene.makeInitialState());
        std::vector<crane_demo::Snapshot> frames;
        const int n = static_cast<int>(std::floor(cycle.duration / interval + 1e-9));
        for (int k = 0; k <= n; ++k) {
            if (k > 0) ts.stepTo(k * interval);
            const SimTK::State& s = ts.getState();
            scene.system().realize(s, SimTK::Stage::Position);
            frames.push_back({s.getTime(), crane_demo::phaseAt(cycle, s.getTime()), crane_demo::drawCrane(scene, s)});
        }
        std::ofstream out(argv[1]);
        crane_demo::writeSnapshots(out, frames);
        if (!out) throw std::runtime_error(std::string("cannot write ") + argv[1]);
        std::printf("crane-animation-frames: %zu frames, every %g s, in %s\n", frames.size(), interval, argv[1]);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "crane-animation-frames: %s\n", e.what());
        return 1;
    }
    return 0;
}
