// The node laws of a RopeModel (plugin/element/src: FixedLaw, SlidingLaw, DrivenLaw, SlippingLaw,
// their NodeLaw variant and the CapstanLaw), as RopeModel calls them: the registration from the
// MaterialNode tags (where each may stand, its traits), the columns each takes, the known laws'
// coordinates and rates, the solved laws' rows and friction, and the capstan law's weights and the
// tension row's angle terms against their definitions and finite differences.
#include "NodeLaw.h"
#include "support/ExpectThrowMessage.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <stdexcept>

using namespace SimbodyReeving;
using namespace SimbodyReeving::detail;

TEST(NodeLaws, RegistrationTurnsEachTagIntoItsLaw) {
    const int N = 3;
    const double L = 12.5;
    struct Expect {
        MaterialNode kind;
        const char* name;
        bool end, interior, external, dependent, drum, turning;
    };
    const Expect table[] = {
        {MaterialNode::Fixed, "Fixed", true, false, false, false, false, false},
        {MaterialNode::Sliding, "Sliding", false, true, false, true, false, true},
        {MaterialNode::Driven, "Driven", true, true, true, false, true, true},
        {MaterialNode::Slipping, "Slipping", false, true, true, true, false, false},
    };
    for (const Expect& e : table)
        for (int node : {0, 1, N}) {
            const bool end = node == 0 || node == N;
            if (end ? !e.end : !e.interior) {
                EXPECT_THROW_MESSAGE(makeNodeLaw(e.kind, node, N, L), std::invalid_argument,
                                     std::string(end ? "end" : "interior") + " node " + std::to_string(node) +
                                         " cannot be " + e.name);
                continue;
            }
            const NodeLaw law = makeNodeLaw(e.kind, node, N, L);
            EXPECT_EQ(kindOf(law), e.kind);
            EXPECT_STREQ(nameOf(law), e.name);
            EXPECT_EQ(hasExternalCoordinate(law), e.external) << e.name;
            EXPECT_EQ(hasDependentCoordinate(law), e.dependent) << e.name;
            EXPECT_EQ(isDrum(law), e.drum) << e.name;
            EXPECT_EQ(allowsTurningGroove(law), e.turning) << e.name;
        }
    // A fastened end's constant: s_0 = 0, s_N = L.
    EXPECT_EQ(std::get<FixedLaw>(makeNodeLaw(MaterialNode::Fixed, 0, N, L).law).value, 0.0);
    EXPECT_EQ(std::get<FixedLaw>(makeNodeLaw(MaterialNode::Fixed, N, N, L).law).value, L);
    // A new slip starts at kappa = 1 (no friction until setSlipLaw).
    const SlippingLaw slip = std::get<SlippingLaw>(makeNodeLaw(MaterialNode::Slipping, 1, N, L).law);
    EXPECT_EQ(slip.capstan.ratio(), 1.0);
    EXPECT_FALSE(slip.capstan.dependsOnAngle());
    EXPECT_THROW_MESSAGE(makeNodeLaw(static_cast<MaterialNode>(7), 1, N, L), std::invalid_argument,
                         "is not a MaterialNode");
}

TEST(NodeLaws, EachLawTakesItsColumnsAndKnownOnesGiveTheirCoordinate) {
    const NodeColumns c{4, 11, 17};
    NodeLaw fixed = makeNodeLaw(MaterialNode::Fixed, 3, 3, 12.5), sliding = makeNodeLaw(MaterialNode::Sliding, 1, 3, 12.5);
    NodeLaw driven = makeNodeLaw(MaterialNode::Driven, 0, 3, 12.5), slipping = makeNodeLaw(MaterialNode::Slipping, 2, 3, 12.5);
    EXPECT_EQ(placeLaw(fixed, c), 17);
    EXPECT_EQ(placeLaw(sliding, c), 11);
    EXPECT_EQ(placeLaw(driven, c), 4);
    EXPECT_EQ(placeLaw(slipping, c), 11);  // s_k solved; the sheave's surface is the external one
    EXPECT_EQ(std::get<SlippingLaw>(slipping.law).sheaveColumn, 4);
    Eigen::VectorXd x = Eigen::VectorXd::LinSpaced(6, 0.5, 3.0), xdot = Eigen::VectorXd::LinSpaced(6, -1.0, 1.5);
    int known = 0;
    visitKnown(fixed, [&](const auto& law) {
        ++known;
        EXPECT_EQ(law.coordinate(x), 12.5);
        EXPECT_EQ(law.rate(xdot), 0.0);
        EXPECT_TRUE(law.agrees(12.5, x));
    });
    visitKnown(driven, [&](const auto& law) {
        ++known;
        EXPECT_EQ(law.coordinate(x), x[4]);
        EXPECT_EQ(law.rate(xdot), xdot[4]);
        EXPECT_TRUE(law.agrees(x[4], x));
        EXPECT_FALSE(law.agrees(x[4] + 1e-15, x));  // the drum turned since the solve
    });
    visitKnown(sliding, [&](const auto&) { ++known; });
    visitKnown(slipping, [&](const auto&) { ++known; });
    EXPECT_EQ(known, 2);
    int solved = 0;
    for (const NodeLaw* law : {&fixed, &sliding, &driven, &slipping}) visitDependent(*law, [&](const auto&) { ++solved; });
    EXPECT_EQ(solved, 2);
}

