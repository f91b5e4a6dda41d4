// Gauss-Legendre rule on [0, 1]: exactness for polynomials, and the measured trigonometric rule
// behind SpanModel::automaticQuadraturePoints.
#include "SimbodyReeving/element/GaussLegendre.h"
#include "SimbodyReeving/element/SpanModel.h"
#include "support/ExpectThrowMessage.h"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

using namespace SimbodyReeving;

TEST(GaussLegendre, WeightsSumToOneAndNodesAscendInsideUnitInterval) {
    for (int n : {1, 2, 3, 7, 40, 150, 200}) {
        const auto rule = makeGaussLegendreRule(n);
        double sum = 0;
        for (int k = 0; k < n; ++k) {
            sum += rule.weights[k];
            EXPECT_GT(rule.nodes[k], 0.0);
            EXPECT_LT(rule.nodes[k], 1.0);
            if (k > 0) {
                EXPECT_GT(rule.nodes[k], rule.nodes[k - 1]);
            }
        }
        EXPECT_NEAR(sum, 1.0, 1e-14) << n;
    }
}

TEST(GaussLegendre, ExactForPolynomialsOfDegree2NMinus1) {
    for (int n : {1, 2, 5, 12}) {
        const auto rule = makeGaussLegendreRule(n);
        for (int p = 0; p <= 2 * n - 1; ++p) {
            double sum = 0;
            for (int k = 0; k < n; ++k) sum += rule.weights[k] * std::pow(rule.nodes[k], p);
            EXPECT_NEAR(sum, 1.0 / (p + 1), 2e-15) << "n=" << n << " p=" << p;
        }
    }
}

// The rule N = ceil(1.15 k) + 12 integrates xi^p cos(k pi xi) and xi^p sin(k pi xi), p <= 3, to
// round-off (absolute error < 5e-15, about 20 ulp: the 200-point reference sum has its own
// round-off) for every k = 0..64 (the strain integrand of a span with n_max modes has k <= 4 n_max).
TEST(GaussLegendre, TrigonometricRuleUsedBySpanModelIsExactToRoundOff) {
    const double pi = std::acos(-1.0);
    const auto ref = makeGaussLegendreRule(200);
    double worst = 0;
    for (int k = 0; k <= 64; ++k) {
        const int n = k == 0 ? 2 : static_cast<int>(std::ceil(1.15 * k)) + 12;
        const auto rule = makeGaussLegendreRule(n);
        for (int p = 0; p <= 3; ++p)
            for (int phase = 0; phase < 2; ++phase) {
                auto f = [&](double x) {
                    return std::pow(x, p) * (phase ? std::sin(k * pi * x) : std::cos(k * pi * x));
                };
                double a = 0, b = 0;
                for (int j = 0; j < n; ++j) a += rule.weights[j] * f(rule.nodes[j]);
                for (size_t j = 0; j < ref.nodes.size(); ++j) b += ref.weights[j] * f(ref.nodes[j]);
                worst = std::max(worst, std::abs(a - b));
                EXPECT_LT(std::abs(a - b), 5e-15) << "k=" << k << " p=" << p << " phase=" << phase;
            }
    }
    RecordProperty("worst_abs_error", std::to_string(worst));
}

TEST(GaussLegendre, AutomaticRuleOfSpanModelFollowsTheMeasuredRule) {
    using I = Integrand;
    EXPECT_EQ(SpanModel<2>::automaticQuadraturePoints(0, 0, I::Kinetic), 2);
    EXPECT_EQ(SpanModel<2>::automaticQuadraturePoints(0, 0, I::Strain), 1);
    EXPECT_EQ(SpanModel<2>::automaticQuadraturePoints(1, 1, I::Kinetic), 3 + 12);   // k = 2
    EXPECT_EQ(SpanModel<3>::automaticQuadraturePoints(3, 1, I::Strain), 14 + 12);   // k = 12
    EXPECT_EQ(SpanModel<3>::automaticQuadraturePoints(16, 2, I::Strain), 74 + 12);  // k = 64
}

TEST(GaussLegendre, RejectsBadPointCounts) {
    EXPECT_THROW_MESSAGE(makeGaussLegendreRule(0), std::invalid_argument,
                         "makeGaussLegendreRule: numPoints = 0 is outside 1..200");
    EXPECT_THROW_MESSAGE(makeGaussLegendreRule(201), std::invalid_argument,
                         "makeGaussLegendreRule: numPoints = 201 is outside 1..200");
}
