#pragma once
// Command line of the reeving-boom-crane demo: options, defaults and validation (on CLI11, see
// common/Cli.h for the shared conventions).

#include "common/Cli.h"
#include "common/RopeLifeOutput.h"

#include <SimbodyReeving/scenes/BoomCraneScene.h>

#include <string>

namespace boom_crane_demo {

/// A bad command line: what() is the one-line message naming the option and quoting the value.
using UsageError = demo_common::UsageError;

struct Options {
    int axialModes = 1;
    int transverseModes = 1;
    SimbodyReeving::AxialDynamics axialDynamics = SimbodyReeving::AxialDynamics::QuasiStatic;
    double lift = 4.0;       // hook lift of the cycle [m]
    double slewDeg = 90.0;   // slewing angle of the cycle [deg]
    double luffDeg = 10.0;   // boom raised by the cycle [deg]
    double tEnd = 40.0;      // [s]: the cycle's duration
    std::string integrator = "rk-merson";
    double accuracy = 1e-6;
    double step = 0.0;             // fixed step [s]; 0 = variable step
    double reportInterval = 0.05;  // [s]
    long maxSteps = 0;             // --max-steps; 0: no limit
    int snapshots = 6;             // machine snapshots, evenly spaced over [0, t_end]
    std::string outDir = "out/boom-crane";
    demo_common::RopeLifeCli ropeLife{0.016};  // both ropes' bending counts: the scene's 16 mm ropes
    bool plots = true, quiet = false, visualize = false, help = false, check = false;
    SimbodyReeving::BoomCraneParameters parameters;  // --boom-angle in degrees sets parameters.boomAngle [rad]

    /// The machine's program: BoomCraneCycle::liftSlewLower(parameters, lift, slew, luff) in radians.
    /// @throws std::invalid_argument for a luff that leaves the boom's range or invalid parameters.
    SimbodyReeving::BoomCraneCycle cycle() const;
};

/// Parses argv; sets Options::help for -h or --help. @throws UsageError for an unknown option, a
/// missing or malformed value, an unknown integrator or sheave model, an out-of-range value, a
/// parameter that BoomCraneParameters::validate rejects or a --report-interval above --t-end.
Options parseCommandLine(int argc, char** argv);

/// "dynamic" or "quasi-static".
std::string axialDynamicsName(SimbodyReeving::AxialDynamics a);

/// The --help text.
std::string usage();

/// Exit status of a run that a rope limit ended early (two-blocking, drum empty); outputs written.
constexpr int kLimitReachedExitStatus = 3;

}  // namespace boom_crane_demo