TEST(NodeLaws, SolvedLawsWriteTheirRowsAndFriction) {
    int angles = 0, stationarities = 0, holds = 0, products = 0, differences = 0;
    auto angleOf = [&] {
        ++angles;
        SlipAngle<2> a;
        a.alpha = 2.0;
        a.count = 1;
        return a;
    };
    auto stationarity = [&] { ++stationarities; };
    auto hold = [&] { ++holds; };
    SlipWeights seen;
    auto product = [&](const SlipWeights& w) {
        ++products;
        seen = w;
    };
    auto difference = [&] {
        ++differences;
        return 250.0;  // P_{k-1} - P_k [N]
    };
    Eigen::VectorXd Qz = Eigen::VectorXd::Constant(8, 1.0);
    // A frictionless sheave: unit weights, no angle, its stationarity row and its products, no friction.
    const SlidingLaw sliding;
    TensionRow<2> row;
    row.weights.before = 0.5;
    sliding.tensionRow(angleOf, row);
    EXPECT_EQ(row.weights.before, 1.0);
    EXPECT_EQ(row.weights.after, 1.0);
    EXPECT_FALSE(row.angleLaw);
    sliding.multiplierRow(stationarity, hold);
    sliding.multiplierProducts(product);
    sliding.addFriction(difference, Qz, 6);
    EXPECT_EQ(angles, 0);
    EXPECT_EQ(stationarities, 1);
    EXPECT_EQ(holds, 0);
    EXPECT_EQ(products, 1);
    EXPECT_EQ(seen.before, 1.0);
    EXPECT_EQ(seen.after, 1.0);
    EXPECT_EQ(differences, 0);
    EXPECT_EQ(Qz, Eigen::VectorXd::Constant(8, 1.0));
    // A slip at a constant ratio kappa = 4: weights (1/4, 1), no angle, nu held at zero, no
    // products, the friction -(P_{k-1} - P_k) on the material and its reaction on the sheave.
    SlippingLaw slipping;
    slipping.capstan = CapstanLaw(4.0, 0.0);
    slipping.place(NodeColumns{2, 6, -1});
    slipping.tensionRow(angleOf, row);
    EXPECT_EQ(row.weights.before, 0.25);
    EXPECT_EQ(row.weights.after, 1.0);
    EXPECT_FALSE(row.angleLaw);
    slipping.multiplierRow(stationarity, hold);
    slipping.multiplierProducts(product);
    slipping.addFriction(difference, Qz, 6);
    EXPECT_EQ(angles, 0);
    EXPECT_EQ(stationarities, 1);
    EXPECT_EQ(holds, 1);
    EXPECT_EQ(products, 1);
    EXPECT_EQ(differences, 1);
    EXPECT_EQ(Qz[6], 1.0 - 250.0);
    EXPECT_EQ(Qz[2], 1.0 + 250.0);
    // Euler-Eytelwein, kappa = e^(0.3 alpha): the angle taken once, the weights at it.
    slipping.capstan = CapstanLaw(1.0, 0.3);
    slipping.tensionRow(angleOf, row);
    EXPECT_EQ(angles, 1);
    EXPECT_TRUE(row.angleLaw);
    EXPECT_EQ(row.angle.alpha, 2.0);
    EXPECT_EQ(row.weights.before, CapstanLaw(1.0, 0.3).weights(2.0).before);
    EXPECT_EQ(row.weights.before, 1.0 / std::exp(0.6));
}

