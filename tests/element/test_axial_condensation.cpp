// AxialCondensation: dU/dq_a, dU/dl and the end strains of a span against SpanModel's own forces,
// end strains and energies; gradients and second time derivatives against finite differences; bad input.
#include "SimbodyReeving/element/AxialCondensation.h"
#include "support/ExpectThrowMessage.h"
#include "support/SpanTestSupport.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>
#include <string>
#include <utility>

using namespace SimbodyReeving;
using SimbodyReeving::test::randomState;
using SimbodyReeving::test::randomVelocity;
using SimbodyReeving::test::relativeError;

namespace {

const RopeProperties kRope{0.8, 2.0e4, 3.0, false};  // rhoA [kg/m], EA [N], EI [N m^2], the paper's linear law

template <int Dim>
SpanModel<Dim> makeSpan(int na, int nt, bool tensionOnly = false, double transition = 1e-6, bool transverse = false) {
    SpanOptions o;
    o.quasiStaticSlackTransitionStrain = transition;
    o.axialModes = na;
    o.transverseModes = nt;
    o.axialDynamics = AxialDynamics::QuasiStatic;
    if (transverse) o.transverseDynamics = TransverseDynamics::QuasiStatic;
    o.velocityModel = VelocityModel::Simplified;  // not the default: the setting these bounds were measured with
    Eigen::Matrix<double, Dim, 1> g = Eigen::Matrix<double, Dim, 1>::Zero();
    g[0] = 1.3;
    g[1] = -9.81;
    Eigen::Matrix<double, Dim, Dim> ref = Eigen::Matrix<double, Dim, Dim>::Identity();
    if constexpr (Dim == 3) ref = makeReferenceFrame(Eigen::Vector3d(0.3, -1.0, 0.2), Eigen::Vector3d(0, 0, 1));
    RopeProperties p = kRope;
    p.tensionOnly = tensionOnly;
    return SpanModel<Dim>(p, o, g, ref);
}

template <int Dim>
Eigen::VectorXd valuesOf(const AxialCondensation<Dim>& c, const Eigen::VectorXd& q) {
    AxialCondensationData<Dim> d;
    c.evaluate(q, Eigen::VectorXd(), d);
    return d.value;
}

/// transition > 0 (tension-only): the rounded law with eps_s = transition, at states whose strains
/// lie within a few eps_s of 0 (chord rescaled, modes scaled down), so many points are in (0, eps_s).
/// transverse: the transverse modes condensed too (TransverseDynamics::QuasiStatic): Phi and the end
/// strains' slopes then run over all n_c = n_a + (Dim - 1) n_t modal amplitudes.
template <int Dim>
void checkAgainstSpanEnergy(int na, int nt, bool tensionOnly = false, double transition = 0, bool transverse = false) {
    SCOPED_TRACE("Dim " + std::to_string(Dim) + " n_a " + std::to_string(na) + " n_t " + std::to_string(nt) +
                 (tensionOnly ? " tension-only" : "") + " eps_s " + std::to_string(transition) +
                 (transverse ? " transverse condensed" : ""));
    const SpanModel<Dim> span = makeSpan<Dim>(na, nt, tensionOnly, transition > 0 ? transition : 1e-6, transverse);
    const int nc = span.numCondensedModes();
    EXPECT_EQ(nc, na + (transverse ? (Dim - 1) * nt : 0));
    EXPECT_EQ(AxialCondensation<Dim>(span).numCondensedModes(), nc);
    const AxialCondensation<Dim> cond(span);
    std::mt19937 rng(7 + na + 10 * nt);
    int mixed = 0;  // states with both slack and taut points (tension-only)
    const int trials = tensionOnly ? 12 : 5;
    for (int trial = 0; trial < trials; ++trial) {
        Eigen::VectorXd q = randomState(span, rng, 2.0);
        if (transition > 0) {
            std::uniform_real_distribution<double> u(-1.0, 1.0);
            const double l = q[span.s2Index()] - q[span.s1Index()];
            const Eigen::Matrix<double, Dim, 1> e = q.template segment<Dim>(Dim) - q.template segment<Dim>(0);
            q.template segment<Dim>(Dim) = q.template segment<Dim>(0) + e * (l / e.norm()) * (1.0 + 2.0 * transition * u(rng));
            q.segment(2 * Dim, span.numModalCoordinates()) *= 25.0 * transition;  // strain variation ~ eps_s
        }
        if (tensionOnly) {
            double lo = 1e300, hi = -1e300;
            const double s1 = q[span.s1Index()], s2 = q[span.s2Index()];
            for (int k = 0; k <= 200; ++k) {
                const double eps = span.strain(q, s1 + (s2 - s1) * k / 200.0);
                lo = std::min(lo, eps);
                hi = std::max(hi, eps);
            }
            mixed += lo < 0 && hi > (transition > 0 ? 0.5 * transition : 0.0);
        }
        const Eigen::VectorXd qd = randomVelocity(span, rng, 1.0);
        AxialCondensationData<Dim> d;
        cond.evaluate(q, qd, d);

        // dU/da_i and dU/dl against SpanModel's own generalized forces (exact: same quadrature) and
        // against central differences of its potential energy.
        SpanData<Dim> sd;
        const Eigen::VectorXd zero = Eigen::VectorXd::Zero(q.size());
        auto potential = [&](const Eigen::VectorXd& x) {
            span.evaluate(x, zero, sd);
            return sd.potentialEnergy();
        };
        span.evaluate(q, zero, sd);
        const Eigen::VectorXd Q = sd.elasticForces + sd.gravityForces;
        const double scale = Q.cwiseAbs().maxCoeff();
        for (int i = 0; i < nc; ++i)
            EXPECT_NEAR(d.value[cond.phi(i)], -Q[2 * Dim + i], 1e-11 * scale) << "phi " << i;
        // Measured at most 2.2e-12 of scale; margin 52x.
        EXPECT_NEAR(d.value[cond.lengthDerivative()], -Q[span.s2Index()], 5e-12 * scale);
        for (int i = 0; i < nc; ++i) {
            const double h = transition > 0 ? 1e-8 : 1e-6;  // the rounding is sharp: small steps
            Eigen::VectorXd qp = q, qm = q;
            qp[2 * Dim + i] += h;
            qm[2 * Dim + i] -= h;
            EXPECT_NEAR(d.value[cond.phi(i)], (potential(qp) - potential(qm)) / (2 * h), 1e-6 * scale);
        }
        // End strains and their partial derivatives against SpanModel::endStrain.
        for (SpanEnd end : {SpanEnd::First, SpanEnd::Second}) {
            EndStrain<Dim> es;
            span.endStrain(q, zero, end, es);
            EXPECT_NEAR(d.value[cond.endStrain(end)], es.strain, 1e-15);
            for (int i = 0; i < nc; ++i)
                EXPECT_NEAR(d.value[cond.endStrainModeSlope(end, i)], es.gradient[2 * Dim + i], 1e-13);
            // Measured at most 4.4e-16 (values ~0.5); margin 45x.
            EXPECT_NEAR(d.value[cond.endStrainLengthSlope(end)], es.gradient[span.s2Index()], 2e-14);
        }

        // Gradients against central differences of the values.
        const int nQ = cond.numQuantities();
        Eigen::MatrixXd fdGradient(nQ, q.size());
        for (int k = 0; k < q.size(); ++k) {
            const double h = transition > 0 ? 1e-8 : 1e-6;
            Eigen::VectorXd qp = q, qm = q;
            qp[k] += h;
            qm[k] -= h;
            fdGradient.col(k) = (valuesOf(cond, qp) - valuesOf(cond, qm)) / (2 * h);
        }
        const Eigen::MatrixXd gradient = d.gradient;
        for (int r = 0; r < nQ; ++r)
            EXPECT_LT((gradient.row(r) - fdGradient.row(r)).cwiseAbs().maxCoeff(),
                      1e-6 * std::max(1e-3, fdGradient.row(r).cwiseAbs().maxCoeff()))
                << "quantity " << r;

        // Rate = gradient qdot; acceleration bias = d^2/dt^2 f(q + t qdot) at t = 0.
        const Eigen::VectorXd rate = d.rate, bias = d.accelerationBias;
        EXPECT_LT(relativeError(rate, gradient * qd), 1e-12);
        // Tension-only: the quantities have a kink where a quadrature point's strain crosses 0, so
        // the second difference is taken on the rates (continuous up to the kink) with a step too
        // small for a point to cross.
        Eigen::VectorXd fd2;
        if (tensionOnly) {
            const double h = transition > 0 ? 1e-9 : 1e-7;
            AxialCondensationData<Dim> dp, dm;
            cond.evaluate(q + h * qd, qd, dp);
            cond.evaluate(q - h * qd, qd, dm);
            fd2 = (dp.rate - dm.rate) / (2 * h);
        } else {
            const double h = 1e-4;
            fd2 = (valuesOf(cond, q + h * qd) - 2.0 * valuesOf(cond, q) + valuesOf(cond, q - h * qd)) / (h * h);
        }
        for (int r = 0; r < nQ; ++r)
            EXPECT_NEAR(bias[r], fd2[r], 1e-5 * std::max(1.0, fd2.cwiseAbs().maxCoeff())) << "quantity " << r;
    }
    if (tensionOnly) {
        std::printf("Dim %d n_a %d n_t %d: %d of %d states partly slack\n", Dim, na, nt, mixed, trials);
        EXPECT_GE(mixed, 2);
    }
}

}  // namespace

