// bench-moving-string: the axially moving string with both velocity models.
//
// A taut span (Table 1 rope's rhoA = 0.6205 kg/m and EA = 16.5 MN, EI = 0, no gravity) of material
// length L = 20 m between fixed nodes, at axial force P = 9 810 N (c = sqrt(P / rhoA) = 125.7 m/s),
// with rope flowing through it at v (both end material coordinates Driven: s = s0 + v t). The
// RopeModel is linearised about the steady flow by central differences of its modal accelerations;
// the table gives the first three transverse frequencies against Wickert & Mote's
//     omega_n = (n pi c / L) (1 - v^2 / c^2)
// for VelocityModel::Complete and ::Simplified, n_t = 1..16, v / c = 0, 0.1, 0.3, 0.5, 0.7.
// The assertions on the same numbers: tests/element/test_axially_moving_string.cpp.
//
// Usage:
//   bench-moving-string                      the frequency table (markdown) on stdout
//   bench-moving-string --evaluate NT NA C K  K span evaluations (n_t = NT, n_a = NA, Complete if
//                                            C = 1; Table 1 rope, a 20 m span in motion), for
//                                            instruction counts under callgrind (cost.sh)
//   bench-moving-string --pendulum           the default demo case (Table 1 pendulum, 1 m/s push,
//                                            20 s, n_a = 3 quasi-static, n_t = 1, RK-Merson 1e-6)
//                                            with each velocity model: steps, rhs evaluations and
//                                            the payload's distance between the two
#include "SimbodyReeving/simbody/Integrators.h"
#include "SimbodyReeving/simbody/InterpolatingTimeStepper.h"
#include "SimbodyReeving/scenes/PendulumScene.h"
#include "SimbodyReeving/element/RopeModel.h"

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <random>
#include <vector>

using namespace SimbodyReeving;

