#include "StoredRope.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace SimbodyReeving::detail {

template <int Dim>
void StoredRope<Dim>::evaluate(const Eigen::VectorXd& x, const Eigen::VectorXd& xdot, double s, double sdot,
                               StoredRopeTerms<Dim>& out) const {
    if (turningAxis_)
        evaluateTurningAxis(x, xdot, s, sdot, out);
    else if (isWrapped())
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

// The Lagrangian in q = (c, phi, s) (see the class comment), then carried to x = (c, T, s) by
// phi = atan2(w . r, up . r), r = T - c, up and w = n x up the groove plane's "up" and its normal
// in the plane: P = dq/dx, and phi's quadratic-velocity term (a = up . r, b = w . r)
//     phiddot = (a bddot - b addot) / (a^2 + b^2) - 2 (a adot + b bdot)(a bdot - b adot) / (a^2 + b^2)^2.
// The groove's axis n is constant (a planar rope's +z; a spatial rope's from x, its rates not read).
template <int Dim>
void StoredRope<Dim>::evaluateWrapped(const Eigen::VectorXd& x, const Eigen::VectorXd& xdot, double s, double sdot,
                                      StoredRopeTerms<Dim>& out) const {
    constexpr int nq = Dim + 2, nx = 2 * Dim + 1;
    using V = Eigen::Matrix<double, Dim, 1>;
    const double R = radius_, sigma = sense_, kappa = slope_, rhoA = rhoA_;
    const double l = length(s), m = rhoA * l;
    V up, w;
    double gPlane = 0;  // |g| in the groove's plane
    if constexpr (Dim == 2) {
        const double gn = gravity_.norm();
        up = gn > 0 ? V(-gravity_ / gn) : V(0.0, 1.0);
        w = V(-up[1], up[0]);
        gPlane = gn;
    } else {
        const Eigen::Vector3d n = x.template segment<3>(axisOffset_).normalized();
        const Eigen::Vector3d gp = gravity_ - n * n.dot(gravity_);
        // (A groove whose axis is along gravity has no "up" in its plane: the station map refuses a
        // grip there; any in-plane direction serves this law, whose gravity terms then vanish.)
        up = gp.norm() > 1e-12 * std::max(1.0, gravity_.norm()) ? Eigen::Vector3d(-gp / gp.norm()) : n.unitOrthogonal();
        w = n.cross(up);
        gPlane = gp.norm();
    }
    const V c = x.template segment<Dim>(centreOffset_), cdot = xdot.template segment<Dim>(centreOffset_);
    const V r = x.template segment<Dim>(tangentOffset_) - c, rdot = xdot.template segment<Dim>(tangentOffset_) - cdot;
    const double a = up.dot(r), b = w.dot(r), adot = up.dot(rdot), bdot = w.dot(rdot), rr = a * a + b * b;
    const double phi = std::atan2(b, a);
    const double phidot = (a * bdot - b * adot) / rr;
    const double phiBias = -2 * (a * adot + b * bdot) * (a * bdot - b * adot) / (rr * rr);
    const V dphidr = (a * w - b * up) / rr;
    const double psiE = phi - sigma * kappa * l / R;
    auto u = [&](double t) { return V(std::cos(t) * up + std::sin(t) * w); };
    auto du = [&](double t) { return V(-std::sin(t) * up + std::cos(t) * w); };
    const V D = u(phi) - u(psiE);
    // mutation-site: ring-speed
    const double v = sdot - sigma * R * phidot;  // the drum's surface speed
    const double psiEdot = -sigma * v / R;
    const V Ddot = du(phi) * phidot - du(psiE) * psiEdot;

    // Mass in q = (c, phi, s).
    Eigen::Matrix<double, nq, nq> Mq = Eigen::Matrix<double, nq, nq>::Zero();
    Mq.template topLeftCorner<Dim, Dim>().diagonal().setConstant(m);
    Mq.template block<Dim, 1>(0, Dim) = rhoA * sigma * kappa * R * R * D;
    Mq.template block<Dim, 1>(0, Dim + 1) = -rhoA * kappa * R * D;
    Mq(Dim, Dim) = m * R * R;
    Mq(Dim, Dim + 1) = -m * sigma * R;
    Mq(Dim + 1, Dim + 1) = m;
    Mq.template block<1, Dim>(Dim, 0) = Mq.template block<Dim, 1>(0, Dim).transpose();
    Mq.template block<1, Dim>(Dim + 1, 0) = Mq.template block<Dim, 1>(0, Dim + 1).transpose();
    Mq(Dim + 1, Dim) = Mq(Dim, Dim + 1);
    // h_q = dT/dq - dU/dq - (dp/dq) qdot.
    const double dTdphi = -rhoA * R * kappa * v * cdot.dot(du(phi) - du(psiE));
    const double dTds = 0.5 * rhoA * kappa * (cdot.squaredNorm() + v * v) - rhoA * kappa * sigma * v * cdot.dot(du(psiE));
    const V dUdc = -m * gravity_;
    const double dUdphi = rhoA * gPlane * sigma * kappa * R * R * (std::cos(phi) - std::cos(psiE));
    const double dUds = -rhoA * kappa * gravity_.dot(c) + rhoA * gPlane * kappa * R * std::cos(psiE);
    const V Bc = rhoA * (kappa * sdot * cdot - R * kappa * v * Ddot);
    const double Bs = rhoA * (kappa * sdot * v - R * kappa * cdot.dot(Ddot));
    const double Bphi = -sigma * R * Bs;
    Eigen::Matrix<double, nq, 1> hq;
    hq.template head<Dim>() = -dUdc - Bc;
    hq[Dim] = dTdphi - dUdphi - Bphi;
    hq[Dim + 1] = dTds - dUds - Bs;
    // Carried to x = (c, T, s).
    Eigen::Matrix<double, nq, nx> P = Eigen::Matrix<double, nq, nx>::Zero();
    P.template topLeftCorner<Dim, Dim>().setIdentity();
    P.template block<1, Dim>(Dim, Dim) = dphidr.transpose();
    P.template block<1, Dim>(Dim, 0) = -dphidr.transpose();
    P(Dim + 1, 2 * Dim) = 1;
    Eigen::Matrix<double, nq, 1> beta = Eigen::Matrix<double, nq, 1>::Zero();
    beta[Dim] = phiBias;
    out.count = nx;
    for (int d = 0; d < Dim; ++d) {
        out.cols[d] = centreOffset_ + d;
        out.cols[Dim + d] = tangentOffset_ + d;
    }
    out.cols[2 * Dim] = materialOffset_;
    out.mass.setZero();
    out.mass.template topLeftCorner<nx, nx>().noalias() = P.transpose() * Mq * P;
    out.force.setZero();
    out.force.template head<nx>().noalias() = P.transpose() * (hq - Mq * beta);
    Eigen::Matrix<double, nq, 1> qdot;
    qdot << cdot, phidot, sdot;
    out.kineticEnergy = 0.5 * qdot.dot(Mq * qdot);
    out.gravityEnergy = -m * gravity_.dot(c) + rhoA * gPlane * sigma * kappa * R * R * (std::sin(phi) - std::sin(psiE));
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
