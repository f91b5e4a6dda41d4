#pragma once
/// @file
/// Starting and stopping Simbody's Visualizer safely on this platform, and the text it shows for
/// the ropes. The ropes themselves (spans coloured by axial force, sheaves, drums with their stored
/// rope, anchors) are drawn by ReevingSubsystem's decorations in any Visualizer (see
/// ReevingSubsystem::setDecorationForceScale).
///
/// Why not Visualizer::RealTime: in that mode Simbody 3.7 draws from its own thread, and when the
/// window is closed the next write to the visualizer's pipe throws (SimTK::Exception, "Broken pipe",
/// VisualizerProtocol's WRITE) in that thread, which ends the program (std::terminate, exit 134).
/// In PassThrough (the mode tryStartVisualizer leaves) and Sampling modes Visualizer::report draws
/// in the caller's thread, so the caller can catch the exception and go on without the window; after
/// such an exception the Visualizer must not be reported to again (its scene lock stays taken).

#include <SimbodyReeving/simbody/ReevingSubsystem.h>

#include <Simbody.h>

#include <memory>
#include <string>

namespace SimbodyReeving {

/// Starts a SimTK::Visualizer for `system` if one can run here, else returns nullptr and says why
/// in `whyNot`. Handles these facts of Debian's Simbody 3.7: the library looks for the executable
/// "simbody-visualizer_d" while the package ships "simbody-visualizer" (SIMBODY_VISUALIZER_NAME is
/// set unless the user set it); with no executable, the launcher's forked child returns through the
/// exception (it is made to exit quietly); with no display (DISPLAY unset) nothing is started;
/// SIGPIPE is ignored (a closed window makes writes fail with EPIPE instead of killing the program).
/// The visualizer is left in PassThrough mode (see the file comment);
/// it does not shut its window down by itself: call stopVisualizer (Simbody's default keeps the
/// window, and its process, alive after the simulation ends).
std::unique_ptr<SimTK::Visualizer> tryStartVisualizer(SimTK::MultibodySystem& system, std::string& whyNot);

/// Adds to `visualizer` a line of screen text with the simulated time and the rope colour scale,
/// e.g. "t = 12.34 s   rope axial force: blue 0 N ... red 48.2 kN" (the red end is
/// ReevingSubsystem::getDecorationForceScale of the frame). `reeving` must outlive the visualizer.
void addRopeLegend(SimTK::Visualizer& visualizer, const ReevingSubsystem& reeving);

/// Shows buffered frames and tells the visualizer process to close its window and exit; call before
/// the system is destroyed. Never throws: a visualizer whose window is already closed is left
/// alone.
void stopVisualizer(SimTK::Visualizer& visualizer);

/// "12.3 kN"-style text of a force [N] with 3 significant digits (N, kN or MN).
std::string formatForce(double newtons);

}  // namespace SimbodyReeving
