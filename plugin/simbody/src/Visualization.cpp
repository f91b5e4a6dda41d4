#include "SimbodyReeving/simbody/Visualization.h"

#include <csignal>
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
        return std::make_unique<SimTK::Visualizer>(system);
    } catch (const std::exception& e) {
        if (getpid() != self) _exit(1);  // the launcher's child found no executable: leave quietly
        whyNot = std::string("the Simbody visualizer could not start: ") + e.what();
        return nullptr;
    }
}

void stopVisualizer(SimTK::Visualizer& visualizer) {
    visualizer.flushFrames();
    visualizer.setMode(SimTK::Visualizer::PassThrough);
}

}  // namespace SimbodyReeving
