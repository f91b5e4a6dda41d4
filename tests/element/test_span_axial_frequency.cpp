// Axial (rod) frequencies of a taut straight span against the closed forms. Linearised about a
// uniformly stretched state (Green strain eps0, no gravity), the span's axial coordinates -- the
// end node along the chord and the axial sine amplitudes a_i -- are the Ritz discretisation of
// the rod
//     rhoA u_tt = EA_t u_ss,   EA_t = EA (1 + 3 eps0),
// u the axial displacement as a function of the material coordinate s in [0, l] (l the unstretched
// length, rhoA per unstretched length). EA_t is the tangent of the nominal tension T = EA eps lambda
// (lambda = sqrt(1 + 2 eps) the stretch): dT/dlambda = EA (eps + lambda^2) = EA (1 + 3 eps), so
// the wave speed is c_t = sqrt(EA_t / rhoA). Closed forms (omega = beta c_t / l):
// - both ends fixed:     beta_n = n pi. The sine modes are the rod's eigenfunctions, so the first n_a
//   frequencies are exact (to round-off) for every n_a;
// - one end fixed, the other free:          beta_n = (2n - 1) pi / 2;
// - one end fixed, a tip mass M on the other: beta tan beta = rhoA l / M.
// With a free or mass-loaded end the Ritz basis {xi, sin(i pi xi)} is not the eigenfunctions: the
// sine coefficients of sin(beta xi) - xi sin(beta) fall as i^-3 (its second derivative does not
// vanish at xi = 1), so the frequency error falls about as n_a^-3, and it is one-sided (Ritz
// frequencies lie above the exact ones).
#include "SimbodyReeving/element/SpanModel.h"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>

#include <cmath>
#include <cstdio>
#include <vector>

using namespace SimbodyReeving;

