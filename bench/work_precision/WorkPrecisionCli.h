#pragma once
// Command line of bench-work-precision (the work-precision study): options, defaults,
// validation. See usage() for the meaning of every option.

#include <SimbodyReeving/element/SpanModel.h>

#include <stdexcept>
#include <string>
#include <vector>

namespace work_precision {

/// A bad command line: what() names the option, the value and why it was refused.
struct UsageError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

struct Options {
    std::vector<std::string> integrators;               // default: SimbodyReeving::integratorNames()
    std::vector<double> accuracies{1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9, 1e-10};
    std::vector<double> steps{1e-3, 1e-4, 1e-5, 1e-6};  // [s] fixed step sizes
    std::vector<std::string> fixedStepIntegrators{"verlet", "explicit-euler"};
    std::vector<int> axialModes{0, 1, 3};
    int transverseModes = 1;
    SimbodyReeving::AxialDynamics axialDynamics = SimbodyReeving::AxialDynamics::Dynamic;
    double tEnd = 20.0;            // [s]
    double reportInterval = 0.01;  // [s]
    double vx0 = 1.0, vy0 = 0.0;   // [m/s]
    int repeats = 3;
    double repeatBelow = 20.0;     // [s] runs slower than this are run once
    double cap = 120.0;            // [s] wall-clock cap per run
    double projectCap = 0;         // > 0: also too slow once the projected wall to t_end exceeds projectCap x cap
    std::string referenceIntegrator = "rk-feldberg";
    double referenceAccuracy = 1e-12;
    double referenceCheckFactor = 2.0;  // the check reference runs at factor * referenceAccuracy
    bool recomputeReference = false;
    bool referenceOnly = false;
    bool capSkipsHigherModes = false;
    bool capSkips = true;          // false (--no-cap-skip): measure tighter settings after a too-slow one
    bool resume = false;           // keep the points already in DIR/results.csv, measure the rest
    int jobs = 1;
    std::string outDir = "out/work-precision";
    bool plots = true, quiet = false, help = false;
};

/// @throws UsageError for an unknown option, a missing or malformed value, an unknown integrator
/// or a value out of range.
Options parseCommandLine(int argc, char** argv);

std::string usage();

}  // namespace work_precision
