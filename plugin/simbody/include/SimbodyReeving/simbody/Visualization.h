#pragma once
/// @file
/// Starting and stopping Simbody's Visualizer safely on this platform. The ropes themselves are
/// drawn by ReevingSubsystem's decorations in any Visualizer.

#include <Simbody.h>

#include <memory>
#include <string>

namespace SimbodyReeving {

/// Starts a SimTK::Visualizer for `system` if one can run here, else returns nullptr and says why
/// in `whyNot`. Handles three facts of Debian's Simbody 3.7: the library looks for the executable
/// "simbody-visualizer_d" while the package ships "simbody-visualizer" (SIMBODY_VISUALIZER_NAME is
/// set unless the user set it); with no executable, the launcher's forked child returns through the
/// exception (it is made to exit quietly); with no display (DISPLAY unset) nothing is started.
std::unique_ptr<SimTK::Visualizer> tryStartVisualizer(SimTK::MultibodySystem& system, std::string& whyNot);

/// Shows buffered frames and stops the drawing thread; call before the system is destroyed (a
/// RealTime visualizer still drawing while the system dies aborts the program).
void stopVisualizer(SimTK::Visualizer& visualizer);

}  // namespace SimbodyReeving
