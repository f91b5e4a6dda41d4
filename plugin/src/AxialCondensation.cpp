#include "SimbodyReeving/AxialCondensation.h"

#include "SimbodyReeving/GaussLegendre.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace SimbodyReeving {
namespace {

/// A truncated Taylor series f(tau) = v + d tau + dd tau^2 / 2 (value, first and second derivative
/// at tau = 0): evaluating a function on it gives the function's first and second derivatives along
/// a path, exactly (no step size).
struct Taylor2 {
    double v = 0, d = 0, dd = 0;
    Taylor2() = default;
    Taylor2(double value, double first = 0, double second = 0) : v(value), d(first), dd(second) {}
};
inline Taylor2 operator+(const Taylor2& a, const Taylor2& b) { return {a.v + b.v, a.d + b.d, a.dd + b.dd}; }
inline Taylor2 operator-(const Taylor2& a, const Taylor2& b) { return {a.v - b.v, a.d - b.d, a.dd - b.dd}; }
inline Taylor2 operator*(const Taylor2& a, const Taylor2& b) {
    return {a.v * b.v, a.d * b.v + a.v * b.d, a.dd * b.v + 2.0 * a.d * b.d + a.v * b.dd};
}
inline Taylor2 operator*(double c, const Taylor2& a) { return {c * a.v, c * a.d, c * a.dd}; }
inline Taylor2& operator+=(Taylor2& a, const Taylor2& b) { return a = a + b; }
inline Taylor2 reciprocal(const Taylor2& a) {
    const double r = 1.0 / a.v;
    return {r, -a.d * r * r, (2.0 * a.d * a.d * r - a.dd) * r * r};
}
inline Taylor2 sqrt(const Taylor2& a) {
    const double s = std::sqrt(a.v);
    return {s, 0.5 * a.d / s, 0.5 * a.dd / s - 0.25 * a.d * a.d / (s * a.v)};
}

}  // namespace

template <int Dim>
AxialCondensation<Dim>::AxialCondensation(const SpanModel<Dim>& span) {
    const SpanOptions& o = span.options();
    if (o.elasticModel != ElasticEnergyModel::Consistent)
        throw std::invalid_argument(
            "AxialCondensation: quasi-static axial modes require ElasticEnergyModel::Consistent on every span of "
            "the rope");
    na_ = o.axialModes;
    nt_ = o.transverseModes;
    numModal_ = span.numModalCoordinates();
    numCoordinates_ = span.numCoordinates();
    EA_ = span.properties().axialStiffness;
    rhoA_ = span.properties().massPerLength;
    EI_ = span.properties().bendingStiffness;
    gravity_ = span.gravity();
    referenceFrame_ = span.referenceFrame();
    const int nq = span.quadraturePoints(Integrand::Strain);
    const int maxMode = std::max(na_, nt_);
    const GaussLegendreRule rule = makeGaussLegendreRule(nq);
    const double pi = std::acos(-1.0);
    weights_.resize(nq);
    slopes_.resize(nq, maxMode);
    for (int k = 0; k < nq; ++k) {
        weights_[k] = rule.weights[k];
        for (int i = 0; i < maxMode; ++i) slopes_(k, i) = (i + 1) * pi * std::cos((i + 1) * pi * rule.nodes[k]);
    }
    sinMean_.resize(maxMode);
    bendFactor_.resize(maxMode);
    endSlope_[0].resize(maxMode);
    endSlope_[1].resize(maxMode);
    for (int i = 0; i < maxMode; ++i) {
        const double kw = (i + 1) * pi;
        sinMean_[i] = ((i + 1) % 2 == 1) ? 2.0 / kw : 0.0;
        bendFactor_[i] = 0.5 * kw * kw * kw * kw;
        endSlope_[0][i] = kw;
        endSlope_[1][i] = ((i + 1) % 2 == 1) ? -kw : kw;
    }
}

