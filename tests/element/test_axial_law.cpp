// AxialLaw: the linear, tension-only and rounded tension-only laws; F' = f and f' against finite
// differences, the rounding's continuity (value, slope, curvature) at 0 and eps_s, its bounds.
#include "SimbodyReeving/element/AxialLaw.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

using namespace SimbodyReeving;

namespace {

AxialLaw makeLaw(bool tensionOnly, double transition) {
    RopeProperties p{0.62, 16.5e6, 0.0, tensionOnly};
    return AxialLaw(p, transition);
}

}  // namespace

TEST(AxialLaw, LinearAndPlainClamp) {
    const AxialLaw linear = makeLaw(false, 1e-6);  // the transition is ignored for the linear law
    EXPECT_EQ(linear.transition, 0.0);
    EXPECT_EQ(linear.f(-2e-3), -2e-3);
    EXPECT_EQ(linear.F(-2e-3), 2e-6);
    EXPECT_EQ(linear.force(1e-3), 16.5e3);
    EXPECT_FALSE(linear.slack(-1.0));
    const AxialLaw clamp = makeLaw(true, 0.0);
    EXPECT_EQ(clamp.f(-2e-3), 0.0);
    EXPECT_EQ(clamp.F(-2e-3), 0.0);
    EXPECT_EQ(clamp.f(3e-3), 3e-3);
    EXPECT_DOUBLE_EQ(clamp.F(3e-3), 4.5e-6);
    EXPECT_EQ(clamp.fPrime(-1e-9), 0.0);
    EXPECT_EQ(clamp.fPrime(1e-9), 1.0);
    EXPECT_TRUE(clamp.slack(0.0));
    EXPECT_TRUE(clamp.slack(std::nan("")));
    EXPECT_FALSE(clamp.slack(1e-300));
}

TEST(AxialLaw, RoundedLawIsSmoothBoundedAndExactOutsideTheTransition) {
    const double es = 1e-6;
    const AxialLaw law = makeLaw(true, es);
    // Exact outside (0, eps_s).
    EXPECT_EQ(law.f(-1e-7), 0.0);
    EXPECT_EQ(law.f(2e-6), 2e-6);
    EXPECT_EQ(law.fPrime(5e-6), 1.0);
    EXPECT_DOUBLE_EQ(law.F(2e-6), 0.5 * 4e-12 - 0.1 * es * es);
    // Inside: 0 <= f <= eps, increasing, the shortfall eps_s x (1 - x)^3 (1 + 3x), max 0.1975 eps_s.
    double worst = 0, previous = 0;
    for (int k = 1; k < 1000; ++k) {
        const double eps = es * k / 1000.0, x = eps / es;
        const double fk = law.f(eps);
        EXPECT_GE(fk, 0.0);
        EXPECT_LE(fk, eps);
        EXPECT_GT(fk, previous);
        previous = fk;
        EXPECT_NEAR(eps - fk, es * x * std::pow(1 - x, 3) * (1 + 3 * x), 1e-15 * es);
        worst = std::max(worst, (eps - fk) / es);
    }
    EXPECT_NEAR(worst, 0.1975, 5e-4);
    // F' = f and f' = df/deps by central differences, across the whole range.
    for (int k = -20; k <= 140; ++k) {
        const double eps = es * (k + 0.37) / 100.0, h = 1e-4 * es;
        EXPECT_NEAR((law.F(eps + h) - law.F(eps - h)) / (2 * h), law.f(eps), 1e-8 * es) << "eps " << eps;
        EXPECT_NEAR((law.f(eps + h) - law.f(eps - h)) / (2 * h), law.fPrime(eps), 1e-7) << "eps " << eps;
    }
    // Continuity of F, f, f' and f'' at both joints: the one-sided limits, extrapolated from h on
    // either side with the next derivative, agree to O(h^2) times the derivative after that.
    for (double joint : {0.0, es}) {
        const double h = 1e-5 * es;
        const double fRight = law.f(joint + h) - h * law.fPrime(joint + h);
        const double fLeft = law.f(joint - h) + h * law.fPrime(joint - h);
        // Measured at both joints: f 1.2e-20 (bound 1e-18, 83x), F 2.0e-28 (bound 1e-26,
        // 50x), f' 1.8e-9 (bound 1e-7, 56x); the O(h^2) Taylor terms cancel for the polynomial pieces.
        EXPECT_NEAR(fRight, fLeft, 1e-18) << "joint " << joint;
        const double FRight = law.F(joint + h) - h * law.f(joint + h);
        const double FLeft = law.F(joint - h) + h * law.f(joint - h);
        EXPECT_NEAR(FRight, FLeft, 1e-26) << "joint " << joint;
        EXPECT_NEAR(law.fPrime(joint + h), law.fPrime(joint - h), 1e-7) << "joint " << joint;
        const double curvRight = (law.fPrime(joint + 2 * h) - law.fPrime(joint + h)) / h;
        const double curvLeft = (law.fPrime(joint - h) - law.fPrime(joint - 2 * h)) / h;
        EXPECT_NEAR(curvRight, curvLeft, 1e-3 / es) << "joint " << joint;  // f'' is up to ~4 / eps_s inside
    }
    // F is continuous at eps_s exactly as written (0.4 eps_s^2 from both sides).
    EXPECT_NEAR(law.F(es * (1 - 1e-12)), 0.4 * es * es, 1e-22);
    EXPECT_NEAR(law.F(es), 0.4 * es * es, 2e-27);  // measured 5.0e-29 (round-off of 4e-13), margin 40x
}
