#include "SimbodyReeving/simbody/Visualization.h"

#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <exception>

#include <unistd.h>

namespace SimbodyReeving {

std::unique_ptr<SimTK::Visualizer> tryStartVisualizer(SimTK::MultibodySystem& system, std::string& whyNot) {
    const char* display = std::getenv("DISPLAY");
    if (!display || !*display) {
        whyNot = "no display (DISPLAY is not set)";
        return nullptr;
    }
    setenv("SIMBODY_VISUALIZER_NAME", "simbody-visualizer", /*overwrite=*/0);
    std::signal(SIGPIPE, SIG_IGN);  // a closed visualizer window must not kill the simulation
    const pid_t self = getpid();
    try {
        auto viz = std::make_unique<SimTK::Visualizer>(system);
        viz->setMode(SimTK::Visualizer::PassThrough);
        viz->setShutdownWhenDestructed(false);  // stopVisualizer shuts down; a destructor must not throw
        return viz;
    } catch (const std::exception& e) {
        if (getpid() != self) _exit(1);  // the launcher's child found no executable: leave quietly
        whyNot = std::string("the Simbody visualizer could not start: ") + e.what();
        return nullptr;
    }
}

std::string formatForce(double newtons) {
    const double a = std::abs(newtons);
    const char* unit = "N";
    double v = newtons;
    if (a >= 1e6) {
        v = newtons / 1e6;
        unit = "MN";
    } else if (a >= 1e3) {
        v = newtons / 1e3;
        unit = "kN";
    }
    char buffer[32];
    std::snprintf(buffer, sizeof buffer, "%.3g %s", v, unit);
    return buffer;
}

namespace {

class RopeLegend : public SimTK::DecorationGenerator {
public:
    explicit RopeLegend(const ReevingSubsystem& reeving) : reeving_(reeving) {}
    void generateDecorations(const SimTK::State& state, SimTK::Array_<SimTK::DecorativeGeometry>& geometry) override {
        char time[48];
        std::snprintf(time, sizeof time, "t = %.2f s", state.getTime());
        std::string text = time;
        try {
            text += "   rope axial force: blue 0 N ... red " + formatForce(reeving_.getDecorationForceScale(state));
        } catch (const std::exception&) {
            // the state is not realized far enough for the forces: the time alone
        }
        geometry.push_back(SimTK::DecorativeText(text).setIsScreenText(true).setColor(SimTK::Vec3(0, 0, 0)));
    }

private:
    const ReevingSubsystem& reeving_;
};

}  // namespace

void addRopeLegend(SimTK::Visualizer& visualizer, const ReevingSubsystem& reeving) {
    visualizer.addDecorationGenerator(new RopeLegend(reeving));  // the Visualizer takes ownership
}

void stopVisualizer(SimTK::Visualizer& visualizer) {
    try {
        visualizer.flushFrames();
        visualizer.setMode(SimTK::Visualizer::PassThrough);
        visualizer.shutdown();
    } catch (const std::exception&) {
        // the window was closed already: nothing left to stop
    }
}

}  // namespace SimbodyReeving
