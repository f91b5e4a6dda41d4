// ChordFrame: orthonormality, exact derivatives (against finite differences), conditioning of
// vertical and horizontal spans, smoothness along a large rotation, and the reversal guard.
#include "SimbodyReeving/element/ChordFrame.h"
#include "support/ExpectThrowMessage.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <random>
#include <stdexcept>

using namespace SimbodyReeving;

namespace {

template <int Dim>
using Vec = Eigen::Matrix<double, Dim, 1>;
template <int Dim>
using Mat = Eigen::Matrix<double, Dim, Dim>;

template <int Dim>
Mat<Dim> frameAt(const Vec<Dim>& e, const Mat<Dim>& ref) {
    ChordFrame<Dim> f;
    computeChordFrame<Dim>(e, Vec<Dim>::Zero(), ref, f);
    return f.A;
}

template <int Dim>
void checkDerivatives(const Vec<Dim>& e, const Vec<Dim>& ed, const Mat<Dim>& ref) {
    ChordFrame<Dim> f;
    computeChordFrame<Dim>(e, ed, ref, f);
    EXPECT_LT((f.A.transpose() * f.A - Mat<Dim>::Identity()).norm(), 1e-14);
    EXPECT_NEAR(f.A.determinant(), 1.0, 1e-14);
    EXPECT_LT((f.A.col(0) - e.normalized()).norm(), 1e-15);
    const double h = 1e-6;
    Mat<Dim> AdotFd = Mat<Dim>::Zero(), AddotFd;
    for (int m = 0; m < Dim; ++m) {
        const Vec<Dim> dm = Vec<Dim>::Unit(m) * h;
        const Mat<Dim> dAFd = (frameAt<Dim>(e + dm, ref) - frameAt<Dim>(e - dm, ref)) / (2 * h);
        EXPECT_LT((f.dA[m] - dAFd).norm(), 1e-8 * (1 + f.dA[m].norm())) << "m=" << m;
        // dAdot[m] = d(Adot)/de_m at fixed edot
        ChordFrame<Dim> fp, fm;
        computeChordFrame<Dim>(e + dm, ed, ref, fp);
        computeChordFrame<Dim>(e - dm, ed, ref, fm);
        // Measured 2.3e-10 against 1.2e-7; bound 1e-8 (1 + |dAdot|), margin 53x.
        EXPECT_LT((f.dAdot[m] - (fp.Adot - fm.Adot) / (2 * h)).norm(), 1e-8 * (1 + f.dAdot[m].norm())) << "m=" << m;
    }
    AdotFd = (frameAt<Dim>(e + h * ed, ref) - frameAt<Dim>(e - h * ed, ref)) / (2 * h);
    EXPECT_LT((f.Adot - AdotFd).norm(), 1e-8 * (1 + f.Adot.norm()));
    const double h2 = 1e-4;
    AddotFd = (frameAt<Dim>(e + h2 * ed, ref) - 2 * f.A + frameAt<Dim>(e - h2 * ed, ref)) / (h2 * h2);
    EXPECT_LT((f.Addot - AddotFd).norm(), 1e-5 * (1 + f.Addot.norm()));
}

}  // namespace

TEST(ChordFrame, OrthonormalWithExactDerivativesPlanar) {
    std::mt19937 rng(1);
    std::uniform_real_distribution<double> u(-1, 1);
    for (int k = 0; k < 20; ++k)
        checkDerivatives<2>(Vec<2>(3 * u(rng), 3 * u(rng)), Vec<2>(u(rng), u(rng)), Mat<2>::Identity());
}

TEST(ChordFrame, OrthonormalWithExactDerivativesSpatial) {
    std::mt19937 rng(2);
    std::uniform_real_distribution<double> u(-1, 1);
    for (int k = 0; k < 20; ++k) {
        const Eigen::Matrix3d ref = makeReferenceFrame(Eigen::Vector3d(u(rng), u(rng), u(rng)));
        const Eigen::Vector3d e = 2.0 * ref.col(0) + Eigen::Vector3d(u(rng), u(rng), u(rng));
        checkDerivatives<3>(e, Eigen::Vector3d(u(rng), u(rng), u(rng)), ref);
    }
}

// A vertical span with its (vertical) reference is exactly as well conditioned as a horizontal
// one: the frame and its derivatives are the same up to the rotation between the two.
TEST(ChordFrame, VerticalSpanAsWellConditionedAsHorizontal) {
    const Eigen::Vector3d horizontal(1, 0, 0), vertical(0, -1, 0);
    const Eigen::Matrix3d refH = makeReferenceFrame(horizontal), refV = makeReferenceFrame(vertical);
    const Eigen::Vector3d tilt(0.1, 0.2, -0.15);
    ChordFrame<3> fh, fv;
    computeChordFrame<3>(Eigen::Vector3d(20 * horizontal + refH * tilt), refH * tilt, refH, fh);
    computeChordFrame<3>(Eigen::Vector3d(20 * vertical + refV * tilt), refV * tilt, refV, fv);
    for (int m = 0; m < 3; ++m) {
        double nh = 0, nv = 0;
        for (int k = 0; k < 3; ++k) {
            nh += fh.dA[k].squaredNorm();
            nv += fv.dA[k].squaredNorm();
        }
        EXPECT_NEAR(std::sqrt(nh), std::sqrt(nv), 1e-12);
    }
    EXPECT_NEAR(fh.Adot.norm(), fv.Adot.norm(), 1e-12);
    EXPECT_NEAR(fh.Addot.norm(), fv.Addot.norm(), 1e-12);
}