TEST(AxialCondensation, PlanarQuantitiesGradientsAndBiasesMatchSpanModelAndFiniteDifferences) {
    checkAgainstSpanEnergy<2>(1, 1);
    checkAgainstSpanEnergy<2>(3, 1);
    checkAgainstSpanEnergy<2>(3, 0);
    checkAgainstSpanEnergy<2>(8, 3);
}

TEST(AxialCondensation, SpatialQuantitiesGradientsAndBiasesMatchSpanModelAndFiniteDifferences) {
    checkAgainstSpanEnergy<3>(1, 1);
    checkAgainstSpanEnergy<3>(3, 2);
    checkAgainstSpanEnergy<3>(8, 1);
}

TEST(AxialCondensation, SpansWithoutAxialModes) { checkAgainstSpanEnergy<2>(0, 2); }

// Tension-only rope: the clamped law and the slack regularisation U_delta, at states where some
// strain quadrature points are slack and others taut (the random states stretch and compress by up
// to a factor 2); the count of mixed states is asserted so the kink is really exercised.
TEST(AxialCondensation, TensionOnlyQuantitiesMatchSpanModelAndFiniteDifferences) {
    checkAgainstSpanEnergy<2>(1, 1, true);
    checkAgainstSpanEnergy<2>(3, 1, true);
    checkAgainstSpanEnergy<2>(3, 0, true);
    checkAgainstSpanEnergy<3>(3, 2, true);
    // The rounded law of quasi-static spans (SpanOptions::quasiStaticSlackTransitionStrain).
    checkAgainstSpanEnergy<2>(3, 1, true, 1e-3);
    checkAgainstSpanEnergy<3>(2, 1, true, 1e-3);
}

