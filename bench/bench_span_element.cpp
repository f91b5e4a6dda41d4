// One span evaluation (M, Q_elastic, Q_v, gravity, energies) for the demo's mode counts.
// Reproduce: build/bench/bench-span-element --benchmark_repetitions=9 --benchmark_report_aggregates_only=true
#include <SimbodyReeving/element/SpanModel.h>

#include <benchmark/benchmark.h>

#include <random>

using namespace SimbodyReeving;

namespace {

template <int Dim>
void evaluateSpan(benchmark::State& state) {
    SpanOptions o;
    o.transverseModes = static_cast<int>(state.range(0));
    o.axialModes = static_cast<int>(state.range(1));
    o.velocityModel = state.range(2) ? VelocityModel::Complete : VelocityModel::Simplified;
    o.axialDynamics = AxialDynamics::Dynamic;  // not the default: the setting of the recorded results
    Eigen::Matrix<double, Dim, Dim> ref = Eigen::Matrix<double, Dim, Dim>::Identity();
    Eigen::Matrix<double, Dim, 1> g = Eigen::Matrix<double, Dim, 1>::Zero();
    g[1] = -9.81;
    const SpanModel<Dim> model({0.6205, 16.5e6, 30.9}, o, g, ref);  // Table 1 rope
    std::mt19937 rng(1);
    std::uniform_real_distribution<double> u(-1, 1);
    Eigen::VectorXd q = Eigen::VectorXd::Zero(model.numCoordinates()), qd(model.numCoordinates());
    q.template segment<Dim>(Dim)[0] = 20.002;
    for (int k = 2 * Dim; k < model.s1Index(); ++k) q[k] = 0.01 * u(rng);
    q[model.s2Index()] = 20.0;
    for (int k = 0; k < qd.size(); ++k) qd[k] = u(rng);
    SpanData<Dim> data;
    for (auto _ : state) {
        model.evaluate(q, qd, data);
        benchmark::DoNotOptimize(data.velocityForces.data());
        benchmark::DoNotOptimize(data.massMatrix.data());
    }
    state.counters["coords"] = model.numCoordinates();
    state.counters["qp_kin"] = model.quadraturePoints(Integrand::Kinetic);
    state.counters["qp_strain"] = model.quadraturePoints(Integrand::Strain);
}

}  // namespace

// Args: n_t, n_a, complete velocity (0/1)
BENCHMARK_TEMPLATE(evaluateSpan, 2)->ArgNames({"nt", "na", "complete"})->Args({1, 3, 0})->Args({1, 3, 1})->Args({1, 0, 0});
BENCHMARK_TEMPLATE(evaluateSpan, 3)->ArgNames({"nt", "na", "complete"})->Args({1, 3, 0})->Args({1, 3, 1})->Args({1, 0, 0});

BENCHMARK_MAIN();
// Velocity models: Complete against Simplified over n_t = 1..3, n_a = 0..3 (planar span), in one run
// (instruction counts of the same grid: bench/moving_string/cost.sh).
BENCHMARK_TEMPLATE(evaluateSpan, 2)->ArgNames({"nt", "na", "complete"})->ArgsProduct({{1, 2, 3}, {0, 1, 2, 3}, {0, 1}});
