#pragma once
// The bundled demos' --visualize: Simbody's Visualizer for one run, paced to real time, that a
// closed window never stops, and whose process ends with the demo.

#include <SimbodyReeving/simbody/ReevingSubsystem.h>

#include <Simbody.h>

#include <atomic>
#include <chrono>
#include <memory>
#include <string>
#include <thread>

namespace demo_common {

/// Shows a run in Simbody's Visualizer (SimbodyReeving::tryStartVisualizer: PassThrough mode, the
/// simulated time and the rope colour scale on screen, SimbodyReeving::addRopeLegend).
///
/// - report() draws in the caller's thread and waits so that simulated time runs no faster than
///   `speed` x wall time; frames closer than 1/40 s of wall time to the last one drawn are skipped
///   (the last report of a run is always drawn: call flush()).
/// - Closing the window: the next report() catches Simbody's exception (a write to the closed
///   pipe fails with EPIPE), says once on stderr "<demo>: the Visualizer window was closed at
///   t = T s; the run goes on without it", and every later report() does nothing.
/// - A visualizer that stops reading (a window closed while its process hangs on the way out, seen
///   under Xvfb) would block a frame's write to its pipe forever: a watchdog thread ends the
///   visualizer process (SIGKILL) when one frame has been writing for 10 s; the write then fails
///   and the run goes on as after a closed window ("<demo>: the Visualizer read no frame for 10 s
///   and was ended at t = T s; the run goes on without it").
/// - close() (also run by the destructor) shuts the visualizer down and waits for its process
///   (found among this process's children when it started) to end: at most 2 s, then SIGTERM.
/// Not copyable; one thread at a time.
class DemoVisualizer {
public:
    /// @param enabled false: nothing is started and every call does nothing.
    /// @param speed simulated seconds per wall second, > 0 (1: real time).
    /// If the visualizer cannot start (no display, no executable) it says why on stderr and the run
    /// goes on without it.
    DemoVisualizer(SimTK::MultibodySystem& system, const SimbodyReeving::ReevingSubsystem& reeving,
                   std::string demoName, bool enabled, double speed = 1.0);
    ~DemoVisualizer();
    DemoVisualizer(const DemoVisualizer&) = delete;
    DemoVisualizer& operator=(const DemoVisualizer&) = delete;

    /// true while a window shows the run.
    bool showing() const { return viz_ != nullptr && !broken_; }
    /// Camera at `eye` looking at `target`, y up [m] (no effect when not showing).
    void lookAt(const SimTK::Vec3& eye, const SimTK::Vec3& target);
    /// Draws `state` (realized to Stage::Position at least) as described above.
    void report(const SimTK::State& state);
    /// Draws the last state reported, if skipped.
    void flush();
    /// Process id of the visualizer, -1 if none (for tests and diagnostics).
    int processId() const { return pid_; }
    void close();

private:
    void draw(const SimTK::State& state);
    void watch();

    std::string name_;
    double speed_ = 1.0;
    std::unique_ptr<SimTK::Visualizer> viz_;
    int pid_ = -1;
    bool broken_ = false, started_ = false, pending_ = false;
    double t0_ = 0;
    std::chrono::steady_clock::time_point wall0_, lastFrame_;
    std::unique_ptr<SimTK::State> last_;
    // Watchdog: steady_clock time (ns) the current write to the visualizer began, 0 when none.
    std::atomic<long long> writingSince_{0};
    std::atomic<bool> stopWatch_{false}, endedHung_{false};
    std::thread watchdog_;
};

/// For a SimTK::TimeStepper loop: a periodic event reporter (interval [s], > 0) that forwards to
/// DemoVisualizer::report. The DemoVisualizer must outlive the simulation.
class DemoVisualizerReporter : public SimTK::PeriodicEventReporter {
public:
    DemoVisualizerReporter(DemoVisualizer& visualizer, double interval)
        : SimTK::PeriodicEventReporter(interval), visualizer_(visualizer) {}
    void handleEvent(const SimTK::State& state) const override { visualizer_.report(state); }

private:
    DemoVisualizer& visualizer_;
};

}  // namespace demo_common