// TransverseDynamics::QuasiStatic: the transverse amplitudes are condensed too (their Phi rows carry
// the string, bending and gravity terms, and for a tension-only rope U_delta,t).
TEST(AxialCondensation, CondensedTransverseModesMatchSpanModelAndFiniteDifferences) {
    checkAgainstSpanEnergy<2>(0, 1, false, 0, true);
    checkAgainstSpanEnergy<2>(3, 2, false, 0, true);
    checkAgainstSpanEnergy<3>(2, 2, false, 0, true);
    checkAgainstSpanEnergy<2>(3, 1, true, 0, true);
    checkAgainstSpanEnergy<2>(3, 1, true, 1e-3, true);
    checkAgainstSpanEnergy<3>(2, 1, true, 1e-3, true);
}

TEST(AxialCondensation, BadInputThrows) {
    SpanOptions o;
    o.axialModes = 2;
    o.axialDynamics = AxialDynamics::QuasiStatic;
    o.elasticModel = ElasticEnergyModel::PaperLiteral;
    EXPECT_THROW_MESSAGE(SpanModel<2>(kRope, o, Eigen::Vector2d(0, -9.81)), std::invalid_argument,
                         "SpanModel: SpanOptions::axialDynamics = QuasiStatic (the default) with axial modes requires "
                         "elasticModel = Consistent (got PaperLiteral)");
    // TransverseDynamics::QuasiStatic: with PaperLiteral, under Dynamic axial modes, with transverse
    // damping, and delta_t out of range.
    auto expectThrow = [](SpanOptions options, const std::string& what) {
        EXPECT_THROW_MESSAGE(SpanModel<2>(kRope, options, Eigen::Vector2d(0, -9.81)), std::invalid_argument, what);
    };
    SpanOptions t;
    t.axialModes = 2;
    t.transverseDynamics = TransverseDynamics::QuasiStatic;
    SpanOptions literal = t;
    literal.axialModes = 0;
    literal.elasticModel = ElasticEnergyModel::PaperLiteral;
    expectThrow(literal, "SpanModel: SpanOptions::transverseDynamics = QuasiStatic requires elasticModel = Consistent");
    SpanOptions dynamicAxial = t;
    dynamicAxial.axialDynamics = AxialDynamics::Dynamic;
    expectThrow(dynamicAxial, "requires axialDynamics = QuasiStatic when n_a > 0");
    SpanOptions damped = t;
    damped.transverseDampingRatio = 0.01;
    expectThrow(damped, "SpanOptions::transverseDampingRatio (zeta_t) = 0.01 must be 0 with transverseDynamics = "
                        "QuasiStatic");
    for (const auto& [bad, text] : {std::pair{0.0, "0"}, std::pair{1e-2, "0.01"}, std::pair{std::nan(""), "nan"}}) {
        SpanOptions o2 = t;
        o2.quasiStaticTransverseSlackStiffness = bad;
        expectThrow(o2, std::string("SpanOptions::quasiStaticTransverseSlackStiffness (delta_t) = ") + text +
                            " must be in [1e-12, 1e-3]");
    }
    // Dynamic axial modes with n_a = 0 and no transverse modes are fine.
    SpanOptions fine = t;
    fine.axialModes = 0;
    fine.axialDynamics = AxialDynamics::Dynamic;
    EXPECT_EQ(SpanModel<2>(kRope, fine, Eigen::Vector2d(0, -9.81)).numCondensedModes(), 1);
    fine.transverseModes = 0;
    EXPECT_EQ(SpanModel<2>(kRope, fine, Eigen::Vector2d(0, -9.81)).numCondensedModes(), 0);
}
