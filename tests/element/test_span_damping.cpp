// Kelvin-Voigt axial damping of a span (RopeProperties::axialRetardationTime): the forces are minus
// the velocity gradient of the Rayleigh dissipation function D = 1/2 dampingPower (convective rate
// of xi included), the power is 2 D >= 0, and a uniformly strained rope that flows through the span
// dissipates nothing.
#include "SimbodyReeving/element/SpanModel.h"
#include "support/ExpectThrowMessage.h"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

using namespace SimbodyReeving;

namespace {

template <int Dim>
SpanModel<Dim> makeSpan(int na, int nt, double c) {
    RopeProperties p{0.6205, 16.5e6, 0.0, false};
    p.axialRetardationTime = c;
    SpanOptions o;
    o.axialModes = na;
    o.transverseModes = nt;
    o.axialDynamics = AxialDynamics::Dynamic;
    return SpanModel<Dim>(p, o, Eigen::Matrix<double, Dim, 1>::UnitY() * -9.81);
}

template <int Dim>
void checkGradient() {
    const SpanModel<Dim> span = makeSpan<Dim>(2, 2, 0.01);
    const int n = span.numCoordinates();
    Eigen::VectorXd q = Eigen::VectorXd::Zero(n), qd(n);
    q.template segment<Dim>(Dim)[0] = 3.0;
    q.template segment<Dim>(Dim)[1] = -4.0;
    for (int i = 0; i < span.numModalCoordinates(); ++i) q[2 * Dim + i] = 1e-2 * std::sin(1.0 + i);
    q[span.s1Index()] = 1.0;
    q[span.s2Index()] = 5.99;
    for (int i = 0; i < n; ++i) qd[i] = 0.3 * std::cos(0.7 + 1.3 * i);
    SpanData<Dim> d;
    span.evaluate(q, qd, d);
    ASSERT_GT(d.dampingPower, 0);
    EXPECT_NEAR(-d.dampingForces.dot(qd), d.dampingPower, 1e-12 * d.dampingPower);
    for (int i = 0; i < n; ++i) {
        const double h = 1e-6;
        Eigen::VectorXd qp = qd, qm = qd;
        qp[i] += h;
        qm[i] -= h;
        SpanData<Dim> dp, dm;
        span.evaluate(q, qp, dp);
        span.evaluate(q, qm, dm);
        const double dD = (0.5 * dp.dampingPower - 0.5 * dm.dampingPower) / (2 * h);  // D is quadratic: exact
        EXPECT_NEAR(d.dampingForces[i], -dD, 1e-7 * d.dampingForces.cwiseAbs().maxCoeff()) << "coordinate " << i;
    }
}

}  // namespace

TEST(SpanDamping, ForcesAreMinusTheGradientOfTheRayleighFunction) {
    checkGradient<2>();
    checkGradient<3>();
}

// 2 D = EA c int (Deps/Dt)^2 ds with Deps/Dt the strain rate at fixed material points s_k = s1 + xi_k l
// (central differences of SpanModel::strain along q + tau qdot): the convective xi rate is right.
TEST(SpanDamping, PowerIsTheQuadratureOfTheMaterialStrainRate) {
    const SpanModel<2> span = makeSpan<2>(2, 2, 0.01);
    const int n = span.numCoordinates();
    Eigen::VectorXd q = Eigen::VectorXd::Zero(n), qd(n);
    q[2] = 3.0;
    q[3] = -4.0;
    for (int i = 0; i < span.numModalCoordinates(); ++i) q[4 + i] = 1e-2 * std::sin(1.0 + i);
    q[span.s1Index()] = 1.0;
    q[span.s2Index()] = 5.99;
    for (int i = 0; i < n; ++i) qd[i] = 0.3 * std::cos(0.7 + 1.3 * i);
    SpanData<2> d;
    span.evaluate(q, qd, d);
    const Eigen::VectorXd& xi = span.quadratureNodes(Integrand::Strain);
    const Eigen::VectorXd& w = span.quadratureWeights(Integrand::Strain);
    const double l = q[span.s2Index()] - q[span.s1Index()], h = 1e-6;
    double sum = 0;
    for (int k = 0; k < xi.size(); ++k) {
        const double sk = q[span.s1Index()] + xi[k] * l;
        const double rate = (span.strain(q + h * qd, sk) - span.strain(q - h * qd, sk)) / (2 * h);
        sum += w[k] * rate * rate;
    }
    const double expected = 16.5e6 * 0.01 * l * sum;
    std::printf("material rate: power %.9e W vs quadrature of FD rates %.9e W\n", d.dampingPower, expected);
    EXPECT_NEAR(d.dampingPower, expected, 1e-8 * expected);  // measured 4e-10 (the differences' h^2 error)
}

TEST(SpanDamping, RopeFlowingThroughAtUniformStrainDissipatesNothing) {
    const SpanModel<2> span = makeSpan<2>(3, 2, 0.05);
    Eigen::VectorXd q = Eigen::VectorXd::Zero(span.numCoordinates()), qd = q;
    q[2] = 6.0;  // r2 = (6, 0): chord 6 m over 5.994 m of rope, strain 1e-3
    q[span.s1Index()] = 2.0;
    q[span.s2Index()] = 7.994;
    qd[span.s1Index()] = qd[span.s2Index()] = 4.0;  // 4 m/s through the span
    SpanData<2> d;
    span.evaluate(q, qd, d);
    const double P = 16.5e6 * 0.5 * (36.0 / (5.994 * 5.994) - 1.0);
    const double transported = P * 4.0;
    std::printf("flow: damping power %.3e W of transported %.3e W\n", d.dampingPower, transported);
    EXPECT_LE(d.dampingPower, 1e-12 * transported);  // the required bound
    EXPECT_LE(d.dampingForces.cwiseAbs().maxCoeff(), 1e-9 * P);
}

TEST(SpanDamping, RetardationTimeForDampingRatio) {
    EXPECT_DOUBLE_EQ(retardationTimeForDampingRatio(0.02, 40.0), 1e-3);
    EXPECT_THROW_MESSAGE(retardationTimeForDampingRatio(-0.1, 1.0), std::invalid_argument,
                         "retardationTimeForDampingRatio: zeta [-] = -0.1 must be finite and >= 0");
    EXPECT_THROW_MESSAGE(retardationTimeForDampingRatio(0.1, 0.0), std::invalid_argument,
                         "retardationTimeForDampingRatio: omega [rad/s] = 0 must be finite and > 0");
    RopeProperties p{1.0, 1e6, 0.0};
    p.axialRetardationTime = -1;
    EXPECT_THROW_MESSAGE(validate(p), std::invalid_argument,
                         "RopeProperties: axialRetardationTime (c) [s] = -1 must be finite and >= 0");
}
