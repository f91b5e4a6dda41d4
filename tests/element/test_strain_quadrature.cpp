// The midpoint rule (makeMidpointRule, SpanModel::automaticStrainPoints: 2 n_max + 1 points) is exact
// where it claims to be, for cosine series with fewer than 2N half-waves; and a span's automatic
// strain rule (Gauss-Legendre with automaticQuadraturePoints points: the midpoint rule is not the
// automatic rule yet, see SpanModel.cpp) gives the strain energy, the elastic forces and the
// condensation quantities of a taut span (linear law, or tension-only with every point above the
// transition strain) of a 200-point Gauss-Legendre evaluation of the same span.
#include "SimbodyReeving/element/AxialCondensation.h"
#include "SimbodyReeving/element/GaussLegendre.h"
#include "SimbodyReeving/element/SpanModel.h"
#include "support/ExpectThrowMessage.h"
#include "support/SpanTestSupport.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <string>

using namespace SimbodyReeving;
using SimbodyReeving::test::randomState;
using SimbodyReeving::test::randomVelocity;
using SimbodyReeving::test::relativeError;

namespace {

const double kPi = std::acos(-1.0);

// sum_j cos(k pi (j + 1/2) / N) / N is exactly int_0^1 cos(k pi xi) dxi (1 for k = 0, else 0)
// for k < 2N, and is -1 at k = 2N, where the rule stops being exact.
TEST(StrainQuadrature, MidpointRuleIntegratesCosinesBelow2NHalfWavesExactly) {
    double worst = 0;
    for (int n = 1; n <= 60; ++n) {
        const GaussLegendreRule rule = makeMidpointRule(n);
        ASSERT_EQ(static_cast<int>(rule.nodes.size()), n);
        for (int k = 0; k <= 2 * n; ++k) {
            double sum = 0;
            for (int j = 0; j < n; ++j) sum += rule.weights[j] * std::cos(k * kPi * rule.nodes[j]);
            if (k < 2 * n) {
                const double err = std::abs(sum - (k == 0 ? 1.0 : 0.0));
                worst = std::max(worst, err);
                // Measured at most 1.2e-14 (N <= 60, k up to 119: the round-off of cos at
                // arguments up to 370); margin 17x.
                EXPECT_LT(err, 2e-13) << "N=" << n << " k=" << k;
            } else {
                EXPECT_NEAR(sum, -1.0, 2e-13) << "N=" << n;
            }
        }
    }
    RecordProperty("worst_abs_error", std::to_string(worst));
    EXPECT_THROW_MESSAGE(makeMidpointRule(0), std::invalid_argument, "makeMidpointRule: numPoints = 0 is outside 1..200");
    EXPECT_THROW_MESSAGE(makeMidpointRule(201), std::invalid_argument,
                         "makeMidpointRule: numPoints = 201 is outside 1..200");
}

TEST(StrainQuadrature, AutomaticPointCounts) {
    EXPECT_EQ(SpanModel<2>::automaticStrainPoints(0, 0), 1);
    EXPECT_EQ(SpanModel<2>::automaticStrainPoints(3, 1), 7);
    EXPECT_EQ(SpanModel<3>::automaticStrainPoints(1, 16), 33);
    SpanOptions o;
    o.axialModes = 3;
    o.transverseModes = 1;
    const SpanModel<2> automatic({0.8, 2.0e4, 3.0, false}, o, Eigen::Vector2d(0, -9.81));
    EXPECT_EQ(automatic.quadraturePoints(Integrand::Strain), SpanModel<2>::automaticQuadraturePoints(3, 1, Integrand::Strain));
    EXPECT_EQ(automatic.quadraturePoints(Integrand::Kinetic), SpanModel<2>::automaticQuadraturePoints(3, 1, Integrand::Kinetic));
    o.quadraturePoints = 11;  // an explicit count stays a Gauss-Legendre rule for both integrals
    const SpanModel<2> explicitRule({0.8, 2.0e4, 3.0, false}, o, Eigen::Vector2d(0, -9.81));
    const GaussLegendreRule gl = makeGaussLegendreRule(11);
    ASSERT_EQ(explicitRule.quadraturePoints(Integrand::Strain), 11);
    for (int k = 0; k < 11; ++k) {
        EXPECT_EQ(explicitRule.quadratureNodes(Integrand::Strain)[k], gl.nodes[k]);
        EXPECT_EQ(explicitRule.quadratureWeights(Integrand::Strain)[k], gl.weights[k]);
    }
}

struct Case {
    int na, nt;
    ElasticEnergyModel elastic;
    bool tensionOnly;
};

template <int Dim>
SpanModel<Dim> makeSpan(const Case& c, int quadraturePoints) {
    SpanOptions o;
    o.axialModes = c.na;
    o.transverseModes = c.nt;
    o.elasticModel = c.elastic;
    o.axialDynamics = c.elastic == ElasticEnergyModel::PaperLiteral ? AxialDynamics::Dynamic : AxialDynamics::QuasiStatic;
    o.quadraturePoints = quadraturePoints;
    Eigen::Matrix<double, Dim, 1> g = Eigen::Matrix<double, Dim, 1>::Zero();
    g[0] = 1.3;
    g[1] = -9.81;
    Eigen::Matrix<double, Dim, Dim> ref = Eigen::Matrix<double, Dim, Dim>::Identity();
    if constexpr (Dim == 3) ref = makeReferenceFrame(Eigen::Vector3d(0.3, -1.0, 0.2), Eigen::Vector3d(0, 0, 1));
    // rhoA [kg/m], EA [N], EI [N m^2]
    return SpanModel<Dim>({0.8, 2.0e4, 3.0, c.tensionOnly}, o, g, ref);
}

/// A taut state of a tension-only span: chord stretched by 5 % (like randomState; a small strain
/// would only measure the round-off of eps = (|r_xi|^2 / l^2 - 1) / 2, about 1e-16 / eps relative),
/// modal amplitudes 2e-3 l / i^2 for mode number i, so that the strain stays above 1e-2
/// everywhere (asserted at 401 points), far above the default transition strain 1e-5.
template <int Dim>
Eigen::VectorXd tautState(const SpanModel<Dim>& span, std::mt19937& rng) {
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    const double l = 2.0;
    Eigen::VectorXd q = Eigen::VectorXd::Zero(span.numCoordinates());
    Eigen::Matrix<double, Dim, 1> dir = Eigen::Matrix<double, Dim, 1>::Zero();
    dir[0] = 0.8;
    dir[1] = -0.6;
    for (int m = 0; m < Dim; ++m) q[m] = u(rng);
    q.template segment<Dim>(Dim) = q.template segment<Dim>(0) + 1.05 * l * dir;
    const int na = span.axialModes(), nt = span.transverseModes();
    for (int j = 0; j < span.numModalCoordinates(); ++j) {
        const int mode = j < na ? j + 1 : (j - na) % nt + 1;
        q[2 * Dim + j] = 2e-3 * l * u(rng) / (mode * mode);
    }
    q[span.s1Index()] = 0.7;
    q[span.s2Index()] = 0.7 + l;
    double minStrain = 1;
    for (int k = 0; k <= 400; ++k) minStrain = std::min(minStrain, span.strain(q, 0.7 + l * k / 400.0));
    EXPECT_GT(minStrain, 1e-2);
    return q;
}

double matrixError(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b) {
    return (a - b).cwiseAbs().maxCoeff() / std::max(b.cwiseAbs().maxCoeff(), 1e-300);
}

template <int Dim>
void compareWithGaussLegendre200(const Case& c, double& worstForce, double& worstEnergy, double& worstCondensation) {
    SCOPED_TRACE("Dim=" + std::to_string(Dim) + " n_a=" + std::to_string(c.na) + " n_t=" + std::to_string(c.nt) +
                 (c.elastic == ElasticEnergyModel::PaperLiteral ? " literal" : " consistent") +
                 (c.tensionOnly ? " tension-only (taut)" : " linear law"));
    const SpanModel<Dim> automatic = makeSpan<Dim>(c, 0), reference = makeSpan<Dim>(c, 200);
    ASSERT_EQ(automatic.quadraturePoints(Integrand::Strain),
              SpanModel<Dim>::automaticQuadraturePoints(c.na, c.nt, Integrand::Strain));
    std::mt19937 rng(11 + c.na + 17 * c.nt + 5 * c.tensionOnly);
    for (int trial = 0; trial < 3; ++trial) {
        const Eigen::VectorXd q = c.tensionOnly ? tautState(automatic, rng) : randomState(automatic, rng);
        const Eigen::VectorXd qd = randomVelocity(automatic, rng);
        SpanData<Dim> a, r;
        automatic.evaluate(q, qd, a);
        reference.evaluate(q, qd, r);
        const double fe = relativeError(Eigen::VectorXd(a.elasticForces), Eigen::VectorXd(r.elasticForces));
        // The string energy (PaperLiteral) is signed: compare it on the scale of the axial one.
        const double scale = r.axialEnergy + std::abs(r.stringEnergy);
        const double ee = std::max(std::abs(a.axialEnergy - r.axialEnergy), std::abs(a.stringEnergy - r.stringEnergy)) / scale;
        worstForce = std::max(worstForce, fe);
        worstEnergy = std::max(worstEnergy, ee);
        // Measured at most 2.2e-14 (forces) and 1.5e-14 (energies) over these cases (n_a, n_t up to
        // 16; 150 against 200 Gauss-Legendre points differ by 2.3e-14 and 1.8e-15, the round-off
        // of the reference itself); margin 23x / 20x.
        EXPECT_LT(fe, 5e-13);
        EXPECT_LT(ee, 3e-13);
        if (c.elastic == ElasticEnergyModel::Consistent && c.na > 0) {
            const AxialCondensation<Dim> ca(automatic), cr(reference);
            AxialCondensationData<Dim> da, dr;
            ca.evaluate(q, qd, da);
            cr.evaluate(q, qd, dr);
            const double ce = std::max({relativeError(Eigen::VectorXd(da.value), Eigen::VectorXd(dr.value)),
                                        matrixError(da.gradient, dr.gradient),
                                        relativeError(Eigen::VectorXd(da.rate), Eigen::VectorXd(dr.rate)),
                                        relativeError(Eigen::VectorXd(da.accelerationBias),
                                                      Eigen::VectorXd(dr.accelerationBias))});
            worstCondensation = std::max(worstCondensation, ce);
            // Measured at most 7.7e-14 (150 against 200 Gauss-Legendre points: 4.9e-14); margin 13x.
            EXPECT_LT(ce, 1e-12);
        }
    }
}

TEST(StrainQuadrature, AutomaticStrainRuleEqualsGaussLegendre200ForTautSpans) {
    double worstForce = 0, worstEnergy = 0, worstCondensation = 0;
    for (bool tensionOnly : {false, true})
        for (auto em : {ElasticEnergyModel::Consistent, ElasticEnergyModel::PaperLiteral})
            for (auto [na, nt] : {std::pair{0, 0}, {0, 1}, {1, 1}, {3, 1}, {2, 3}, {8, 2}, {16, 16}}) {
                if (tensionOnly && em == ElasticEnergyModel::PaperLiteral) continue;  // not a valid span
                const Case c{na, nt, em, tensionOnly};
                compareWithGaussLegendre200<2>(c, worstForce, worstEnergy, worstCondensation);
                compareWithGaussLegendre200<3>(c, worstForce, worstEnergy, worstCondensation);
            }
    RecordProperty("worst_force_error", std::to_string(worstForce));
    RecordProperty("worst_energy_error", std::to_string(worstEnergy));
    RecordProperty("worst_condensation_error", std::to_string(worstCondensation));
    std::printf("worst relative differences: forces %.2e, energies %.2e, condensation %.2e\n", worstForce,
                worstEnergy, worstCondensation);
}

}  // namespace