namespace {

const double kPi = std::acos(-1.0);
// The Table 1 rope with EI = 0 and the linear law; its vertical span and payload.
const RopeProperties kRope{0.6205, 16.5e6, 0.0, false};
constexpr double kLength = 20.0, kPayload = 1000.0, kG = 9.81;

enum class FarEnd { Fixed, Free, Mass };

/// Axial angular frequencies [rad/s], ascending, of a span of unstretched length l held at node 1
/// (and at its material coordinates), stretched uniformly to Green strain eps0. FarEnd::Fixed holds
/// node 2 too (the axial amplitudes alone move); Free and Mass let node 2 move along the chord (Mass
/// adds a point mass `tipMass` there; the pretension is then held by a dead load at the tip, which
/// adds no stiffness). K = -dQ_elastic/dq by central differences of the analytic elastic forces
/// (extrapolated, below); M the span's mass matrix. *coupling: largest stiffness or mass entry between these coordinates
/// and every other free one (transverse modes, node 2 across the chord), relative to the largest
/// entry (zero on the straight state).
template <int Dim>
Eigen::VectorXd axialFrequencies(int na, double l, double eps0, FarEnd end, double tipMass, double* coupling) {
    SpanOptions o;
    o.axialModes = na;
    o.transverseModes = 1;
    o.axialDynamics = AxialDynamics::Dynamic;  // the amplitudes carry their own inertia
    const SpanModel<Dim> model(kRope, o, Eigen::Matrix<double, Dim, 1>::Zero());
    Eigen::VectorXd q0 = Eigen::VectorXd::Zero(model.numCoordinates());
    q0[SpanModel<Dim>::r2Index()] = std::sqrt(1.0 + 2.0 * eps0) * l;  // chord along x
    q0[model.s2Index()] = l;
    std::vector<int> axial, other;  // the moving axial coordinates, the other free ones
    if (end != FarEnd::Fixed) axial.push_back(SpanModel<Dim>::r2Index());
    for (int i = 0; i < na; ++i) axial.push_back(model.axialModeIndex(i));
    if (end != FarEnd::Fixed)
        for (int k = 1; k < Dim; ++k) other.push_back(SpanModel<Dim>::r2Index() + k);
    for (int dir = 0; dir < Dim - 1; ++dir) other.push_back(model.transverseModeIndex(dir, 0));

    const Eigen::VectorXd zero = Eigen::VectorXd::Zero(q0.size());
    SpanData<Dim> d;
    model.evaluate(q0, zero, d);
    const int n = static_cast<int>(axial.size()), m = static_cast<int>(other.size());
    Eigen::MatrixXd K(n, n), M(n, n), Kc(m, n), Mc(m, n);
    // Along these coordinates the strain is quadratic (the chord keeps its direction), so U is a
    // quartic and Q_elastic a cubic: the central difference D(h) = Q'(0) + Q'''(0) h^2 / 6 exactly,
    // and (4 D(h) - D(2h)) / 3 = Q'(0) with no truncation error. A large step then keeps the
    // round-off small: eps = (|t|^2 / l^2 - 1) / 2 carries an absolute round-off of about 1e-16,
    // against a change of about pi h / l = 3e-3 here (a plain difference with h = 1e-7 l left
    // 2e-10 in the frequencies).
    const double h = 1e-3 * l;
    auto difference = [&](int j, double step) {
        Eigen::VectorXd qp = q0, qm = q0;
        qp[axial[j]] += step;
        qm[axial[j]] -= step;
        SpanData<Dim> dp, dm;
        model.evaluate(qp, zero, dp);
        model.evaluate(qm, zero, dm);
        return Eigen::VectorXd(-(dp.elasticForces - dm.elasticForces) / (2 * step));
    };
    for (int j = 0; j < n; ++j) {
        const Eigen::VectorXd col = (4.0 * difference(j, h) - difference(j, 2 * h)) / 3.0;
        for (int i = 0; i < n; ++i) {
            K(i, j) = col[axial[i]];
            M(i, j) = d.massMatrix(axial[i], axial[j]);
        }
        for (int i = 0; i < m; ++i) {
            Kc(i, j) = col[other[i]];
            Mc(i, j) = d.massMatrix(other[i], axial[j]);
        }
    }
    *coupling = std::max(m > 0 ? Kc.cwiseAbs().maxCoeff() / K.cwiseAbs().maxCoeff() : 0.0,
                         m > 0 ? Mc.cwiseAbs().maxCoeff() / M.cwiseAbs().maxCoeff() : 0.0);
    if (end == FarEnd::Mass) M(0, 0) += tipMass;
    Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> eig(0.5 * (K + K.transpose()), M);
    return eig.eigenvalues().cwiseSqrt();
}

/// Roots beta_k, k = 1..count, of beta sin(beta) - mu cos(beta) = 0 (beta tan beta = mu, mu > 0):
/// one in each ((k - 1) pi, (k - 1) pi + pi / 2), by bisection to round-off.
std::vector<double> tipMassRoots(double mu, int count) {
    std::vector<double> roots;
    for (int k = 1; k <= count; ++k) {
        double lo = (k - 1) * kPi, hi = (k - 1) * kPi + 0.5 * kPi;
        auto g = [mu](double b) { return b * std::sin(b) - mu * std::cos(b); };
        const double glo = g(lo);
        for (int it = 0; it < 200 && hi - lo > 1e-15 * hi; ++it) {
            const double mid = 0.5 * (lo + hi);
            if ((g(mid) > 0) == (glo > 0))
                lo = mid;
            else
                hi = mid;
        }
        roots.push_back(0.5 * (lo + hi));
    }
    return roots;
}

double waveSpeed(double eps0) { return std::sqrt(kRope.axialStiffness * (1.0 + 3.0 * eps0) / kRope.massPerLength); }

}  // namespace

// Both ends fixed: the first n_a frequencies are n c_t / (2 l) to round-off, for n_a up to 16, at
// no pretension, at the Table 1 payload's (eps0 = M g / EA = 5.9e-4) and at eps0 = 1e-2, where the
// tangent factor sqrt(1 + 3 eps0) = 1.0149 is far above round-off: a linear strain (eps = lambda - 1,
// whose nominal tension EA eps has the tangent EA) would miss it by 1.5e-2.
TEST(SpanAxialFrequency, FixedFixedSpanGivesTheRodFrequencies) {
    double worst = 0, worstCoupling = 0;
    for (double eps0 : {0.0, kPayload * kG / kRope.axialStiffness, 1e-2}) {
        for (int na : {1, 3, 8, 16}) {
            double c2 = 0, c3 = 0;
            const Eigen::VectorXd w2 = axialFrequencies<2>(na, kLength, eps0, FarEnd::Fixed, 0, &c2);
            const Eigen::VectorXd w3 = axialFrequencies<3>(na, kLength, eps0, FarEnd::Fixed, 0, &c3);
            worstCoupling = std::max({worstCoupling, c2, c3});
            ASSERT_EQ(w2.size(), na);
            ASSERT_EQ(w3.size(), na);
            for (int k = 1; k <= na; ++k) {
                const double exact = k * kPi * waveSpeed(eps0) / kLength;
                worst = std::max({worst, std::abs(w2[k - 1] / exact - 1), std::abs(w3[k - 1] / exact - 1)});
            }
            const double rod = kPi / kLength * std::sqrt(kRope.axialStiffness / kRope.massPerLength);
            std::printf("[ fixed-fixed ] eps0 = %.3e, n_a = %2d: f_1 = %.6f Hz (closed form %.6f Hz; untensioned rod "
                        "%.6f Hz), f_%d = %.4f Hz\n",
                        eps0, na, w2[0] / (2 * kPi), kPi * waveSpeed(eps0) / kLength / (2 * kPi), rod / (2 * kPi), na,
                        w2[na - 1] / (2 * kPi));
        }
    }
    std::printf("[ fixed-fixed ] worst relative frequency error %.2e, worst coupling %.2e\n", worst, worstCoupling);
    // Measured 3.1e-14 (the Richardson difference above; a plain one with h = 1e-7 l gave 2e-10):
    // round-off, bound 1e-12 (margin 32x), 1e-10 of the tangent factor it verifies (1.5e-2).
    EXPECT_LT(worst, 1e-12);
    EXPECT_LT(worstCoupling, 1e-14);  // measured exactly 0: the axial block decouples on a straight span
}

