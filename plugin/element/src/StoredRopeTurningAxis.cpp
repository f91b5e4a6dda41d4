// The rope stored on a wrapped drum whose axis turns (StoredRope::setTurningAxis; the law is
// stated in StoredRope.h): kinetic energy T = 1/2 V^T K V of the stored rope's velocity
// components V = G ydot, V = (cdot, Omega_s, Omega_perp), and gravity energy U, in the coordinates
// y = (c, T, n, s). Forward automatic differentiation over y (fixed size: no allocation) gives
//     mass = G^T K G,   force = dT/dy - (d(G^T K G ydot)/dy) ydot - dU/dy.
#include "StoredRope.h"

#include <unsupported/Eigen/AutoDiff>

#include <Eigen/Geometry>

#include <cmath>
#include <stdexcept>

namespace SimbodyReeving::detail {

namespace {

constexpr int kCoordinates = 10;  // c (3), T (3), n (3), s
using Derivatives = Eigen::Matrix<double, kCoordinates, 1>;
using Ad = Eigen::AutoDiffScalar<Derivatives>;
using AdVec3 = Eigen::Matrix<Ad, 3, 1>;

AdVec3 cross(const AdVec3& a, const AdVec3& b) {
    return AdVec3(a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]);
}
Ad dot(const AdVec3& a, const AdVec3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
AdVec3 constant(const Eigen::Vector3d& v) { return AdVec3(Ad(v[0]), Ad(v[1]), Ad(v[2])); }

}  // namespace

template <>
void StoredRope<3>::evaluateTurningAxis(const Eigen::VectorXd& x, const Eigen::VectorXd& xdot, double s, double sdot,
                                        StoredRopeTerms<3>& out) const {
    const double R = radius_, sigma = sense_, kappa = slope_, rhoA = rhoA_;
    // y and ydot: c, T, n, s.
    Eigen::Matrix<double, kCoordinates, 1> y, ydot;
    y << x.segment<3>(centreOffset_), x.segment<3>(tangentOffset_), x.segment<3>(axisOffset_), s;
    ydot << xdot.segment<3>(centreOffset_), xdot.segment<3>(tangentOffset_), xdot.segment<3>(axisOffset_), sdot;
    Eigen::Matrix<Ad, kCoordinates, 1> Y;
    for (int i = 0; i < kCoordinates; ++i) Y[i] = Ad(y[i], kCoordinates, i);
    const AdVec3 c = Y.segment<3>(0), T = Y.segment<3>(3), n = Y.segment<3>(6);
    const Ad& sk = Y[9];

    // The tangent point's radial e, f = n x e, and the stored arc from there: length l, turned by
    // Delta = -sigma kappa l / R about n (u(t) = cos t e + sin t f, dlambda = -sigma kappa R dt).
    // (T - c projected onto the groove's plane: a drum's groove placement may put its tangent
    // point along n from c, NodeWrap::groove; the stored ring stays in c's plane.)
    const AdVec3 r = T - c;
    const AdVec3 e = (r - n * n.dot(r)) / R, f = cross(n, e);
    const Ad l = lengthAtZero_ + kappa * sk;
    const Ad delta = -sigma * kappa * l / R;
    const double scale = -sigma * kappa * R;
    const Ad sinD = sin(delta), cosD = cos(delta), sin2D = sin(2.0 * delta);
    const AdVec3 I1 = scale * (sinD * e + (1.0 - cosD) * f);
    const Ad C2 = 0.5 * delta + 0.25 * sin2D, S2 = 0.5 * delta - 0.25 * sin2D, X2 = 0.5 * sinD * sinD;
    Eigen::Matrix<Ad, 3, 3> I2;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) I2(i, j) = scale * (C2 * e[i] * e[j] + S2 * f[i] * f[j] + X2 * (e[i] * f[j] + f[i] * e[j]));
    const AdVec3 k = cross(n, I1);

