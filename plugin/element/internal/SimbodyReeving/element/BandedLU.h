#pragma once
/// @file
/// LU factorization with partial (row) pivoting of a square band matrix (pure C++17): the solver of
/// the rope's chain-structured systems (RopeModel), whose cost is O(n kl (kl + ku)) to factor and
/// O(n (2 kl + ku)) per solve instead of O(n^3) and O(n^2) for a dense LU.

#include <cstddef>
#include <vector>

namespace SimbodyReeving {

/// A = P L U of an n x n matrix with kl sub- and ku superdiagonals. Row swaps within the kl rows
/// below the pivot fill U up to kl + ku superdiagonals, so each row is stored over the columns
/// [i - kl, i + kl + ku] (width 2 kl + ku + 1). Storage grows on demand and is reused: resetting to
/// a size not larger than any earlier one, assembling, factoring and solving never allocate.
class BandedLU {
public:
    /// Sets the size and bandwidths and zeroes the matrix.
    /// @throws std::invalid_argument if n < 0, kl < 0 or ku < 0.
    void reset(int n, int kl, int ku);
    int size() const { return n_; }             ///< n, the matrix's order
    int lowerBandwidth() const { return kl_; }  ///< kl, the number of subdiagonals
    int upperBandwidth() const { return ku_; }  ///< ku, the number of superdiagonals

    /// A(i, j) += value (before factor()).
    /// @throws std::out_of_range if (i, j) is outside the matrix or its band (-kl <= j - i <= ku).
    void add(int i, int j, double value) {
        if (i < 0 || j < 0 || i >= n_ || j >= n_ || j - i > ku_ || i - j > kl_) outOfBand(n_, kl_, ku_, i, j);
        at(i, j) += value;
    }
    /// A(i, j) (before factor(): the assembled entry; 0 outside the band).
    double entry(int i, int j) const;

    /// Where A(i, j) is stored in an n x n band matrix with bandwidths kl, ku (as reset(n, kl, ku)
    /// lays it out), for assembly by addAt without per-entry index arithmetic: assemblers whose
    /// structure is fixed compute their entries' offsets once.
    /// @throws std::out_of_range if (i, j) is outside the matrix or its band.
    static std::ptrdiff_t offset(int n, int kl, int ku, int i, int j);
    /// A(i, j) += value at an offset from offset(size(), lowerBandwidth(), upperBandwidth(), i, j)
    /// (before factor(); not checked).
    void addAt(std::ptrdiff_t offset, double value) { w_[static_cast<std::size_t>(offset)] += value; }

    /// Factors in place. Returns false (and leaves the factorization unusable) if a pivot column is
    /// exactly zero (A singular); true otherwise.
    bool factor();
    /// Solves A x = b in place (b has size() entries) with the factors of the last factor().
    void solve(double* b) const;
    /// Solves A X = B in place for numRhs right-hand sides stored row by row (B(i, r) at
    /// B[i * numRhs + r]): the factors are read once for all of them. Each column's result equals
    /// solve() on that column exactly (same operations in the same order).
    void solve(double* B, int numRhs) const;

private:
    [[noreturn]] static void outOfBand(int n, int kl, int ku, int i, int j);
    template <int NR>
    void solveBlock(double* B, int numRhs) const;
    template <int BAND>
    bool factorBand();
    double& at(int i, int j) { return w_[static_cast<std::size_t>(i) * width_ + (j - i + kl_)]; }
    double at(int i, int j) const { return w_[static_cast<std::size_t>(i) * width_ + (j - i + kl_)]; }
    int n_ = 0, kl_ = 0, ku_ = 0, width_ = 1;
    std::vector<double> w_;   // row i: columns i - kl .. i + kl + ku
    std::vector<int> pivot_;  // row exchanged with row k at step k
};

}  // namespace SimbodyReeving
