#pragma once
/// @file
/// Records when the spans of tension-only ropes go slack and taut again during a simulation.

#include "SimbodyReeving/simbody/ReevingSubsystem.h"

#include <Simbody.h>

#include <memory>
#include <vector>

namespace SimbodyReeving {

/// One slack/taut transition of a span.
struct SlackTransition {
    double time = 0;     ///< [s], localized by the integrator to its event-time window
    int rope = 0;        ///< the rope's index (ReevingSubsystem::addRope)
    int span = 0;        ///< the span's index in the rope, from its start
    bool slack = false;  ///< true: the span went slack (max strain fell to 0); false: taut again
};

/// Watches every span of every tension-only rope (RopeProperties::tensionOnly) of a
/// ReevingSubsystem with one Simbody triggered event per span, whose witness is the span's largest
/// strain (ReevingSubsystem::getSpanMaxStrain, Stage::Position). The integrator localizes each zero
/// crossing (so a step never straddles a slack/taut transition, where the axial force has a kink)
/// and the transition is recorded; the events change no state.
///
/// Construct it after the ropes are added and before System::realizeTopology; the system owns the
/// event handlers, so the monitor must outlive the simulation's use of its log only. Drive the
/// system with a stepper that handles triggered events (SimTK::TimeStepper or
/// InterpolatingTimeStepper).
class SlackMonitor {
public:
    /// @param system the system the ReevingSubsystem belongs to; it owns the events.
    /// @param reeving the ropes to watch, all added already.
    /// @param eventWindow required localization window of each transition [s], > 0.
    /// @throws std::invalid_argument if eventWindow is not finite and > 0.
    SlackMonitor(SimTK::MultibodySystem& system, const ReevingSubsystem& reeving, double eventWindow = 1e-6);

    /// The transitions recorded so far, in time order.
    const std::vector<SlackTransition>& transitions() const { return *log_; }
    /// Number of spans watched (the spans of tension-only ropes).
    int numWatchedSpans() const { return watched_; }

private:
    std::shared_ptr<std::vector<SlackTransition>> log_;
    int watched_ = 0;
};

}  // namespace SimbodyReeving