// Along a 170-degree swing of the chord away from its reference the frame changes smoothly: the
// change per angle step stays within the minimal rotation's bound |dA/dphi| <= 2 (1 + tan(theta/2))
// (the twist rate grows as the chord nears reversal) and consecutive changes differ by less than 2 %,
// so there is no jump anywhere.
TEST(ChordFrame, SmoothAlongLargeRotation) {
    const Eigen::Matrix3d ref = makeReferenceFrame(Eigen::Vector3d(0, -1, 0), Eigen::Vector3d(0, 0, 1));
    const Eigen::Vector3d axis = Eigen::Vector3d(0.3, 0.2, 1).normalized();
    const int steps = 1700;
    const double dphi = (170.0 / 180.0 * std::acos(-1.0)) / steps;
    Eigen::Matrix3d prev = frameAt<3>(Eigen::Vector3d(0, -5, 0), ref);
    double prevRate = -1;
    for (int k = 1; k <= steps; ++k) {
        const Eigen::Vector3d e = Eigen::AngleAxisd(k * dphi, axis) * Eigen::Vector3d(0, -5, 0);
        const Eigen::Matrix3d A = frameAt<3>(e, ref);
        const double rate = (A - prev).norm() / dphi;
        const double theta = std::acos(std::clamp(e.normalized().dot(ref.col(0)), -1.0, 1.0));
        EXPECT_LT(rate, 2.0 * (1.0 + std::tan(0.5 * theta))) << "k=" << k;
        if (prevRate > 0) {
            EXPECT_NEAR(rate / prevRate, 1.0, 0.02) << "k=" << k;
        }
        prevRate = rate;
        prev = A;
    }
}

TEST(ChordFrame, ReversedChordThrowsDomainError) {
    const Eigen::Matrix3d ref = makeReferenceFrame(Eigen::Vector3d(1, 0, 0));
    EXPECT_THROW_MESSAGE(frameAt<3>(Eigen::Vector3d(-1, 1e-4, 0), ref), std::domain_error,
                         "is reversed against the span's reference direction (1, 0, 0); 1 + cos(angle) = ");
    EXPECT_NO_THROW(frameAt<3>(Eigen::Vector3d(-1, 0.1, 0), ref));
    EXPECT_THROW_MESSAGE(frameAt<3>(Eigen::Vector3d::Zero(), ref), std::domain_error,
                         "ChordFrame: chord e = r2 - r1 = (0 0 0) is zero or not finite");
    EXPECT_THROW_MESSAGE(frameAt<2>(Eigen::Vector2d::Zero(), Eigen::Matrix2d::Identity()), std::domain_error,
                         "ChordFrame: chord e = r2 - r1 = (0 0) is zero or not finite");
}

TEST(ChordFrame, ReferenceFrameHonoursPlaneNormal) {
    const Eigen::Matrix3d ref = makeReferenceFrame(Eigen::Vector3d(3, -4, 0), Eigen::Vector3d(0, 0, 2));
    EXPECT_LT((ref.col(0) - Eigen::Vector3d(0.6, -0.8, 0)).norm(), 1e-15);
    EXPECT_LT((ref.col(2) - Eigen::Vector3d(0, 0, 1)).norm(), 1e-15);
    EXPECT_NEAR(ref.determinant(), 1.0, 1e-15);
    // For in-plane chords the spatial frame equals the planar one.
    const Eigen::Vector2d e2(1.0, 2.0);
    const Eigen::Matrix3d A3 = frameAt<3>(Eigen::Vector3d(e2.x(), e2.y(), 0), ref);
    const Eigen::Matrix2d A2 = frameAt<2>(e2, Eigen::Matrix2d::Identity());
    EXPECT_LT((A3.topLeftCorner<2, 2>() - A2).norm(), 1e-15);
    EXPECT_THROW_MESSAGE(makeReferenceFrame(Eigen::Vector3d::Zero()), std::invalid_argument,
                         "makeReferenceFrame: chordDirection = (0 0 0) must be finite and non-zero");
    EXPECT_THROW_MESSAGE(makeReferenceFrame(Eigen::Vector3d(NAN, 0, 0)), std::invalid_argument,
                         "makeReferenceFrame: chordDirection = (nan");
    EXPECT_THROW_MESSAGE(makeReferenceFrame(Eigen::Vector3d(NAN, 0, 0)), std::invalid_argument,
                         ") must be finite and non-zero");
}