// kappa(alpha) = kappa_0 e^(c alpha) as weights (w_before, w_after) = (1, kappa) / max(1, kappa):
// the ratio w_after / w_before is kappa (to round-off, measured below 3e-16 relative; bound 1e-15),
// the larger weight is 1, and the derivatives in alpha match 4th-order central differences
// (h = 1e-3 rad; measured below 1e-12 relative; bound 1e-9). The tension row's angle terms:
// dC/dalpha, and the bias (C's second time derivative at zero accelerations, the strains moving at
// their rates and alpha along alpha0 + alphadot t + bias t^2 / 2) against central differences of C
// along that path (h = 1e-3 s; measured below 1e-9 relative; bound 1e-7).
TEST(NodeLaws, CapstanWeightsAreTheScaledRatioAndTheAngleTermsItsDerivatives) {
    double worstRatio = 0, worstSlope = 0, worstBias = 0;
    for (double kappa0 : {0.3, 1.0, 4.0})
        for (double c : {0.5, -0.5, 0.0})
            for (double alpha : {0.4, 2.5}) {
                const CapstanLaw law(kappa0, c);
                const double kappa = kappa0 * std::exp(c * alpha);
                if (std::abs(kappa - 1) < 0.05) continue;  // (the weights' kink at kappa = 1)
                const SlipWeights w = law.weights(alpha);
                worstRatio = std::max(worstRatio, std::abs(w.after / w.before / kappa - 1));
                EXPECT_LE(std::abs(w.after / w.before / kappa - 1), 1e-15);
                EXPECT_EQ(std::max(w.before, w.after), 1.0);
                const double h = 1e-3;
                auto d1 = [&](auto f) {
                    return (f(alpha - 2 * h) - 8 * f(alpha - h) + 8 * f(alpha + h) - f(alpha + 2 * h)) / (12 * h);
                };
                auto before = [&](double a) { return law.weights(a).before; };
                auto after = [&](double a) { return law.weights(a).after; };
                auto dBefore = [&](double a) { return law.weights(a).dBefore; };
                auto dAfter = [&](double a) { return law.weights(a).dAfter; };
                for (double e : {w.dBefore - d1(before), w.dAfter - d1(after), w.ddBefore - d1(dBefore),
                                 w.ddAfter - d1(dAfter)}) {
                    worstSlope = std::max(worstSlope, std::abs(e));
                    EXPECT_LE(std::abs(e), 1e-9 * std::max(1.0, c * c));
                }
                // The row C(t) = w_b(alpha(t)) a(t) - w_a(alpha(t)) b(t).
                TensionRow<2> row;
                row.weights = w;
                row.angleLaw = law.dependsOnAngle();
                row.angle.alpha = alpha;
                row.angle.rate = 0.7;
                row.angle.bias = -0.4;
                const double a0 = 2.1e-3, b0 = 1.3e-3, ar = 4e-4, br = -6e-4;
                auto C = [&](double t) {
                    const double at = alpha + row.angle.rate * t + 0.5 * row.angle.bias * t * t;
                    const SlipWeights wt = law.weights(at);
                    return wt.before * (a0 + ar * t) - wt.after * (b0 + br * t);
                };
                auto Calpha = [&](double at) {
                    const SlipWeights wt = law.weights(at);
                    return wt.before * a0 - wt.after * b0;
                };
                const double slope = d1(Calpha), scale = std::abs(a0) + std::abs(b0);
                EXPECT_LE(std::abs(row.angleSlope(a0, b0) - slope), 1e-9 * scale);
                const double second = (-C(2 * h) + 16 * C(h) - 30 * C(0) + 16 * C(-h) - C(-2 * h)) / (12 * h * h);
                // C's own second derivative without the strains' accelerations is the angle's bias
                // terms (the strains' accelerationBias is the caller's).
                const double bias = row.angleBias(a0, b0, ar, br);
                worstBias = std::max(worstBias, std::abs(bias - second) / scale);
                EXPECT_LE(std::abs(bias - second), 1e-7 * scale) << kappa0 << " " << c << " " << alpha;
            }
    std::printf("capstan weights: ratio %.1e relative, derivatives %.1e, row bias %.1e (relative to the strains)\n",
                worstRatio, worstSlope, worstBias);
}
