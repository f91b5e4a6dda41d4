#include "SimbodyReeving/element/GrooveArc.h"

#include <Eigen/Geometry>
#include <unsupported/Eigen/AutoDiff>

#include <cmath>
#include <sstream>
#include <stdexcept>

namespace SimbodyReeving {
namespace {

template <int Dim, class S>
using VecOf = Eigen::Matrix<S, Dim, 1>;

// n_e x v for the groove's signed axis n_e = sigma n: in the plane (Dim = 2) n = +z.
template <class S>
VecOf<3, S> turn(const VecOf<3, S>& ne, int /*sigma*/, const VecOf<3, S>& v) {
    return ne.cross(v);
}
template <class S>
VecOf<2, S> turn(const VecOf<3, S>& /*ne*/, int sigma, const VecOf<2, S>& v) {
    return VecOf<2, S>(-sigma * v[1], sigma * v[0]);
}
// a x b of two Dim-vectors, as a Dim-vector of the axis-coordinate block: in 3D the cross product;
// unused in the plane (no axis coordinates).
template <class S>
VecOf<3, S> crossForAxis(const VecOf<3, S>& a, const VecOf<3, S>& b) {
    return a.cross(b);
}

// The integrals of 1, cos, sin, cos^2, sin^2, cos sin over theta in [0, alpha].
template <class S>
struct ArcIntegrals {
    S one, c, s, cc, ss, cs;
    explicit ArcIntegrals(const S& alpha) {
        using std::cos;
        using std::sin;
        const S sa = sin(alpha), ca = cos(alpha), s2 = sin(2.0 * alpha);
        one = alpha;
        c = sa;
        s = 1.0 - ca;
        cc = 0.5 * alpha + 0.25 * s2;
        ss = 0.5 * alpha - 0.25 * s2;
        cs = 0.5 * sa * sa;
    }
};

// The arc's geometry and velocity amplitudes at (x, xdot) with x of scalar type S (double, or an
// automatic-differentiation scalar for the derivatives with respect to x).
template <int Dim, class S>
struct ArcState {
    using Arc = GrooveArc<Dim>;
    VecOf<Dim, S> c, d, ndCross;  // centre, d = T - c, n_e x d
    VecOf<3, S> ne = VecOf<3, S>(S(0), S(0), S(1));
    S alpha;
    VecOf<Dim, S> A0, A1, A2;  // rdot = A0 + cos(theta) A1 + sin(theta) A2

