#pragma once
// Command line of the reeving-crane demo: options, defaults and validation (on CLI11, see
// common/Cli.h for the shared conventions).

#include "common/Cli.h"
#include "common/RopeLifeOutput.h"

#include <SimbodyReeving/scenes/CraneScene.h>

#include <string>

namespace crane_demo {

/// A bad command line: what() is the one-line message naming the option and quoting the value.
using UsageError = demo_common::UsageError;

struct Options {
    SimbodyReeving::CraneScenario scenario = SimbodyReeving::CraneScenario::Cycle;
    int axialModes = 1;
    int transverseModes = 1;
    SimbodyReeving::AxialDynamics axialDynamics = SimbodyReeving::AxialDynamics::QuasiStatic;
    double lift = 5.0;        // hook lift of the cycle [m]
    double traverse = 10.0;   // trolley travel of the cycle [m]
    double tEnd = 36.0;       // [s]; 0 on the command line is not allowed; lift-off: the cycle's duration
    std::string integrator = "rk-merson";
    double accuracy = 1e-6;
    double step = 0.0;             // fixed step [s]; 0 = variable step
    double reportInterval = 0.02;  // [s]; lift-off: 0.001
    long maxSteps = 0;             // --max-steps; 0: no limit
    int snapshots = 6;             // rope-geometry snapshots, evenly spaced over [0, t_end]
    std::string outDir = "out/crane";
    // Bending cycles per rope section (RopeLifeMonitor; rope_bending.csv, summary.json rope_life).
    demo_common::RopeLifeCli ropeLife;  // d = 0.02 m: the scene's 20 mm rope
    bool plots = true, quiet = false, visualize = false, help = false, check = false;
    SimbodyReeving::CraneParameters parameters;  // parameters.scenario == scenario, parameters.hoistSpeed: --hoist-speed

    /// The machine's program: CraneCycle::liftTraverseLower(lift, traverse) or CraneCycle::liftOff(parameters).
    SimbodyReeving::CraneCycle cycle() const;
    bool liftOff() const { return scenario == SimbodyReeving::CraneScenario::LiftOff; }
};

/// Parses argv; sets Options::help for -h or --help. @throws UsageError for an unknown option, a
/// missing or malformed value, an unknown integrator or scenario, an out-of-range value, a --set
/// that makes the parameters invalid (CraneParameters::validate), an option of the other scenario
/// (--lift and --traverse: cycle; --hoist-speed: lift-off) or a --report-interval above --t-end.
/// Lift-off's defaults: --t-end the lift-off cycle's duration, --report-interval 0.001 s.
Options parseCommandLine(int argc, char** argv);

/// "dynamic" or "quasi-static".
std::string axialDynamicsName(SimbodyReeving::AxialDynamics a);

/// The --help text.
std::string usage();

/// Exit status of a run that a rope limit ended early (two-blocking, drum empty); outputs written.
constexpr int kLimitReachedExitStatus = 3;

}  // namespace crane_demo