namespace {

const double kPi = std::acos(-1.0);
const RopeProperties kString{0.6205, 16.5e6, 0.0};
constexpr double kL = 20.0, kP = 9810.0;
const double kC = std::sqrt(kP / kString.massPerLength);
const double kLambda = std::sqrt(1.0 + 2.0 * kP / kString.axialStiffness);

/// Linearised transverse frequencies [rad/s], ascending, of the span with n_t modes (n_a = 0)
/// at flow speed v.
std::vector<double> frequencies(VelocityModel vm, int nt, double v) {
    SpanOptions o;
    o.axialModes = 0;
    o.transverseModes = nt;
    o.velocityModel = vm;
    const RopeModel<2> rope({SpanModel<2>(kString, o, Eigen::Vector2d::Zero())}, kL + 100,
                            {MaterialNode::Driven, MaterialNode::Driven});
    Eigen::Matrix2Xd nodes(2, 2), vel = Eigen::Matrix2Xd::Zero(2, 2);
    nodes << 0, kLambda * kL, 0, 0;
    const Eigen::VectorXd s = Eigen::Vector2d(3.7, 3.7 + kL), sd = Eigen::Vector2d(v, v);
    const Eigen::VectorXd xdd = Eigen::VectorXd::Zero(rope.numExternalCoordinates());
    RopeData<2> d;
    auto acc = [&](const Eigen::VectorXd& q, const Eigen::VectorXd& qd) {
        rope.computeDynamics(nodes, vel, s, sd, q, qd, d);
        Eigen::VectorXd a;
        rope.modalAccelerations(d, xdd, a);
        return a;
    };
    const int n = rope.numModalCoordinates();
    const double h = 1e-6;
    const Eigen::VectorXd zero = Eigen::VectorXd::Zero(n);
    Eigen::MatrixXd A = Eigen::MatrixXd::Zero(2 * n, 2 * n);
    A.topRightCorner(n, n).setIdentity();
    for (int j = 0; j < n; ++j) {
        Eigen::VectorXd e = zero;
        e[j] = h;
        A.block(n, j, n, 1) = (acc(e, zero) - acc(-e, zero)) / (2 * h);
        A.block(n, n + j, n, 1) = (acc(zero, e) - acc(zero, -e)) / (2 * h);
    }
    Eigen::EigenSolver<Eigen::MatrixXd> es(A);
    std::vector<double> w;
    for (int k = 0; k < 2 * n; ++k)
        if (es.eigenvalues()[k].imag() > 0) w.push_back(es.eigenvalues()[k].imag());
    std::sort(w.begin(), w.end());
    return w;
}

void table() {
    std::printf("Axially moving string: L = %.0f m, P = %.0f N, rhoA = %.4f kg/m, EA = %.3g N, c = %.2f m/s.\n",
                kL, kP, kString.massPerLength, kString.axialStiffness, kC);
    std::printf("Relative error of omega_1, omega_2, omega_3 against Wickert & Mote (n pi c / L)(1 - v^2/c^2).\n\n");
    std::printf("| v/c | n_t | Complete omega_1 | omega_2 | omega_3 | Simplified omega_1 | omega_2 | omega_3 |\n");
    std::printf("|---|---|---|---|---|---|---|---|\n");
    for (double r : {0.0, 0.1, 0.3, 0.5, 0.7})
        for (int nt : {1, 2, 3, 4, 8, 16}) {
            const double v = r * kC;
            const std::vector<double> c = frequencies(VelocityModel::Complete, nt, v);
            const std::vector<double> s = frequencies(VelocityModel::Simplified, nt, v);
            std::printf("| %.1f | %2d |", r, nt);
            for (const auto* w : {&c, &s})
                for (int k = 0; k < 3; ++k) {
                    if (k < static_cast<int>(w->size()))
                        std::printf(" %+.2e |", (*w)[k] / ((k + 1) * kPi * kC / kL * (1 - r * r)) - 1);
                    else
                        std::printf(" - |");
                }
            std::printf("\n");
        }
}

int evaluate(int nt, int na, bool complete, long count) {
    SpanOptions o;
    o.transverseModes = nt;
    o.axialModes = na;
    o.velocityModel = complete ? VelocityModel::Complete : VelocityModel::Simplified;
    o.axialDynamics = AxialDynamics::Dynamic;  // the span alone: no condensation (RopeModel's job)
    const PlanarSpanModel model({0.6205, 16.5e6, 30.9}, o, Eigen::Vector2d(0, -9.81));  // Table 1 rope
    std::mt19937 rng(1);
    std::uniform_real_distribution<double> u(-1, 1);
    Eigen::VectorXd q = Eigen::VectorXd::Zero(model.numCoordinates()), qd(model.numCoordinates());
    q[model.r2Index()] = 20.002;
    for (int k = 4; k < model.s1Index(); ++k) q[k] = 0.01 * u(rng);
    q[model.s2Index()] = 20.0;
    for (int k = 0; k < qd.size(); ++k) qd[k] = u(rng);
    SpanData<2> data;
    double sink = 0;
    for (long k = 0; k < count; ++k) {
        model.evaluate(q, qd, data);
        sink += data.kineticEnergy;
    }
    std::printf("n_t = %d, n_a = %d, %s: %ld evaluations (T = %.6g J)\n", nt, na, complete ? "Complete" : "Simplified",
                count, sink / static_cast<double>(count));
    return 0;
}

int pendulum() {
    std::printf("| velocity model | steps | rhs evaluations | payload x(20 s) [m] | payload y(20 s) [m] |\n");
    std::printf("|---|---:|---:|---:|---:|\n");
    SimTK::Vec3 final[2];
    for (int c = 0; c < 2; ++c) {
        SpanOptions o;
        o.axialModes = 3;
        o.transverseModes = 1;
        o.axialDynamics = AxialDynamics::QuasiStatic;
        o.velocityModel = c ? VelocityModel::Complete : VelocityModel::Simplified;
        const PendulumScene scene(PendulumParameters{}, o);
        SimTK::State st = scene.makeInitialState(1.0, 0.0);
        auto integ = makeIntegrator("rk-merson", scene.system());
        integ->setAccuracy(1e-6);
        InterpolatingTimeStepper ts(scene.system(), *integ);
        ts.initialize(st);
        ts.stepTo(20.0);
        final[c] = scene.payloadPosition(ts.getState());
        std::printf("| %s | %d | %d | %.9f | %.9f |\n", c ? "Complete" : "Simplified", integ->getNumStepsTaken(),
                    integ->getNumRealizations(), final[c][0], final[c][1]);
    }
    std::printf("\npayload distance Complete - Simplified at 20 s: %.3e m\n", (final[1] - final[0]).norm());
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    if (argc == 2 && std::strcmp(argv[1], "--pendulum") == 0) return pendulum();
    if (argc == 6 && std::strcmp(argv[1], "--evaluate") == 0)
        return evaluate(std::atoi(argv[2]), std::atoi(argv[3]), std::atoi(argv[4]) != 0, std::atol(argv[5]));
    if (argc != 1) {
        std::fprintf(stderr, "usage: %s | %s --evaluate NT NA COMPLETE COUNT | %s --pendulum\n", argv[0], argv[0],
                     argv[0]);
        return 2;
    }
    table();
    return 0;
}
