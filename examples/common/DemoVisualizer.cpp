#include "common/DemoVisualizer.h"

#include <SimbodyReeving/simbody/Visualization.h>

#include <algorithm>
#include <cerrno>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <set>
#include <thread>
#include <utility>

#include <dirent.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <unistd.h>

namespace demo_common {

namespace {

/// Children of this process whose command name starts with "simbody-visuali" (/proc/<pid>/stat).
std::set<int> visualizerChildren() {
    std::set<int> out;
    DIR* proc = opendir("/proc");
    if (!proc) return out;
    const pid_t self = getpid();
    while (const dirent* e = readdir(proc)) {
        const int pid = std::atoi(e->d_name);
        if (pid <= 0) continue;
        std::ifstream stat(std::string("/proc/") + e->d_name + "/stat");
        std::string line;
        if (!std::getline(stat, line)) continue;
        const auto open = line.find('('), close = line.rfind(')');
        if (open == std::string::npos || close == std::string::npos || close + 2 >= line.size()) continue;
        const std::string comm = line.substr(open + 1, close - open - 1);
        char state = 0;
        int ppid = 0;
        if (std::sscanf(line.c_str() + close + 2, "%c %d", &state, &ppid) == 2 && ppid == self &&
            comm.rfind("simbody-visuali", 0) == 0)
            out.insert(pid);
    }
    closedir(proc);
    return out;
}

/// Waits up to `seconds` for child `pid` to end (reaping it); true if it did.
bool waitForChild(int pid, double seconds) {
    const auto until = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
    do {
        int status = 0;
        const pid_t r = waitpid(pid, &status, WNOHANG);
        if (r == pid || (r == -1 && errno == ECHILD)) return true;
        std::this_thread::sleep_for(std::chrono::milliseconds(20));
    } while (std::chrono::steady_clock::now() < until);
    return false;
}

}  // namespace

DemoVisualizer::DemoVisualizer(SimTK::MultibodySystem& system, const SimbodyReeving::ReevingSubsystem& reeving,
                               std::string demoName, bool enabled, double speed)
    : name_(std::move(demoName)), speed_(speed > 0 ? speed : 1.0) {
    if (!enabled) return;
    // Simbody's default geometry (body frames, lines to the parent body) would clutter the machine.
    system.updMatterSubsystem().setShowDefaultGeometry(false);
    const std::set<int> before = visualizerChildren();
    std::string whyNot;
    viz_ = SimbodyReeving::tryStartVisualizer(system, whyNot);
    if (!viz_) {
        std::cerr << name_ << ": --visualize: " << whyNot << "; running without the Visualizer\n";
        return;
    }
    for (int pid : visualizerChildren())
        if (!before.count(pid)) pid_ = pid;
    if (pid_ > 0) watchdog_ = std::thread([this] { watch(); });
    try {
        viz_->setWindowTitle(name_);
        viz_->setBackgroundType(SimTK::Visualizer::SolidColor);
        viz_->setBackgroundColor(SimTK::White);
        SimbodyReeving::addRopeLegend(*viz_, reeving);
    } catch (const std::exception&) {
        broken_ = true;  // closed already
    }
}

DemoVisualizer::~DemoVisualizer() { close(); }

namespace {
long long steadyNanoseconds() {
    return std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::steady_clock::now().time_since_epoch())
        .count();
}
}  // namespace

void DemoVisualizer::watch() {
    constexpr long long limit = 10'000'000'000LL;  // 10 s of one write
    while (!stopWatch_) {
        const long long since = writingSince_;
        if (since != 0 && steadyNanoseconds() - since > limit) {
            endedHung_ = true;
            kill(pid_, SIGKILL);  // the blocked write now fails with EPIPE
            return;
        }
        std::this_thread::sleep_for(std::chrono::milliseconds(100));
    }
}

void DemoVisualizer::lookAt(const SimTK::Vec3& eye, const SimTK::Vec3& target) {
    if (!showing()) return;
    // The camera looks along its -z with its y up: z from the target to the eye, x = y_up x z.
    const SimTK::UnitVec3 z(eye - target);
    const SimTK::UnitVec3 x(SimTK::cross(SimTK::Vec3(0, 1, 0), SimTK::Vec3(z)));
    const SimTK::Vec3 y = SimTK::cross(SimTK::Vec3(z), SimTK::Vec3(x));
    SimTK::Mat33 m;
    m.col(0) = SimTK::Vec3(x);
    m.col(1) = y;
    m.col(2) = SimTK::Vec3(z);
    try {
        viz_->setCameraTransform(SimTK::Transform(SimTK::Rotation(m), eye));
    } catch (const std::exception&) {
        broken_ = true;
    }
}

void DemoVisualizer::report(const SimTK::State& state) {
    if (!showing()) return;
    const auto now = std::chrono::steady_clock::now();
    if (!started_) {
        started_ = true;
        t0_ = state.getTime();
        wall0_ = now;
    } else {
        // Real-time pacing: simulated time t is shown at wall time wall0 + (t - t0) / speed.
        const auto due = wall0_ + std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                                      std::chrono::duration<double>((state.getTime() - t0_) / speed_));
        if (due > now) std::this_thread::sleep_until(due);
        if (std::chrono::steady_clock::now() - lastFrame_ < std::chrono::milliseconds(25)) {
            last_ = std::make_unique<SimTK::State>(state);  // skipped: kept for flush()
            pending_ = true;
            return;
        }
    }
    draw(state);
}

void DemoVisualizer::flush() {
    if (pending_ && last_ && showing()) draw(*last_);
    pending_ = false;
}

void DemoVisualizer::draw(const SimTK::State& state) {
    pending_ = false;
    writingSince_ = steadyNanoseconds();
    try {
        viz_->report(state);
        writingSince_ = 0;
        lastFrame_ = std::chrono::steady_clock::now();
    } catch (const std::exception&) {
        writingSince_ = 0;
        broken_ = true;
        std::cerr << "\n" << name_
                  << (endedHung_ ? ": the Visualizer read no frame for 10 s and was ended at t = "
                                 : ": the Visualizer window was closed at t = ")
                  << state.getTime() << " s; the run goes on without it\n";
    }
}

void DemoVisualizer::close() {
    if (!viz_) return;
    flush();
    if (!broken_) {
        writingSince_ = steadyNanoseconds();
        SimbodyReeving::stopVisualizer(*viz_);
        writingSince_ = 0;
    }
    stopWatch_ = true;
    if (watchdog_.joinable()) watchdog_.join();
    viz_.reset();
    if (pid_ > 0 && !waitForChild(pid_, 2.0)) {
        kill(pid_, SIGTERM);
        if (!waitForChild(pid_, 1.0)) {
            kill(pid_, SIGKILL);
            waitForChild(pid_, 1.0);
        }
    }
    pid_ = -1;
}

}  // namespace demo_common