    // G (7 x 10): cdot; Omega_s = f . (Tdot - cdot) / R - (f . ndot)(n . (T - c)) / R - sigma sdot / R
    // (the rate of the projected radial R e; the last but one term 0 unless the tangent point
    // lies off c's plane, a drum spooling across its width); Omega_perp = n x ndot.
    Eigen::Matrix<Ad, 7, kCoordinates> G;
    for (int i = 0; i < 7; ++i)
        for (int j = 0; j < kCoordinates; ++j) G(i, j) = Ad(0.0);
    const Ad axial = n.dot(r);
    for (int i = 0; i < 3; ++i) {
        G(i, i) = Ad(1.0);
        G(3, 3 + i) = f[i] / R;
        G(3, i) = -f[i] / R;
        G(3, 6 + i) = -f[i] * axial / R;
    }
    G(3, 9) = Ad(-sigma / R);
    // n x ndot = [n]x ndot.
    G(4, 7) = -n[2];
    G(4, 8) = n[1];
    G(5, 6) = n[2];
    G(5, 8) = -n[0];
    G(6, 6) = -n[1];
    G(6, 7) = n[0];

    // K (7 x 7), rhoA times [[l 1, R k, -R [I1]x], [R k^T, R^2 l, 0], [R [I1]x, 0, R^2 (l 1 - I2)]].
    Eigen::Matrix<Ad, 7, 7> K;
    for (int i = 0; i < 7; ++i)
        for (int j = 0; j < 7; ++j) K(i, j) = Ad(0.0);
    Eigen::Matrix<Ad, 3, 3> I1x;
    I1x << Ad(0.0), -I1[2], I1[1], I1[2], Ad(0.0), -I1[0], -I1[1], I1[0], Ad(0.0);
    for (int i = 0; i < 3; ++i) {
        K(i, i) = l;
        K(i, 3) = R * k[i];
        K(3, i) = R * k[i];
        for (int j = 0; j < 3; ++j) {
            K(i, 4 + j) = -R * I1x(i, j);
            K(4 + j, i) = -R * I1x(i, j);
            K(4 + i, 4 + j) = -R * R * I2(i, j) + (i == j ? R * R * l : Ad(0.0));
        }
    }
    K(3, 3) = R * R * l;
    K *= Ad(rhoA);

    // V = G ydot, p = G^T K V (= dT/dydot), T = 1/2 V . K V.
    Eigen::Matrix<Ad, 7, 1> V, KV;
    for (int i = 0; i < 7; ++i) {
        V[i] = Ad(0.0);
        for (int j = 0; j < kCoordinates; ++j) V[i] += G(i, j) * ydot[j];
    }
    for (int i = 0; i < 7; ++i) {
        KV[i] = Ad(0.0);
        for (int j = 0; j < 7; ++j) KV[i] += K(i, j) * V[j];
    }
    Ad kinetic(0.0);
    for (int i = 0; i < 7; ++i) kinetic += 0.5 * V[i] * KV[i];
    Eigen::Matrix<Ad, kCoordinates, 1> p;
    for (int j = 0; j < kCoordinates; ++j) {
        p[j] = Ad(0.0);
        for (int i = 0; i < 7; ++i) p[j] += G(i, j) * KV[i];
    }
    const AdVec3 g = constant(gravity_);
    const Ad potential = -rhoA * (l * dot(g, c) + R * dot(g, I1));

    // Mass G^T K G (values), force dT/dy - (dp/dy) ydot - dU/dy.
    Eigen::Matrix<double, 7, kCoordinates> Gv;
    Eigen::Matrix<double, 7, 7> Kv;
    for (int i = 0; i < 7; ++i) {
        for (int j = 0; j < kCoordinates; ++j) Gv(i, j) = G(i, j).value();
        for (int j = 0; j < 7; ++j) Kv(i, j) = K(i, j).value();
    }
    out.count = kCoordinates;
    for (int d = 0; d < 3; ++d) {
        out.cols[d] = centreOffset_ + d;
        out.cols[3 + d] = tangentOffset_ + d;
        out.cols[6 + d] = axisOffset_ + d;
    }
    out.cols[9] = materialOffset_;
    out.mass.setZero();
    out.mass.topLeftCorner<kCoordinates, kCoordinates>().noalias() = Gv.transpose() * Kv * Gv;
    out.force.setZero();
    for (int j = 0; j < kCoordinates; ++j)
        out.force[j] = kinetic.derivatives()[j] - p[j].derivatives().dot(ydot) - potential.derivatives()[j];
    out.kineticEnergy = kinetic.value();
    out.gravityEnergy = potential.value();
}

template <>
void StoredRope<2>::evaluateTurningAxis(const Eigen::VectorXd&, const Eigen::VectorXd&, double, double,
                                        StoredRopeTerms<2>&) const {
    throw std::logic_error("StoredRope: a turning drum axis needs a spatial rope");
}

}  // namespace SimbodyReeving::detail
