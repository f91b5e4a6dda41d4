#pragma once
// Command line of the reeving-pendulum demo: options, defaults and validation (on CLI11, see
// common/Cli.h for the shared conventions).

#include "common/Cli.h"

#include <SimbodyReeving/scenes/PendulumScene.h>

#include <string>
#include <vector>

namespace pendulum_demo {

/// A bad command line: what() is the one-line message naming the option and quoting the value.
using UsageError = demo_common::UsageError;

struct Options {
    std::vector<int> axialModes{0, 1, 2, 3};
    int transverseModes = 1;
    SimbodyReeving::AxialDynamics axialDynamics = SimbodyReeving::AxialDynamics::QuasiStatic;
    /// Which spans' transverse modes are condensed (TransverseDynamics::QuasiStatic): none (default),
    /// the horizontal 3 m span only, or both.
    enum class QuasiStaticTransverse { None, Horizontal, All } quasiStaticTransverse = QuasiStaticTransverse::None;
    double tEnd = 20.0;            // [s]
    double vx0 = 1.0, vy0 = 0.0;   // [m/s], added after static equilibrium
    std::string integrator = "rk-merson";
    double accuracy = 1e-6;
    double step = 0.0;             // fixed step [s]; 0 = variable step
    double reportInterval = 0.01;  // [s]
    std::string outDir = "out/pendulum";
    bool plots = true, quiet = false, visualize = false, help = false;
    /// --check: validate the options and build every case's scene, then exit (nothing run or written).
    bool check = false;
    /// --max-steps: a case stops (exit status 1, nothing written) once its integrator has taken
    /// this many steps; 0: no limit.
    long maxSteps = 0;
    SimbodyReeving::PendulumParameters parameters;
};

/// Parses argv; sets Options::help for -h or --help. @throws UsageError for an unknown option, a
/// missing or malformed value, an unknown integrator, an out-of-range value, a --set that makes
/// the parameters invalid (PendulumParameters::validate) or a --report-interval above --t-end.
Options parseCommandLine(int argc, char** argv);

/// "dynamic" or "quasi-static".
std::string axialDynamicsName(SimbodyReeving::AxialDynamics a);
std::string quasiStaticTransverseName(Options::QuasiStaticTransverse q);

/// The --help text.
std::string usage();

}  // namespace pendulum_demo
