#pragma once
// Simbody's own floor (the demos' scenes without ropes): what the shared bench-floor-* programs do. A scene
// without the rope is integrated exactly as the demos integrate theirs (the named integrator from
// SimbodyReeving::makeIntegrator, its accuracy, SimbodyReeving::InterpolatingTimeStepper with
// reports at a fixed interval, a reporter that realizes the stage the demo's reporter realizes),
// and the cost is counted the way the demos count it: steps (Integrator::getNumStepsTaken), right-
// hand sides (InterpolatingTimeStepper::getNumRealizations: realizations through
// Stage::Acceleration, reports not included) and the wall time of the integration loop.

#include "common/Cli.h"
#include "common/DemoOutput.h"

#include <Simbody.h>

#include <functional>
#include <string>
#include <vector>

namespace bench_floor {

/// The command line common to both floor programs.
struct Options {
    double tEnd = 0;               ///< [s] (the program sets its demo's default)
    double accuracy = 1e-6;        ///< integrator accuracy
    std::string integrator = "rk-merson";
    double reportInterval = 0;     ///< [s] (the program sets its demo's default)
    std::string outDir;            ///< "" = write nothing
    bool quiet = false;
};

/// Adds --t-end, --accuracy, --integrator, --report-interval, --out and --quiet bound to `o`
/// (the defaults in the help text are o's values).
void defineOptions(CLI::App& app, Options& o);

/// What a run measured, and its reports.
struct Result {
    long steps = 0;                 ///< integrator steps
    long rhsEvaluations = 0;        ///< InterpolatingTimeStepper::getNumRealizations
    double wallSeconds = 0;         ///< the integration loop with its reports [s]
    std::vector<std::vector<double>> rows;  ///< one per report: the reporter's values
};

/// Integrates `system` from `initial` to o.tEnd, calling `report(state)` at t = 0 and every
/// o.reportInterval (the state realized to Stage::Velocity; the reporter realizes further if it
/// needs to) and keeping the rows it returns.
/// @throws std::exception from the integrator.
Result run(const SimTK::MultibodySystem& system, const SimTK::State& initial, const Options& o,
           const std::function<std::vector<double>(const SimTK::State&)>& report);

/// Writes o.outDir/timeseries.csv (`columns`, then the rows at 12 significant digits) and
/// o.outDir/summary.json: `program`, the options, "steps", "rhs_evaluations", "wall_seconds",
/// then the members of `extra` (an object).
void writeOutputs(const std::string& program, const Options& o, const Result& r, const std::vector<std::string>& columns,
                  const demo_common::Json& extra);

/// The one-line summary printed on stdout (unless --quiet).
void printSummary(const std::string& program, const Options& o, const Result& r);

}  // namespace bench_floor
