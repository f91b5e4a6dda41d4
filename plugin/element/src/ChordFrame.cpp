#include "SimbodyReeving/element/ChordFrame.h"

#include <Eigen/Geometry>

#include <cmath>
#include <sstream>
#include <stdexcept>

namespace SimbodyReeving {
namespace {

/// Hyper-dual number v + d1 e1 + d2 e2 + d12 e1 e2 with e1^2 = e2^2 = 0: one evaluation gives the
/// value, two directional derivatives and the mixed second derivative, exactly.
struct HyperDual {
    double v = 0, d1 = 0, d2 = 0, d12 = 0;
};
inline HyperDual operator+(HyperDual a, HyperDual b) { return {a.v + b.v, a.d1 + b.d1, a.d2 + b.d2, a.d12 + b.d12}; }
inline HyperDual operator-(HyperDual a, HyperDual b) { return {a.v - b.v, a.d1 - b.d1, a.d2 - b.d2, a.d12 - b.d12}; }
inline HyperDual operator-(HyperDual a) { return {-a.v, -a.d1, -a.d2, -a.d12}; }
inline HyperDual operator*(HyperDual a, HyperDual b) {
    return {a.v * b.v, a.v * b.d1 + a.d1 * b.v, a.v * b.d2 + a.d2 * b.v,
            a.v * b.d12 + a.d1 * b.d2 + a.d2 * b.d1 + a.d12 * b.v};
}
inline HyperDual operator*(double s, HyperDual a) { return {s * a.v, s * a.d1, s * a.d2, s * a.d12}; }
inline HyperDual operator+(double s, HyperDual a) { return {s + a.v, a.d1, a.d2, a.d12}; }
/// f(a) for scalar f with derivatives f0, f1, f2 at a.v.
inline HyperDual applyScalar(HyperDual a, double f0, double f1, double f2) {
    return {f0, f1 * a.d1, f1 * a.d2, f1 * a.d12 + f2 * a.d1 * a.d2};
}
inline HyperDual reciprocal(HyperDual a) {
    const double r = 1.0 / a.v;
    return applyScalar(a, r, -r * r, 2.0 * r * r * r);
}
inline HyperDual inverseSqrt(HyperDual a) {
    const double r = 1.0 / std::sqrt(a.v);
    return applyScalar(a, r, -0.5 * r * r * r, 0.75 * r * r * r * r * r);
}

using HD = HyperDual;

// Frame for Dim = 2: A = [i, z x i].
void frame(const std::array<HD, 2>& e, const Eigen::Matrix2d&, HD A[2][2]) {
    const HD inv = inverseSqrt(e[0] * e[0] + e[1] * e[1]);
    const HD ix = inv * e[0], iy = inv * e[1];
    A[0][0] = ix;  A[0][1] = -iy;
    A[1][0] = iy;  A[1][1] = ix;
}

// Frame for Dim = 3: A = R(i0 -> i) A0 with the minimal rotation R = c I + [a]x + a a^T/(1+c).
void frame(const std::array<HD, 3>& e, const Eigen::Matrix3d& A0, HD A[3][3]) {
    const HD inv = inverseSqrt(e[0] * e[0] + e[1] * e[1] + e[2] * e[2]);
    const HD i[3] = {inv * e[0], inv * e[1], inv * e[2]};
    const double i0[3] = {A0(0, 0), A0(1, 0), A0(2, 0)};
    const HD c = i0[0] * i[0] + i0[1] * i[1] + i0[2] * i[2];
    if (1.0 + c.v < kMinReferenceAlignment) {
        std::ostringstream msg;
        msg << "ChordFrame: chord direction (" << i[0].v << ", " << i[1].v << ", " << i[2].v
            << ") is reversed against the span's reference direction (" << i0[0] << ", " << i0[1] << ", "
            << i0[2] << "); 1 + cos(angle) = " << 1.0 + c.v << " < " << kMinReferenceAlignment;
        throw std::domain_error(msg.str());
    }
    const HD a[3] = {i0[1] * i[2] - i0[2] * i[1], i0[2] * i[0] - i0[0] * i[2], i0[0] * i[1] - i0[1] * i[0]};
    const HD k = reciprocal(1.0 + c);
    HD R[3][3];
    for (int r = 0; r < 3; ++r)
        for (int s = 0; s < 3; ++s) R[r][s] = k * (a[r] * a[s]);
    for (int r = 0; r < 3; ++r) R[r][r] = R[r][r] + c;
    R[0][1] = R[0][1] - a[2];  R[0][2] = R[0][2] + a[1];
    R[1][0] = R[1][0] + a[2];  R[1][2] = R[1][2] - a[0];
    R[2][0] = R[2][0] - a[1];  R[2][1] = R[2][1] + a[0];
    for (int r = 0; r < 3; ++r)
        for (int s = 0; s < 3; ++s)
            A[r][s] = A0(0, s) * R[r][0] + A0(1, s) * R[r][1] + A0(2, s) * R[r][2];
}

}  // namespace

template <int Dim>
void computeChordFrame(const Eigen::Matrix<double, Dim, 1>& e, const Eigen::Matrix<double, Dim, 1>& edot,
                       const Eigen::Matrix<double, Dim, Dim>& reference, ChordFrame<Dim>& out) {
    if (!(e.squaredNorm() > 0.0) || !e.allFinite()) {
        std::ostringstream msg;
        msg << "ChordFrame: chord e = r2 - r1 = (" << e.transpose() << ") is zero or not finite";
        throw std::domain_error(msg.str());
    }
    out.Addot.setZero();
    for (int m = 0; m < Dim; ++m) {
        std::array<HD, Dim> eh;
        for (int k = 0; k < Dim; ++k) eh[k] = HD{e[k], k == m ? 1.0 : 0.0, edot[k], 0.0};
        HD A[Dim][Dim];
        frame(eh, reference, A);
        for (int r = 0; r < Dim; ++r)
            for (int s = 0; s < Dim; ++s) {
                out.A(r, s) = A[r][s].v;
                out.dA[m](r, s) = A[r][s].d1;
                out.Adot(r, s) = A[r][s].d2;
                out.dAdot[m](r, s) = A[r][s].d12;
            }
        out.Addot += edot[m] * out.dAdot[m];
    }
}

template void computeChordFrame<2>(const Eigen::Vector2d&, const Eigen::Vector2d&, const Eigen::Matrix2d&,
                                   ChordFrame<2>&);
template void computeChordFrame<3>(const Eigen::Vector3d&, const Eigen::Vector3d&, const Eigen::Matrix3d&,
                                   ChordFrame<3>&);

double referenceAlignment(const Eigen::Vector3d& e, const Eigen::Matrix3d& reference) {
    const double n = e.norm();
    if (!(n > 0.0) || !e.allFinite()) {
        std::ostringstream msg;
        msg << "referenceAlignment: chord e = (" << e.transpose() << ") is zero or not finite";
        throw std::domain_error(msg.str());
    }
    return 1.0 + reference.col(0).dot(e) / n;
}

void reReferenceTransverseModes(const Eigen::Vector3d& e, const Eigen::Vector3d& edot,
                                const Eigen::Matrix3d& oldReference, const Eigen::Matrix3d& newReference,
                                bool completeVelocity, Eigen::Ref<Eigen::VectorXd> b, Eigen::Ref<Eigen::VectorXd> c,
                                Eigen::Ref<Eigen::VectorXd> bdot, Eigen::Ref<Eigen::VectorXd> cdot) {
    const Eigen::Index n = b.size();
    if (c.size() != n || bdot.size() != n || cdot.size() != n)
        throw std::invalid_argument("reReferenceTransverseModes: b, c, bdot, cdot must have the same size (sizes " +
                                    std::to_string(n) + ", " + std::to_string(c.size()) + ", " +
                                    std::to_string(bdot.size()) + ", " + std::to_string(cdot.size()) + ")");
    ChordFrame<3> from, to;
    computeChordFrame<3>(e, edot, oldReference, from);
    computeChordFrame<3>(e, edot, newReference, to);
    const Eigen::Matrix<double, 3, 2> J0 = from.A.rightCols<2>(), J1 = to.A.rightCols<2>();
    const Eigen::Matrix<double, 3, 2> J0dot = from.Adot.rightCols<2>(), J1dot = to.Adot.rightCols<2>();
    for (Eigen::Index i = 0; i < n; ++i) {
        const Eigen::Vector2d q0(b[i], c[i]), q0dot(bdot[i], cdot[i]);
        const Eigen::Vector3d w = J0 * q0;  // displacement of mode i, normal to the chord
        Eigen::Vector3d wdot = J0 * q0dot;  // its velocity (Simplified: without the frame's rotation)
        if (completeVelocity) wdot += J0dot * q0;
        const Eigen::Vector2d q1 = J1.transpose() * w;
        Eigen::Vector3d rest = wdot;
        if (completeVelocity) rest -= J1dot * q1;
        const Eigen::Vector2d q1dot = J1.transpose() * rest;
        b[i] = q1[0];
        c[i] = q1[1];
        bdot[i] = q1dot[0];
        cdot[i] = q1dot[1];
    }
}

Eigen::Matrix3d makeReferenceFrame(const Eigen::Vector3d& chordDirection, const Eigen::Vector3d& normalHint) {
    const double n = chordDirection.norm();
    if (!(n > 0.0) || !chordDirection.allFinite()) {
        std::ostringstream msg;
        msg << "makeReferenceFrame: chordDirection = (" << chordDirection.transpose()
            << ") must be finite and non-zero";
        throw std::invalid_argument(msg.str());
    }
    const Eigen::Vector3d i0 = chordDirection / n;
    Eigen::Vector3d j0, k0;
    Eigen::Vector3d kHint = normalHint.allFinite() ? Eigen::Vector3d(normalHint - normalHint.dot(i0) * i0)
                                                   : Eigen::Vector3d::Zero();
    if (kHint.norm() > 1e-6 * normalHint.norm() && kHint.norm() > 0.0) {
        k0 = kHint.normalized();
        j0 = k0.cross(i0);
    } else {
        int axis = 0;
        i0.cwiseAbs().minCoeff(&axis);
        Eigen::Vector3d a = Eigen::Vector3d::Unit(axis);
        j0 = (a - a.dot(i0) * i0).normalized();
        k0 = i0.cross(j0);
    }
    Eigen::Matrix3d A0;
    A0 << i0, j0, k0;
    return A0;
}

}  // namespace SimbodyReeving
