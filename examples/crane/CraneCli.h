#pragma once
// Command line of the reeving-crane demo: options, defaults and validation.

#include <SimbodyReeving/CraneScene.h>

#include <stdexcept>
#include <string>

namespace crane_demo {

/// A bad command line: what() is the one-line message naming the option and value.
struct UsageError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

struct Options {
    int axialModes = 1;
    int transverseModes = 1;
    SimbodyReeving::AxialDynamics axialDynamics = SimbodyReeving::AxialDynamics::QuasiStatic;
    double lift = 5.0;        // hook lift of the cycle [m]
    double traverse = 10.0;   // trolley travel of the cycle [m]
    double tEnd = 36.0;       // [s]; 0 on the command line is not allowed
    std::string integrator = "rk-merson";
    double accuracy = 1e-6;
    double step = 0.0;             // fixed step [s]; 0 = variable step
    double reportInterval = 0.02;  // [s]
    int snapshots = 6;             // rope-geometry snapshots, evenly spaced over [0, t_end]
    std::string outDir = "out/crane";
    bool plots = true, quiet = false, help = false;
    bool visualize = false;  // --visualize: show the run in Simbody's Visualizer
    SimbodyReeving::CraneParameters parameters;
};

/// Parses argv. @throws UsageError for an unknown option, a missing or malformed value, an unknown
/// integrator or an out-of-range value.
Options parseCommandLine(int argc, char** argv);

/// "dynamic" or "quasi-static".
std::string axialDynamicsName(SimbodyReeving::AxialDynamics a);

/// The --help text.
std::string usage();

/// Exit status of a run that a rope limit ended early (two-blocking, drum empty); outputs written.
constexpr int kLimitReachedExitStatus = 3;

}  // namespace crane_demo