template <int Dim>
template <class Scalar>
void AxialCondensation<Dim>::quantities(const Scalar& chordLength, const Scalar& spanLength,
                                        const Scalar* gravityOnFrame, const Scalar& gravityOnMean,
                                        const Scalar* modal, Scalar* out) const {
    const Scalar invL = reciprocal(spanLength);
    const Scalar invL2 = invL * invL;
    const Scalar* axial = modal;
    const Scalar* transverse = modal + na_;
    for (int i = 0; i < numQuantities(); ++i) out[i] = Scalar(0.0);
    // Strain integrals: Phi_i (axial part) and dU_ax/dl.
    Scalar axialLength(0.0);
    for (int k = 0; k < weights_.size(); ++k) {
        Scalar lambda = chordLength;
        for (int i = 0; i < na_; ++i) lambda += slopes_(k, i) * axial[i];
        Scalar t2 = lambda * lambda;
        for (int d = 0; d + 1 < Dim; ++d) {
            Scalar tau(0.0);
            for (int i = 0; i < nt_; ++i) tau += slopes_(k, i) * transverse[d * nt_ + i];
            t2 += tau * tau;
        }
        const Scalar eps = 0.5 * (t2 * invL2) - Scalar(0.5);
        const Scalar epsLambda = eps * lambda;
        for (int i = 0; i < na_; ++i) out[phi(i)] += (weights_[k] * slopes_(k, i)) * epsLambda;
        axialLength += weights_[k] * ((-1.5) * (eps * eps) - eps);
    }
    // Gravity: U_g = -rhoA l (g . r_mean + sum_d (g . A_e col d) ubar_d).
    Scalar gravityOnModes(0.0);
    for (int i = 0; i < na_; ++i) gravityOnModes += sinMean_[i] * (gravityOnFrame[0] * axial[i]);
    for (int d = 0; d + 1 < Dim; ++d)
        for (int i = 0; i < nt_; ++i) gravityOnModes += sinMean_[i] * (gravityOnFrame[d + 1] * transverse[d * nt_ + i]);
    for (int i = 0; i < na_; ++i)
        out[phi(i)] = EA_ * (invL * out[phi(i)]) - (rhoA_ * sinMean_[i]) * (spanLength * gravityOnFrame[0]);
    // Bending (transverse modes only, Consistent): U_b = EI / (2 l^3) sum f_i b_i^2, dU_b/dl = -3 U_b / l.
    Scalar bending(0.0);
    if (EI_ > 0)
        for (int d = 0; d + 1 < Dim; ++d)
            for (int i = 0; i < nt_; ++i)
                bending += bendFactor_[i] * (transverse[d * nt_ + i] * transverse[d * nt_ + i]);
    out[lengthDerivative()] = EA_ * axialLength + (-1.5 * EI_) * (bending * (invL2 * invL2)) -
                              rhoA_ * (gravityOnMean + gravityOnModes);
    // End strains and their slopes.
    for (int end = 0; end < 2; ++end) {
        const SpanEnd E = end == 0 ? SpanEnd::First : SpanEnd::Second;
        Scalar lambda = chordLength;
        for (int i = 0; i < na_; ++i) lambda += endSlope_[end][i] * axial[i];
        Scalar t2 = lambda * lambda;
        for (int d = 0; d + 1 < Dim; ++d) {
            Scalar tau(0.0);
            for (int i = 0; i < nt_; ++i) tau += endSlope_[end][i] * transverse[d * nt_ + i];
            t2 += tau * tau;
        }
        const Scalar eps = 0.5 * (t2 * invL2) - Scalar(0.5);
        out[endStrain(E)] = eps;
        const Scalar lambdaOverL2 = lambda * invL2;
        for (int i = 0; i < na_; ++i) out[endStrainAxialSlope(E, i)] = endSlope_[end][i] * lambdaOverL2;
        out[endStrainLengthSlope(E)] = (-1.0) * ((2.0 * eps + Scalar(1.0)) * invL);
    }
}