namespace {

// The taut fast path (SpanModel::strainTautEverywhere): where the bound proves a span taut, the
// automatic rule evaluates the strain integrals by the midpoint rule and must equal its own
// Gauss-Legendre rule to round-off; where it does not (a slack or nearly slack tension-only span),
// the automatic span must be its Gauss-Legendre rule exactly (bit for bit).
template <int Dim>
void checkTautFastPath(double& worstTaut) {
    const Case c{3, 1, ElasticEnergyModel::Consistent, true};
    const int glPoints = SpanModel<Dim>::automaticQuadraturePoints(c.na, c.nt, Integrand::Strain);
    const SpanModel<Dim> automatic = makeSpan<Dim>(c, 0), gaussLegendre = makeSpan<Dim>(c, glPoints);
    ASSERT_TRUE(automatic.tautStrainRule());
    ASSERT_FALSE(gaussLegendre.tautStrainRule());
    ASSERT_EQ(automatic.quadraturePoints(Integrand::Strain), glPoints);  // the model's rule is unchanged
    EXPECT_EQ(automatic.tautStrainNodes().size(), SpanModel<Dim>::automaticStrainPoints(c.na, c.nt));
    std::mt19937 rng(5);
    const AxialCondensation<Dim> ka(automatic), kg(gaussLegendre);
    auto chordAndLength = [](const SpanModel<Dim>& span, const Eigen::VectorXd& q) {
        const double chord = (q.template segment<Dim>(Dim) - q.template segment<Dim>(0)).norm();
        return std::pair{chord, q[span.s2Index()] - q[span.s1Index()]};
    };
    for (int trial = 0; trial < 4; ++trial) {
        Eigen::VectorXd q = tautState(automatic, rng);
        const Eigen::VectorXd qd = randomVelocity(automatic, rng);
        const bool slack = trial >= 2;  // chord 0.98 l: compressed, slack points
        if (slack) q.template segment<Dim>(Dim) = q.template segment<Dim>(0) + 0.98 / 1.05 * (q.template segment<Dim>(Dim) - q.template segment<Dim>(0));
        const auto [chord, l] = chordAndLength(automatic, q);
        EXPECT_EQ(automatic.strainTautEverywhere(chord, l, q.data() + 2 * Dim), !slack);
        EXPECT_FALSE(gaussLegendre.strainTautEverywhere(chord, l, q.data() + 2 * Dim));
        SpanData<Dim> a, g;
        automatic.evaluate(q, qd, a);
        gaussLegendre.evaluate(q, qd, g);
        AxialCondensationData<Dim> da, dg;
        ka.evaluate(q, qd, da);
        kg.evaluate(q, qd, dg);
        if (slack) {
            for (int i = 0; i < automatic.numCoordinates(); ++i) EXPECT_EQ(a.elasticForces[i], g.elasticForces[i]);
            EXPECT_EQ(a.axialEnergy, g.axialEnergy);
            for (int i = 0; i < ka.numQuantities(); ++i) {
                EXPECT_EQ(da.value[i], dg.value[i]);
                EXPECT_EQ(da.rate[i], dg.rate[i]);
                EXPECT_EQ(da.accelerationBias[i], dg.accelerationBias[i]);
            }
            EXPECT_EQ(matrixError(da.gradient, dg.gradient), 0.0);
        } else {
            const double err = std::max(
                {relativeError(Eigen::VectorXd(a.elasticForces), Eigen::VectorXd(g.elasticForces)),
                 std::abs(a.axialEnergy - g.axialEnergy) / g.axialEnergy,
                 relativeError(Eigen::VectorXd(da.value), Eigen::VectorXd(dg.value)), matrixError(da.gradient, dg.gradient),
                 relativeError(Eigen::VectorXd(da.rate), Eigen::VectorXd(dg.rate)),
                 relativeError(Eigen::VectorXd(da.accelerationBias), Eigen::VectorXd(dg.accelerationBias))});
            worstTaut = std::max(worstTaut, err);
        }
    }
    // The linear law has no slack: always the fast path.
    const SpanModel<Dim> linear = makeSpan<Dim>({c.na, c.nt, c.elastic, false}, 0);
    const double a0[3] = {0, 0, 0};
    EXPECT_TRUE(linear.strainTautEverywhere(0.5, 1.0, a0));
    // The bound: chord 1.01, l = 1, a_1 = 1e-3 (lambda_min = 1.01 - pi 1e-3 > sqrt(1 + 2e-5)) is taut;
    // a_1 = 3.2e-3 (lambda_min = 0.99995) is not.
    const double small[3] = {1e-3, 0, 0}, large[3] = {3.2e-3, 0, 0};
    EXPECT_TRUE(automatic.strainTautEverywhere(1.01, 1.0, small));
    EXPECT_FALSE(automatic.strainTautEverywhere(1.01, 1.0, large));
}

TEST(StrainQuadrature, TautFastPathEqualsGaussLegendreAndSlackSpansKeepIt) {
    double worstTaut = 0;
    checkTautFastPath<2>(worstTaut);
    checkTautFastPath<3>(worstTaut);
    std::printf("taut fast path against Gauss-Legendre: worst relative difference %.2e\n", worstTaut);
    // Measured 2.0e-14; bound 100x.
    EXPECT_LT(worstTaut, 2e-12);
}

}  // namespace