namespace {

/// Relative errors f / f_exact - 1 of the first min(3, n) axial frequencies of a span with a free
/// (tipMass = 0) or mass-loaded far end, at the Table 1 pretension, in 2D and 3D (which must agree),
/// for each n_a of `counts`; checks them against `measured` (row per n_a; bound: 0 <= error <=
/// 1.25 x measured) and prints the table. Returns the errors (row per n_a).
std::vector<std::vector<double>> checkConvergence(const char* name, double tipMass, const std::vector<int>& counts,
                                                  const std::vector<std::vector<double>>& measured) {
    const double eps0 = kPayload * kG / kRope.axialStiffness;
    std::vector<double> beta;
    if (tipMass > 0) {
        beta = tipMassRoots(kRope.massPerLength * kLength / tipMass, 3);
    } else {
        for (int k = 1; k <= 3; ++k) beta.push_back((2 * k - 1) * kPi / 2);
    }
    std::vector<std::vector<double>> errors;
    for (size_t row = 0; row < counts.size(); ++row) {
        const int na = counts[row];
        const FarEnd end = tipMass > 0 ? FarEnd::Mass : FarEnd::Free;
        double c2 = 0, c3 = 0;
        const Eigen::VectorXd w2 = axialFrequencies<2>(na, kLength, eps0, end, tipMass, &c2);
        const Eigen::VectorXd w3 = axialFrequencies<3>(na, kLength, eps0, end, tipMass, &c3);
        EXPECT_LT(c2, 1e-14);  // measured exactly 0 (straight span), bound at round-off
        EXPECT_LT(c3, 1e-14);
        std::vector<double> e;
        std::printf("[ %s ] n_a = %2d:", name, na);
        for (int k = 1; k <= std::min<int>(3, static_cast<int>(w2.size())); ++k) {
            const double exact = beta[k - 1] * waveSpeed(eps0) / kLength;
            e.push_back(w2[k - 1] / exact - 1);
            std::printf("  f_%d = %11.6f Hz (closed form %11.6f, error %+.3e)", k, w2[k - 1] / (2 * kPi),
                        exact / (2 * kPi), e.back());
            EXPECT_NEAR(w3[k - 1], w2[k - 1], 1e-12 * w2[k - 1]) << name << ": 3D differs, n_a = " << na;
            // Ritz: the discretisation only constrains the rod, so its frequencies lie above the exact
            // ones (the round-off of the fixed-fixed case, 3e-14, allowed below zero).
            EXPECT_GT(e.back(), -1e-13) << name << ", n_a = " << na << ", mode " << k;
            EXPECT_LE(e.back(), 1.25 * measured[row][k - 1]) << name << ", n_a = " << na << ", mode " << k;
        }
        std::printf("\n");
        errors.push_back(e);
    }
    return errors;
}

}  // namespace

