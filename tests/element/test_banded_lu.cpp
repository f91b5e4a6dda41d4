// BandedLU: solutions of random band systems (symmetric indefinite ones with zero diagonal blocks,
// as the rope's KKT systems, included) against Eigen's dense partial-pivoting LU; singularity;
// range checks.
#include "SimbodyReeving/element/BandedLU.h"
#include "support/ExpectThrowMessage.h"

#include <Eigen/Dense>
#include <gtest/gtest.h>

#include <random>
#include <stdexcept>

using namespace SimbodyReeving;

namespace {
double solveError(int n, int kl, int ku, bool zeroDiagonal, std::mt19937& rng) {
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    Eigen::MatrixXd A = Eigen::MatrixXd::Zero(n, n);
    for (int i = 0; i < n; ++i)
        for (int j = std::max(0, i - kl); j <= std::min(n - 1, i + ku); ++j) A(i, j) = u(rng);
    if (zeroDiagonal)
        for (int i = 1; i < n; i += 2) A(i, i) = 0;  // pivoting needed
    BandedLU lu;
    lu.reset(n, kl, ku);
    for (int i = 0; i < n; ++i)
        for (int j = std::max(0, i - kl); j <= std::min(n - 1, i + ku); ++j) lu.add(i, j, A(i, j));
    EXPECT_EQ(lu.entry(0, 0), A(0, 0));
    EXPECT_TRUE(lu.factor());
    Eigen::VectorXd b = Eigen::VectorXd::NullaryExpr(n, [&] { return u(rng); });
    Eigen::VectorXd x = b;
    lu.solve(x.data());
    // Backward error |A x - b| / (|A| |x| + |b|) (random band matrices, triangular ones especially,
    // can be badly conditioned, so forward errors would measure the matrix, not the solver), and
    // the dense LU's for comparison.
    const Eigen::VectorXd ref = A.partialPivLu().solve(b);
    auto backward = [&](const Eigen::VectorXd& y) {
        return (A * y - b).cwiseAbs().maxCoeff() /
               (A.cwiseAbs().rowwise().sum().maxCoeff() * y.cwiseAbs().maxCoeff() + b.cwiseAbs().maxCoeff());
    };
    EXPECT_LE(backward(ref), 1e-13);
    return backward(x);
}
}  // namespace

TEST(BandedLU, MatchesDenseLuOnRandomBandSystems) {
    std::mt19937 rng(7);
    double worst = 0;
    for (int n : {1, 2, 5, 17, 60})
        for (int kl : {0, 1, 3, 8})
            for (int ku : {0, 2, 8})
                for (bool zero : {false, true}) {
                    if (zero && (kl == 0 || ku == 0)) continue;  // structurally singular then
                    const double e = solveError(n, kl, ku, zero, rng);
                    worst = std::max(worst, e);
                }
    // Measured 7.9e-17 (backward error: round-off, as Eigen's dense LU); bound about 100x.
    EXPECT_LE(worst, 1e-14);
}

TEST(BandedLU, ReportsExactlySingularMatricesAndReusesStorage) {
    BandedLU lu;
    lu.reset(3, 1, 1);
    lu.add(0, 0, 1.0);
    lu.add(2, 2, 1.0);  // row and column 1 are zero
    EXPECT_FALSE(lu.factor());
    lu.reset(2, 0, 0);  // smaller: zeroed, reused
    EXPECT_EQ(lu.entry(0, 0), 0.0);
    lu.add(0, 0, 2.0);
    lu.add(1, 1, 4.0);
    ASSERT_TRUE(lu.factor());
    double b[2] = {2.0, 2.0};
    lu.solve(b);
    EXPECT_EQ(b[0], 1.0);
    EXPECT_EQ(b[1], 0.5);
}

TEST(BandedLU, RejectsEntriesOutsideTheBandAndBadSizes) {
    BandedLU lu;
    lu.reset(4, 1, 0);
    EXPECT_THROW_MESSAGE(lu.add(0, 1, 1.0), std::out_of_range,
                         "BandedLU: entry (0, 1) is outside the 4 x 4 band matrix (kl = 1, ku = 0)");
    EXPECT_THROW_MESSAGE(lu.add(3, 1, 1.0), std::out_of_range, "entry (3, 1) is outside the 4 x 4 band matrix");
    EXPECT_THROW_MESSAGE(lu.add(4, 4, 1.0), std::out_of_range, "entry (4, 4) is outside the 4 x 4 band matrix");
    EXPECT_THROW_MESSAGE(lu.reset(-1, 0, 0), std::invalid_argument,
                         "BandedLU::reset: n = -1, kl = 0, ku = 0 must all be >= 0");
    EXPECT_THROW_MESSAGE(lu.reset(3, 0, -2), std::invalid_argument, "ku = -2 must all be >= 0");
}

TEST(BandedLU, AssemblyAtPrecomputedOffsetsEqualsAddAndChecksTheBand) {
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    const int n = 9, kl = 2, ku = 3;
    BandedLU byIndex, byOffset;
    byIndex.reset(n, kl, ku);
    byOffset.reset(n, kl, ku);
    for (int i = 0; i < n; ++i)
        for (int j = std::max(0, i - kl); j <= std::min(n - 1, i + ku); ++j) {
            const double v = u(rng);
            byIndex.add(i, j, v);
            byOffset.addAt(BandedLU::offset(n, kl, ku, i, j), v);
        }
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) EXPECT_EQ(byOffset.entry(i, j), byIndex.entry(i, j));
    EXPECT_THROW_MESSAGE(BandedLU::offset(n, kl, ku, 0, 4), std::out_of_range,  // above the band
                         "entry (0, 4) is outside the 9 x 9 band matrix (kl = 2, ku = 3)");
    EXPECT_THROW_MESSAGE(BandedLU::offset(n, kl, ku, 5, 2), std::out_of_range,  // below it
                         "entry (5, 2) is outside the 9 x 9 band matrix");
    EXPECT_THROW_MESSAGE(BandedLU::offset(n, kl, ku, n, n), std::out_of_range,  // outside the matrix
                         "entry (9, 9) is outside the 9 x 9 band matrix");
}

TEST(BandedLU, BlockSolveEqualsColumnByColumnSolvesExactly) {
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    const int n = 23, kl = 4, ku = 5, nr = 7;
    BandedLU lu;
    lu.reset(n, kl, ku);
    for (int i = 0; i < n; ++i)
        for (int j = std::max(0, i - kl); j <= std::min(n - 1, i + ku); ++j) lu.add(i, j, i % 3 == 1 && i == j ? 0.0 : u(rng));
    ASSERT_TRUE(lu.factor());
    std::vector<double> block(n * nr), column(n);
    for (double& b : block) b = u(rng);
    std::vector<double> original = block;
    lu.solve(block.data(), nr);
    for (int r = 0; r < nr; ++r) {
        for (int i = 0; i < n; ++i) column[i] = original[i * nr + r];
        lu.solve(column.data());
        for (int i = 0; i < n; ++i) EXPECT_EQ(block[i * nr + r], column[i]) << i << " " << r;
    }
}