template <int Dim>
void AxialCondensation<Dim>::evaluate(const Eigen::Ref<const Eigen::VectorXd>& q,
                                      const Eigen::Ref<const Eigen::VectorXd>& qdot, Data& d) const {
    using Vec = Eigen::Matrix<double, Dim, 1>;
    const int iM = 2 * Dim, iS1 = numCoordinates_ - 2, iS2 = numCoordinates_ - 1;
    const int nQ = numQuantities();
    const bool withRates = qdot.size() == q.size();
    const Vec e = q.template segment<Dim>(Dim) - q.template segment<Dim>(0);
    computeChordFrame<Dim>(e, Vec::Zero(), referenceFrame_, d.frame);
    const ChordFrame<Dim>& F = d.frame;
    const double chord = e.norm(), l = q[iS2] - q[iS1];
    const double gMean = 0.5 * gravity_.dot(q.template segment<Dim>(0) + q.template segment<Dim>(Dim));

    Taylor2 gA[Dim], modal[2 * kMaxModesPerDirection], out[AxialCondensationData<Dim>::kMaxQuantities];
    Taylor2 chordT(chord), lT(l), gMeanT(gMean);
    auto reset = [&] {
        chordT = Taylor2(chord);
        lT = Taylor2(l);
        gMeanT = Taylor2(gMean);
        for (int c = 0; c < Dim; ++c) gA[c] = Taylor2(gravity_.dot(F.A.col(c)));
        for (int j = 0; j < numModal_; ++j) modal[j] = Taylor2(q[iM + j]);
    };
    auto run = [&] { quantities(chordT, lT, gA, gMeanT, modal, out); };

    d.value.resize(nQ);
    d.gradient.setZero(nQ, numCoordinates_);
    reset();
    run();
    for (int k = 0; k < nQ; ++k) d.value[k] = out[k].v;
    // Gradient: one directional pass per independent input.
    for (int m = 0; m < Dim; ++m) {  // chord component e_m (r2 - r1)
        reset();
        chordT.d = e[m] / chord;
        for (int c = 0; c < Dim; ++c) gA[c].d = gravity_.dot(F.dA[m].col(c));
        run();
        for (int k = 0; k < nQ; ++k) {
            d.gradient(k, m) -= out[k].d;
            d.gradient(k, Dim + m) += out[k].d;
        }
    }
    reset();
    gMeanT.d = 1.0;
    run();
    for (int k = 0; k < nQ; ++k)
        for (int m = 0; m < Dim; ++m) {
            d.gradient(k, m) += 0.5 * gravity_[m] * out[k].d;
            d.gradient(k, Dim + m) += 0.5 * gravity_[m] * out[k].d;
        }
    for (int j = 0; j < numModal_; ++j) {
        reset();
        modal[j].d = 1.0;
        run();
        for (int k = 0; k < nQ; ++k) d.gradient(k, iM + j) = out[k].d;
    }
    reset();
    lT.d = 1.0;
    run();
    for (int k = 0; k < nQ; ++k) {
        d.gradient(k, iS1) = -out[k].d;
        d.gradient(k, iS2) = out[k].d;
    }
    if (!withRates) {
        d.rate.setZero(nQ);
        d.accelerationBias.setZero(nQ);
        return;
    }
    evaluateRates(q, qdot, d);
}

template <int Dim>
void AxialCondensation<Dim>::evaluateRates(const Eigen::Ref<const Eigen::VectorXd>& q,
                                           const Eigen::Ref<const Eigen::VectorXd>& qdot, Data& d) const {
    using Vec = Eigen::Matrix<double, Dim, 1>;
    const int iM = 2 * Dim, iS1 = numCoordinates_ - 2, iS2 = numCoordinates_ - 1;
    const int nQ = numQuantities();
    const Vec e = q.template segment<Dim>(Dim) - q.template segment<Dim>(0);
    const Vec ed = qdot.template segment<Dim>(Dim) - qdot.template segment<Dim>(0);
    computeChordFrame<Dim>(e, ed, referenceFrame_, d.frame);
    const ChordFrame<Dim>& F = d.frame;
    const double l = q[iS2] - q[iS1];
    const double gMean = 0.5 * gravity_.dot(q.template segment<Dim>(0) + q.template segment<Dim>(Dim));
    // Rates and second time derivatives along qdot (qddot = 0): the chord moves as e + edot tau, so
    // |e|^2 is a quadratic in tau; the frame's projections follow from ChordFrame's Adot and Addot.
    Taylor2 gA[Dim], modal[2 * kMaxModesPerDirection], out[AxialCondensationData<Dim>::kMaxQuantities];
    const Taylor2 chordT = sqrt(Taylor2(e.squaredNorm(), 2.0 * e.dot(ed), 2.0 * ed.squaredNorm()));
    const Taylor2 lT(l, qdot[iS2] - qdot[iS1], 0.0);
    const Taylor2 gMeanT(gMean, 0.5 * gravity_.dot(qdot.template segment<Dim>(0) + qdot.template segment<Dim>(Dim)),
                         0.0);
    for (int c = 0; c < Dim; ++c)
        gA[c] = Taylor2(gravity_.dot(F.A.col(c)), gravity_.dot(F.Adot.col(c)), gravity_.dot(F.Addot.col(c)));
    for (int j = 0; j < numModal_; ++j) modal[j] = Taylor2(q[iM + j], qdot[iM + j], 0.0);
    quantities(chordT, lT, gA, gMeanT, modal, out);
    d.rate.resize(nQ);
    d.accelerationBias.resize(nQ);
    for (int k = 0; k < nQ; ++k) {
        d.rate[k] = out[k].d;
        d.accelerationBias[k] = out[k].dd;
    }
}

template class AxialCondensation<2>;
template class AxialCondensation<3>;

}  // namespace SimbodyReeving