// One end fixed, the other free: beta_n = (2n - 1) pi / 2. The end node along the chord carries the
// linear field xi, the sines the rest; the free end's mode shape sin(beta xi) has a second
// derivative that the sines (all zero at both ends with their second derivatives) cannot follow,
// so its sine coefficients fall as i^-3, the strain-energy error of the truncation as
// sum_{i > n_a} (i pi)^2 i^-6 ~ n_a^-3, and with it the frequency error: halving it takes 2^(1/3)
// times the modes, and doubling n_a divides it by 8 asymptotically.
TEST(SpanAxialFrequency, FreeEndConvergesAsTheInverseCubeOfTheModeCount) {
    // Measured errors (2D = 3D to 1e-12) per n_a = 1, 2, 4, 8, 16 and mode 1..3; bound 1.25x each.
    const std::vector<int> counts{1, 2, 4, 8, 16};
    const std::vector<std::vector<double>> measured{{4.465e-3, 1.688e-1},
                                                    {1.030e-3, 1.179e-2, 1.850e-1},
                                                    {1.823e-4, 1.751e-3, 5.658e-3},
                                                    {2.737e-5, 2.506e-4, 7.217e-4},
                                                    {3.754e-6, 3.394e-5, 9.515e-5}};
    const auto e = checkConvergence("free end", 0.0, counts, measured);
    // The rate: error(n_a) / error(2 n_a) measured 4.3, 5.7, 6.7, 7.3 for the first mode, rising
    // towards 8; the last one must lie in [6.5, 8.5] (an error falling as n_a^-2 would give 4, as
    // n_a^-4 16).
    for (int k = 0; k < 3; ++k) {
        const double rate = e[3][k] / e[4][k];
        std::printf("[ free end ] mode %d: error(n_a = 8) / error(n_a = 16) = %.2f\n", k + 1, rate);
        EXPECT_GT(rate, 6.5);
        EXPECT_LT(rate, 8.5);
    }
}

// One end fixed, a tip mass M on the other, at the pretension M g: beta tan beta = rhoA l / M.
// The Table 1 vertical span with its payload (M = 1000 kg, 80x the span's 12.4 kg): the bounce
// (4.57 Hz; the linear field alone, n_a = 0, already gives it within 2e-6 from the mass M + m/3)
// and the span's first two rod frequencies, near the fixed-fixed ones (129.19 against 129.03 Hz)
// because the payload hardly moves at them. Each needs the axial modes: with n_a = 0 there is no
// rod frequency at all. And a light tip mass (M = rhoA l), whose modes are far from the
// fixed-fixed ones. Both converge like the free end (n_a^-3), from above.
TEST(SpanAxialFrequency, TipMassMatchesTheTranscendentalEquation) {
    const std::vector<int> counts{1, 2, 4, 8, 16};
    // Measured errors per n_a = 1, 2, 4, 8, 16 and mode 1..3; bound 1.25x each.
    const std::vector<std::vector<double>> payload{{1.291e-7, 3.321e-7},
                                                   {3.109e-8, 6.865e-8, 9.957e-8},
                                                   {5.600e-9, 1.161e-8, 1.279e-8},
                                                   {8.439e-10, 1.717e-9, 1.762e-9},
                                                   {1.165e-10, 2.344e-10, 2.362e-10}};
    checkConvergence("tip mass 1000 kg", kPayload, counts, payload);
    const std::vector<std::vector<double>> light{{4.647e-4, 2.006e-3},
                                                 {1.107e-4, 3.906e-4, 6.555e-4},
                                                 {1.985e-5, 6.493e-5, 8.003e-5},
                                                 {2.992e-6, 9.551e-6, 1.094e-5},
                                                 {4.109e-7, 1.303e-6, 1.464e-6}};
    checkConvergence("tip mass rhoA l", kRope.massPerLength * kLength, counts, light);
    // Without axial modes: only the bounce, from the linear field's mass M + m/3 (Rayleigh).
    const double eps0 = kPayload * kG / kRope.axialStiffness;
    double c = 0;
    const Eigen::VectorXd w0 = axialFrequencies<2>(0, kLength, eps0, FarEnd::Mass, kPayload, &c);
    const double beta1 = tipMassRoots(kRope.massPerLength * kLength / kPayload, 1)[0];
    const double exact = beta1 * waveSpeed(eps0) / kLength;
    const double rayleigh = std::sqrt(kRope.axialStiffness * (1 + 3 * eps0) / kLength /
                                      (kPayload + kRope.massPerLength * kLength / 3));
    std::printf("[ tip mass 1000 kg ] n_a =  0: f_1 = %.6f Hz (closed form %.6f Hz, error %+.3e; K / (M + m/3): "
                "%.6f Hz)\n",
                w0[0] / (2 * kPi), exact / (2 * kPi), w0[0] / exact - 1, rayleigh / (2 * kPi));
    ASSERT_EQ(w0.size(), 1);
    EXPECT_NEAR(w0[0], rayleigh, 1e-12 * rayleigh);  // the model's n_a = 0 system is that 1-DOF Ritz
    EXPECT_GT(w0[0] / exact - 1, 0.0);
}

