#include "StoredRope.h"

#include <cmath>
#include <stdexcept>

namespace SimbodyReeving::detail {

template <int Dim>
void StoredRope<Dim>::evaluate(const Eigen::VectorXd& x, const Eigen::VectorXd& xdot, double s, double sdot,
                               StoredRopeTerms<Dim>& out) const {
    if (isWrapped())
        evaluateWrapped(x, xdot, s, sdot, out);
    else
        evaluatePoint(x, xdot, s, sdot, out);
}

// L = 1/2 rhoA l (|rdot|^2 + sdot^2) + rhoA l g.r, l = l0 + kappa s:
//     rhoA l rddot = rhoA l g - rhoA kappa sdot rdot + f_r,
//     rhoA l sddot = rhoA kappa (1/2 |rdot|^2 - 1/2 sdot^2 + g.r) + f_s.
template <int Dim>
void StoredRope<Dim>::evaluatePoint(const Eigen::VectorXd& x, const Eigen::VectorXd& xdot, double s, double sdot,
                                    StoredRopeTerms<Dim>& out) const {
    const double l = length(s), m = rhoA_ * l;
    const Vec r = x.template segment<Dim>(centreOffset_), rdot = xdot.template segment<Dim>(centreOffset_);
    out.count = Dim + 1;
    out.mass.setZero();
    out.force.setZero();
    for (int d = 0; d < Dim; ++d) {
        out.cols[d] = centreOffset_ + d;
        out.mass(d, d) = m;
        out.force[d] = m * gravity_[d] - rhoA_ * slope_ * sdot * rdot[d];
    }
    out.cols[Dim] = materialOffset_;
    out.mass(Dim, Dim) = m;
    out.force[Dim] = rhoA_ * slope_ * (0.5 * rdot.squaredNorm() - 0.5 * sdot * sdot + gravity_.dot(r));
    out.kineticEnergy = 0.5 * m * (rdot.squaredNorm() + sdot * sdot);
    out.gravityEnergy = -m * gravity_.dot(r);
}

namespace {
// "Up" in the plane (against gravity; +y without gravity) and its counter-clockwise normal.
void planeUp(const Eigen::Vector2d& g, Eigen::Vector2d& up, Eigen::Vector2d& upPerp) {
    const double gn = g.norm();
    up = gn > 0 ? Eigen::Vector2d(-g / gn) : Eigen::Vector2d(0.0, 1.0);
    upPerp = Eigen::Vector2d(-up[1], up[0]);
}
}  // namespace

// The Lagrangian in q = (c, phi, s) (see the class comment), then carried to x = (c, T, s) by
// phi = angle of T - c from up: P = dq/dx, and phi's quadratic-velocity term
//     phiddot = (r x rddot) / |r|^2 - 2 (r . rdot)(r x rdot) / |r|^4,  r = T - c.
template <int Dim>
void StoredRope<Dim>::evaluateWrapped(const Eigen::VectorXd& x, const Eigen::VectorXd& xdot, double s, double sdot,
                                      StoredRopeTerms<Dim>& out) const {
    if constexpr (Dim != 2) {
        (void)x, (void)xdot, (void)s, (void)sdot, (void)out;
        throw std::invalid_argument("StoredRope: a wrapped drum's stored rope is built for planar ropes");
    } else {
        using V2 = Eigen::Vector2d;
        const double R = radius_, sigma = sense_, kappa = slope_, rhoA = rhoA_;
        const double l = length(s), m = rhoA * l, gmag = gravity_.norm();
        V2 up, upPerp;
        planeUp(gravity_, up, upPerp);
        const V2 c = x.segment<2>(centreOffset_), cdot = xdot.segment<2>(centreOffset_);
        const V2 r = x.segment<2>(tangentOffset_) - c, rdot = xdot.segment<2>(tangentOffset_) - cdot;
        const double rr = r.squaredNorm();
        const double cross = r[0] * rdot[1] - r[1] * rdot[0];
        const double phi = std::atan2(up[0] * r[1] - up[1] * r[0], up.dot(r));
        const double phidot = cross / rr;
        const double phiBias = -2 * r.dot(rdot) * cross / (rr * rr);
        const double psiE = phi - sigma * kappa * l / R;
        auto u = [&](double a) { return V2(std::cos(a) * up + std::sin(a) * upPerp); };
        auto du = [&](double a) { return V2(-std::sin(a) * up + std::cos(a) * upPerp); };
        const V2 D = u(phi) - u(psiE);
        const double v = sdot - sigma * R * phidot;  // the drum's surface speed
        const double psiEdot = -sigma * v / R;
        const V2 Ddot = du(phi) * phidot - du(psiE) * psiEdot;

        // Mass in q = (c0, c1, phi, s).
        Eigen::Matrix4d Mq = Eigen::Matrix4d::Zero();
        Mq(0, 0) = Mq(1, 1) = m;
        Mq.block<2, 1>(0, 2) = rhoA * sigma * kappa * R * R * D;
        Mq.block<2, 1>(0, 3) = -rhoA * kappa * R * D;
        Mq(2, 2) = m * R * R;
        Mq(2, 3) = -m * sigma * R;
        Mq(3, 3) = m;
        Mq.block<1, 2>(2, 0) = Mq.block<2, 1>(0, 2).transpose();
        Mq.block<1, 2>(3, 0) = Mq.block<2, 1>(0, 3).transpose();
        Mq(3, 2) = Mq(2, 3);
        // h_q = dT/dq - dU/dq - (dp/dq) qdot.
        const V2 dTdc = V2::Zero();
        const double dTdphi = -rhoA * R * kappa * v * cdot.dot(du(phi) - du(psiE));
        const double dTds = 0.5 * rhoA * kappa * (cdot.squaredNorm() + v * v) - rhoA * kappa * sigma * v * cdot.dot(du(psiE));
        const V2 dUdc = -m * gravity_;
        const double dUdphi = rhoA * gmag * sigma * kappa * R * R * (std::cos(phi) - std::cos(psiE));
        const double dUds = -rhoA * kappa * gravity_.dot(c) + rhoA * gmag * kappa * R * std::cos(psiE);
        const V2 Bc = rhoA * (kappa * sdot * cdot - R * kappa * v * Ddot);
        const double Bs = rhoA * (kappa * sdot * v - R * kappa * cdot.dot(Ddot));
        const double Bphi = -sigma * R * Bs;
        Eigen::Vector4d hq;
        hq.head<2>() = dTdc - dUdc - Bc;
        hq[2] = dTdphi - dUdphi - Bphi;
        hq[3] = dTds - dUds - Bs;
        // Carried to x = (c0, c1, T0, T1, s).
        Eigen::Matrix<double, 4, 5> P = Eigen::Matrix<double, 4, 5>::Zero();
        P(0, 0) = P(1, 1) = 1;
        const V2 dphidT(-r[1] / rr, r[0] / rr);
        P.block<1, 2>(2, 2) = dphidT.transpose();
        P.block<1, 2>(2, 0) = -dphidT.transpose();
        P(3, 4) = 1;
        Eigen::Vector4d beta(0, 0, phiBias, 0);
        out.count = 5;
        out.cols = {centreOffset_, centreOffset_ + 1, tangentOffset_, tangentOffset_ + 1, materialOffset_};
        out.mass.setZero();
        out.mass.template topLeftCorner<5, 5>().noalias() = P.transpose() * Mq * P;
        out.force.setZero();
        out.force.template head<5>().noalias() = P.transpose() * (hq - Mq * beta);
        const Eigen::Vector4d qdot(cdot[0], cdot[1], phidot, sdot);
        out.kineticEnergy = 0.5 * qdot.dot(Mq * qdot);
        out.gravityEnergy = -m * gravity_.dot(c) + rhoA * gmag * sigma * kappa * R * R * (std::sin(phi) - std::sin(psiE));
    }
}

template <int Dim>
double StoredRope<Dim>::gravityEnergy(const Eigen::VectorXd& x, double s) const {
    StoredRopeTerms<Dim> t;
    const Eigen::VectorXd zero = Eigen::VectorXd::Zero(x.size());
    evaluate(x, zero, s, 0.0, t);
    return t.gravityEnergy;
}

template class StoredRope<2>;
template class StoredRope<3>;

}  // namespace SimbodyReeving::detail
