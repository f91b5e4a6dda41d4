#include "FloorRun.h"

#include <SimbodyReeving/simbody/Integrators.h>
#include <SimbodyReeving/simbody/InterpolatingTimeStepper.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iomanip>

namespace bench_floor {

void defineOptions(CLI::App& app, Options& o) {
    using namespace demo_common;
    applyConventions(app);
    app.add_option("--t-end", o.tEnd, "end time [s] (default " + numberText(o.tEnd) + ", the demo's)")
        ->type_name("T")
        ->check(positiveNumber());
    app.add_option("--accuracy", o.accuracy, "integrator accuracy, 0 < TOL < 1 (default 1e-6)")
        ->type_name("TOL")
        ->check(numberInOpenInterval(0, 1));
    app.add_option("--integrator", o.integrator,
                   "rk-merson (default), rk3, rk-feldberg, cpodes, verlet,\nsemi-explicit-euler2, explicit-euler")
        ->type_name("NAME")
        ->check(oneOf(SimbodyReeving::integratorNames()));
    app.add_option("--report-interval", o.reportInterval,
                   "output interval [s] (default " + numberText(o.reportInterval) + ", the demo's)")
        ->type_name("DT")
        ->check(positiveNumber());
    app.add_option("--out", o.outDir, "write timeseries.csv and summary.json in DIR (default: nothing written)")
        ->type_name("DIR")
        ->check(nonEmpty());
    app.add_flag("--quiet", o.quiet, "print nothing on success");
}

Result run(const SimTK::MultibodySystem& system, const SimTK::State& initial, const Options& o,
           const std::function<std::vector<double>(const SimTK::State&)>& report) {
    Result r;
    auto integ = SimbodyReeving::makeIntegrator(o.integrator, system);
    integ->setAccuracy(o.accuracy);
    SimbodyReeving::InterpolatingTimeStepper ts(system, *integ);
    ts.initialize(initial);
    const auto start = std::chrono::steady_clock::now();
    r.rows.push_back(report(ts.getState()));
    const int reports = static_cast<int>(std::floor(o.tEnd / o.reportInterval + 1e-9));
    for (int n = 1; n <= reports; ++n) {
        ts.stepTo(n * o.reportInterval);
        r.rows.push_back(report(ts.getState()));
    }
    r.wallSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    r.steps = integ->getNumStepsTaken();
    r.rhsEvaluations = ts.getNumRealizations();
    return r;
}

void writeOutputs(const std::string& program, const Options& o, const Result& r, const std::vector<std::string>& columns,
                  const demo_common::Json& extra) {
    namespace fs = std::filesystem;
    const fs::path dir(o.outDir);
    demo_common::OutputFile tsFile(dir / "timeseries.csv"), jsFile(dir / "summary.json");
    std::ofstream& ts = tsFile.stream();
    for (size_t c = 0; c < columns.size(); ++c) ts << (c ? "," : "") << columns[c];
    ts << '\n' << std::setprecision(12);
    for (const auto& row : r.rows) {
        for (size_t c = 0; c < row.size(); ++c) ts << (c ? "," : "") << row[c];
        ts << '\n';
    }
    using demo_common::jsonNumber;
    demo_common::Json js;
    js["program"] = program;
    js["integrator"] = o.integrator;
    js["accuracy"] = jsonNumber(o.accuracy);
    js["t_end"] = jsonNumber(o.tEnd);
    js["report_interval"] = jsonNumber(o.reportInterval);
    js["steps"] = r.steps;
    js["rhs_evaluations"] = r.rhsEvaluations;
    js["wall_seconds"] = jsonNumber(r.wallSeconds);
    for (const auto& [key, value] : extra.items()) js[key] = value;
    demo_common::writeJson(jsFile.stream(), js);
    tsFile.commit();
    jsFile.commit();  // last: a summary.json means the outputs are complete
}

void printSummary(const std::string& program, const Options& o, const Result& r) {
    if (o.quiet) return;
    std::printf("%s: %s %.3g, %.4g s simulated, %ld steps, %ld rhs evaluations, wall %.3f s%s%s\n", program.c_str(),
                o.integrator.c_str(), o.accuracy, o.tEnd, r.steps, r.rhsEvaluations, r.wallSeconds,
                o.outDir.empty() ? "" : ", outputs in ", o.outDir.c_str());
}

}  // namespace bench_floor
