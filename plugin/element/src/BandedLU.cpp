#include "SimbodyReeving/element/BandedLU.h"


#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace SimbodyReeving {
namespace {
// y += a x over n entries (x, y not overlapping): y[r] + (a x[r]), the rounding of y - l x with a = -l.
inline void axpy(double a, const double* __restrict x, double* __restrict y, int n) {
    for (int r = 0; r < n; ++r) y[r] += a * x[r];
}
// Clears n doubles with vector stores. Not memset: glibc clears a band of this size (a few to tens
// of kB) by `rep stosb`, which callgrind counts byte by byte (8-20 k "instructions" per reset of the
// 12-fall crane's bands, in the instruction counts of bench/cost.sh), so GCC must not turn this
// loop into a memset call.
__attribute__((optimize("no-tree-loop-distribute-patterns"))) void clearBand(double* w, std::size_t n) {
    for (std::size_t i = 0; i < n; ++i) w[i] = 0.0;
}
}  // namespace

void BandedLU::reset(int n, int kl, int ku) {
    if (n < 0 || kl < 0 || ku < 0)
        throw std::invalid_argument("BandedLU::reset: n = " + std::to_string(n) + ", kl = " + std::to_string(kl) +
                                    ", ku = " + std::to_string(ku) + " must all be >= 0");
    n_ = n;
    kl_ = kl;
    ku_ = ku;
    width_ = 2 * kl + ku + 1;
    const std::size_t need = static_cast<std::size_t>(n) * width_;
    if (w_.size() < need) w_.resize(need);
    clearBand(w_.data(), need);
    if (pivot_.size() < static_cast<std::size_t>(n)) pivot_.resize(n);
}

void BandedLU::outOfBand(int n, int kl, int ku, int i, int j) {
    throw std::out_of_range("BandedLU: entry (" + std::to_string(i) + ", " + std::to_string(j) + ") is outside the " +
                            std::to_string(n) + " x " + std::to_string(n) + " band matrix (kl = " + std::to_string(kl) +
                            ", ku = " + std::to_string(ku) + ")");
}

std::ptrdiff_t BandedLU::offset(int n, int kl, int ku, int i, int j) {
    if (i < 0 || j < 0 || i >= n || j >= n || j - i > ku || i - j > kl) outOfBand(n, kl, ku, i, j);
    return static_cast<std::ptrdiff_t>(i) * (2 * kl + ku + 1) + (j - i + kl);
}

double BandedLU::entry(int i, int j) const {
    if (i < 0 || j < 0 || i >= n_ || j >= n_ || j - i > ku_ + kl_ || i - j > kl_) return 0.0;
    return at(i, j);
}

// The elimination with U's bandwidth BAND = kl + ku known at compile time (BAND > 0; 0: at run
// time), so the row updates of interior rows (length BAND) unroll. The same operations in the same
// order either way.
template <int BAND>
bool BandedLU::factorBand() {
    const int band = BAND > 0 ? BAND : kl_ + ku_;  // upper bandwidth of U
    for (int k = 0; k < n_; ++k) {
        const int last = std::min(n_ - 1, k + kl_);
        int p = k;
        double best = std::abs(at(k, k));
        for (int i = k + 1; i <= last; ++i)
            if (std::abs(at(i, k)) > best) {
                best = std::abs(at(i, k));
                p = i;
            }
        pivot_[k] = p;
        if (best == 0.0) return false;
        const int right = std::min(n_ - 1, k + band);
        if (p != k)
            for (int j = k; j <= right; ++j) std::swap(at(k, j), at(p, j));
        const double inv = 1.0 / at(k, k);
        const bool interior = right - k == band;
        for (int i = k + 1; i <= last; ++i) {
            const double l = at(i, k) * inv;
            at(i, k) = l;
            if (l == 0.0) continue;
            // at(i, j) -= l at(k, j) for j = k + 1..right (rows i and k do not overlap)
            if (interior)
                axpy(-l, &at(k, k + 1), &at(i, k + 1), band);
            else
                axpy(-l, &at(k, k + 1), &at(i, k + 1), right - k);
        }
    }
    return true;
}

bool BandedLU::factor() {
    switch (kl_ + ku_) {
        case 4: return factorBand<4>();
        case 5: return factorBand<5>();
        case 6: return factorBand<6>();
        case 7: return factorBand<7>();
        case 8: return factorBand<8>();
        case 10: return factorBand<10>();
        case 12: return factorBand<12>();
        case 14: return factorBand<14>();
        case 16: return factorBand<16>();
        case 18: return factorBand<18>();
        case 20: return factorBand<20>();
        default: return factorBand<0>();
    }
}

void BandedLU::solve(double* b) const {
    const int band = kl_ + ku_;
    for (int k = 0; k < n_; ++k) {  // L y = P b
        const int p = pivot_[k];
        if (p != k) std::swap(b[k], b[p]);
        const double bk = b[k];
        const int last = std::min(n_ - 1, k + kl_);
        for (int i = k + 1; i <= last; ++i) b[i] -= at(i, k) * bk;
    }
    for (int k = n_ - 1; k >= 0; --k) {  // U x = y
        const int right = std::min(n_ - 1, k + band);
        double sum = b[k];
        for (int j = k + 1; j <= right; ++j) sum -= at(k, j) * b[j];
        b[k] = sum / at(k, k);
    }
}

// The block solve for NR right-hand sides (NR > 0: a compile-time count, so the row updates
// unroll; NR = 0: numRhs at run time). The same operations in the same order either way.
template <int NR>
void BandedLU::solveBlock(double* B, int numRhs) const {
    const int band = kl_ + ku_, nr = NR > 0 ? NR : numRhs;
    for (int k = 0; k < n_; ++k) {  // L Y = P B
        const int p = pivot_[k];
        double* bk = B + static_cast<std::size_t>(k) * nr;
        if (p != k) std::swap_ranges(bk, bk + nr, B + static_cast<std::size_t>(p) * nr);
        const int last = std::min(n_ - 1, k + kl_);
        for (int i = k + 1; i <= last; ++i) {
            const double l = at(i, k);
            if (l != 0.0) axpy(-l, bk, B + static_cast<std::size_t>(i) * nr, nr);
        }
    }
    for (int k = n_ - 1; k >= 0; --k) {  // U X = Y
        const int right = std::min(n_ - 1, k + band);
        double* bk = B + static_cast<std::size_t>(k) * nr;
        for (int j = k + 1; j <= right; ++j) {
            const double u = at(k, j);
            if (u != 0.0) axpy(-u, B + static_cast<std::size_t>(j) * nr, bk, nr);
        }
        const double d = at(k, k);
        for (int r = 0; r < nr; ++r) bk[r] /= d;
    }
}

void BandedLU::solve(double* B, int numRhs) const {
    switch (numRhs) {
        case 1: solve(B); return;
        case 2: solveBlock<2>(B, numRhs); return;
        case 3: solveBlock<3>(B, numRhs); return;
        case 4: solveBlock<4>(B, numRhs); return;
        case 5: solveBlock<5>(B, numRhs); return;
        case 6: solveBlock<6>(B, numRhs); return;
        case 7: solveBlock<7>(B, numRhs); return;
        case 8: solveBlock<8>(B, numRhs); return;
        default: solveBlock<0>(B, numRhs); return;
    }
}

}  // namespace SimbodyReeving