    template <class X, class XDot>
    ArcState(const X& x, const XDot& xdot, double radius, int sigma) {
        c = x.template segment<Dim>(Arc::centreIndex());
        d = x.template segment<Dim>(Arc::tangentPointIndex()) - c;
        if constexpr (Dim == 3) ne = double(sigma) * x.template segment<3>(Arc::axisIndex());
        ndCross = turn<S>(ne, sigma, d);
        alpha = x[Arc::lengthIndex()] / radius;
        const VecOf<Dim, S> cdot = xdot.template segment<Dim>(Arc::centreIndex()).template cast<S>();
        const VecOf<Dim, S> ddot = xdot.template segment<Dim>(Arc::tangentPointIndex()).template cast<S>() - cdot;
        const S rate = S(xdot[Arc::materialIndex()] / radius);
        A0 = cdot;
        A1 = ddot - rate * ndCross;
        A2 = turn<S>(ne, sigma, ddot) + rate * d;
        if constexpr (Dim == 3) {
            const VecOf<3, S> nedot = double(sigma) * xdot.template segment<3>(Arc::axisIndex()).template cast<S>();
            A2 += nedot.cross(d);
        }
    }
};

template <int Dim, class S>
using CoordinatesOf = Eigen::Matrix<S, GrooveArcData<Dim>::kNumCoordinates, 1>;

// g(x) = M(x) xdot (its Jacobian G gives Mdot xdot = G xdot and dT/dx = 1/2 G^T xdot).
template <int Dim, class S, class X, class XDot>
CoordinatesOf<Dim, S> massTimesVelocity(const X& x, const XDot& xdot, double rhoA, double radius, int sigma) {
    using Arc = GrooveArc<Dim>;
    const ArcState<Dim, S> st(x, xdot, radius, sigma);
    const ArcIntegrals<S> I(st.alpha);
    const VecOf<Dim, S> y0 = I.one * st.A0 + I.c * st.A1 + I.s * st.A2;
    const VecOf<Dim, S> y1 = I.c * st.A0 + I.cc * st.A1 + I.cs * st.A2;
    const VecOf<Dim, S> y2 = I.s * st.A0 + I.cs * st.A1 + I.ss * st.A2;
    CoordinatesOf<Dim, S> g = CoordinatesOf<Dim, S>::Constant(S(0));
    // B_0 = [I 0 0 0 0]; B_1 = [-I I 0 -(n_e x d)/R 0]; B_2 = [-[n_e]x [n_e]x -sigma [d]x d/R 0].
    const VecOf<Dim, S> ney2 = turn<S>(st.ne, sigma, y2);
    g.template segment<Dim>(Arc::centreIndex()) = y0 - y1 + ney2;
    g.template segment<Dim>(Arc::tangentPointIndex()) = y1 - ney2;
    if constexpr (Dim == 3) g.template segment<3>(Arc::axisIndex()) = double(sigma) * crossForAxis<S>(st.d, y2);
    g[Arc::materialIndex()] = (st.d.dot(y2) - st.ndCross.dot(y1)) / radius;
    g *= rhoA * radius;
    return g;
}

template <int Dim, class S, class X>
S gravityEnergyOf(const X& x, const VecOf<Dim, double>& gravity, double rhoA, double radius, int sigma) {
    using std::cos;
    using std::sin;
    const CoordinatesOf<Dim, double> zero = CoordinatesOf<Dim, double>::Zero();
    const ArcState<Dim, S> st(x, zero, radius, sigma);
    const VecOf<Dim, S> moment = st.alpha * st.c + sin(st.alpha) * st.d + (1.0 - cos(st.alpha)) * st.ndCross;
    return -rhoA * radius * gravity.template cast<S>().dot(moment);
}

template <int Dim>
void checkState(const typename GrooveArc<Dim>::Coordinates& x, const typename GrooveArc<Dim>::Coordinates* xdot) {
    if (!x.allFinite() || (xdot && !xdot->allFinite()))
        throw std::invalid_argument("GrooveArc: the coordinates and their rates must be finite");
    const double l = x[GrooveArc<Dim>::lengthIndex()];
    if (l < 0) {
        std::ostringstream msg;
        msg << "GrooveArc: the arc length l = " << l << " m must be >= 0";
        throw std::invalid_argument(msg.str());
    }
}

}  // namespace

template <int Dim>
GrooveArc<Dim>::GrooveArc(const RopeProperties& properties, double radius, int wrapSense, const Vec& gravity)
    : massPerLength_(properties.massPerLength), radius_(radius), wrapSense_(wrapSense), gravity_(gravity) {
    validate(properties);
    if (!std::isfinite(radius) || !(radius > 0)) {
        std::ostringstream msg;
        msg << "GrooveArc: radius R = " << radius << " m must be finite and > 0";
        throw std::invalid_argument(msg.str());
    }
    if (wrapSense != 1 && wrapSense != -1)
        throw std::invalid_argument("GrooveArc: wrapSense = " + std::to_string(wrapSense) + " must be +1 or -1");
    if (!gravity.allFinite()) throw std::invalid_argument("GrooveArc: gravity must be finite");
}

template <int Dim>
void GrooveArc<Dim>::evaluate(const Coordinates& x, const Coordinates& xdot, Data& data) const {
    checkState<Dim>(x, &xdot);
    constexpr int n = kNumCoordinates;
    using Derivatives = Eigen::Matrix<double, n, 1>;
    using AD = Eigen::AutoDiffScalar<Derivatives>;
    const double rhoA = massPerLength_, R = radius_;
    const int sigma = wrapSense_;

    // Mass matrix: M = rhoA R sum_ij I_ij B_i^T B_j, B_i the (constant in xdot) Jacobians of A_i.
    const ArcState<Dim, double> st(x, Coordinates::Zero(), R, sigma);
    const ArcIntegrals<double> I(st.alpha);
    Eigen::Matrix<double, Dim, n> B0 = Eigen::Matrix<double, Dim, n>::Zero(), B1 = B0, B2 = B0;
    using Mat = Eigen::Matrix<double, Dim, Dim>;
    Mat neCross;  // v -> n_e x v
    for (int k = 0; k < Dim; ++k) neCross.col(k) = turn<double>(st.ne, sigma, Vec(Vec::Unit(k)));
    B0.template block<Dim, Dim>(0, centreIndex()).setIdentity();
    B1.template block<Dim, Dim>(0, centreIndex()) = -Mat::Identity();
    B1.template block<Dim, Dim>(0, tangentPointIndex()).setIdentity();
    B1.col(materialIndex()) = -st.ndCross / R;
    B2.template block<Dim, Dim>(0, centreIndex()) = -neCross;
    B2.template block<Dim, Dim>(0, tangentPointIndex()) = neCross;
    if constexpr (Dim == 3) {
        for (int k = 0; k < 3; ++k)
            B2.col(axisIndex() + k) = double(sigma) * Eigen::Vector3d::Unit(k).cross(st.d);
    }
    B2.col(materialIndex()) = st.d / R;
    const auto B0tB1 = (B0.transpose() * B1).eval();
    const auto B0tB2 = (B0.transpose() * B2).eval();
    const auto B1tB2 = (B1.transpose() * B2).eval();
    data.massMatrix = rhoA * R *  // mutation-site: arc-mass
                      (I.one * B0.transpose() * B0 + I.cc * B1.transpose() * B1 + I.ss * B2.transpose() * B2 +
                       I.c * (B0tB1 + B0tB1.transpose()) + I.s * (B0tB2 + B0tB2.transpose()) +
                       I.cs * (B1tB2 + B1tB2.transpose()));

    // g(x) = M(x) xdot by forward differentiation in x: G = dg/dx.
    CoordinatesOf<Dim, AD> xad;
    for (int i = 0; i < n; ++i) xad[i] = AD(x[i], n, i);
    const CoordinatesOf<Dim, AD> g = massTimesVelocity<Dim, AD>(xad, xdot, rhoA, R, sigma);
    Eigen::Matrix<double, n, n> G;
    Coordinates gValue;
    for (int i = 0; i < n; ++i) {
        G.row(i) = g[i].derivatives().transpose();
        gValue[i] = g[i].value();
    }
    data.kineticEnergy = 0.5 * xdot.dot(gValue);
    data.velocityForces = 0.5 * G.transpose() * xdot - G * xdot;  // mutation-site: arc-qv-forces

    const AD U = gravityEnergyOf<Dim, AD>(xad, gravity_, rhoA, R, sigma);
    data.gravityEnergy = U.value();
    data.gravityForces = -U.derivatives();
}

template <int Dim>
double GrooveArc<Dim>::kineticEnergy(const Coordinates& x, const Coordinates& xdot) const {
    checkState<Dim>(x, &xdot);
    return 0.5 * xdot.dot(massTimesVelocity<Dim, double>(x, xdot, massPerLength_, radius_, wrapSense_));
}

template <int Dim>
double GrooveArc<Dim>::gravityEnergy(const Coordinates& x) const {
    checkState<Dim>(x, nullptr);
    return gravityEnergyOf<Dim, double>(x, gravity_, massPerLength_, radius_, wrapSense_);
}

template <int Dim>
typename GrooveArc<Dim>::Vec GrooveArc<Dim>::materialPosition(const Coordinates& x, double arcLength) const {
    const ArcState<Dim, double> st(x, Coordinates::Zero(), radius_, wrapSense_);
    const double theta = arcLength / radius_;
    return st.c + std::cos(theta) * st.d + std::sin(theta) * st.ndCross;
}

template <int Dim>
typename GrooveArc<Dim>::Vec GrooveArc<Dim>::materialVelocity(const Coordinates& x, const Coordinates& xdot,
                                                               double arcLength) const {
    const ArcState<Dim, double> st(x, xdot, radius_, wrapSense_);
    const double theta = arcLength / radius_;
    return st.A0 + std::cos(theta) * st.A1 + std::sin(theta) * st.A2;
}

template class GrooveArc<2>;
template class GrooveArc<3>;

}  // namespace SimbodyReeving
