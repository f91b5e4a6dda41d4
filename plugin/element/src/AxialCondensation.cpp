#include "SimbodyReeving/element/AxialCondensation.h"

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
inline double primal(const Taylor2& a) { return a.v; }
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
    law_ = span.axialLaw();
    nc_ = span.numCondensedModes();
    ncAxial_ = span.condensesAxialModes() ? na_ : 0;
    ncTransverse_ = span.condensesTransverseModes() ? nt_ : 0;
    slackStiffness_ = span.slackRegularised() && ncAxial_ > 0 ? 0.5 * o.quasiStaticSlackStiffness * EA_ : 0.0;
    transverseSlackStiffness_ =
        span.slackRegularised() && ncTransverse_ > 0 ? 0.5 * o.quasiStaticTransverseSlackStiffness * EA_ : 0.0;
    gravity_ = span.gravity();
    referenceFrame_ = span.referenceFrame();
    // The span's own strain rule (SpanModel::quadratureNodes: Gauss-Legendre, automatic or explicit
    // count), so that Phi and dU/dl are the derivatives of the energy SpanModel::evaluate computes.
    const int maxMode = std::max(na_, nt_);
    const double pi = std::acos(-1.0);
    auto makeRule = [&](const Eigen::VectorXd& nodes, const Eigen::VectorXd& weights, StrainRule& rule) {
        const int nq = static_cast<int>(nodes.size());
        rule.weights = weights;
        rule.slopes.resize(nq, maxMode);
        for (int k = 0; k < nq; ++k)
            for (int i = 0; i < maxMode; ++i) rule.slopes(k, i) = (i + 1) * pi * std::cos((i + 1) * pi * nodes[k]);
    };
    makeRule(span.quadratureNodes(Integrand::Strain), span.quadratureWeights(Integrand::Strain), rule_);
    if (span.tautStrainRule()) makeRule(span.tautStrainNodes(), span.tautStrainWeights(), tautRule_);
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
void AxialCondensation<Dim>::quantities(const StrainRule& rule, const Scalar& chordLength, const Scalar& spanLength,
                                        const Scalar* gravityOnFrame, const Scalar& gravityOnMean,
                                        const Scalar* modal, Scalar* out) const {
    const Eigen::VectorXd& weights = rule.weights;
    const Eigen::MatrixXd& slopes = rule.slopes;
    const Scalar invL = reciprocal(spanLength);
    const Scalar invL2 = invL * invL;
    const Scalar* axial = modal;
    const Scalar* transverse = modal + na_;
    for (int i = 0; i < numQuantities(); ++i) out[i] = Scalar(0.0);
    // Strain integrals: Phi_i (axial part) and dU_ax/dl.
    Scalar axialLength(0.0);
    for (int k = 0; k < weights.size(); ++k) {
        Scalar lambda = chordLength;
        for (int i = 0; i < na_; ++i) lambda += slopes(k, i) * axial[i];
        Scalar t2 = lambda * lambda;
        Scalar tau[Dim];
        for (int d = 0; d + 1 < Dim; ++d) {
            tau[d] = Scalar(0.0);
            for (int i = 0; i < nt_; ++i) tau[d] += slopes(k, i) * transverse[d * nt_ + i];
            t2 += tau[d] * tau[d];
        }
        const Scalar eps = 0.5 * (t2 * invL2) - Scalar(0.5);
        const double e0 = primal(eps);
        if (law_.slack(e0)) continue;  // slack point: no axial force, no energy
        const Scalar f = law_.f(eps, e0);
        const Scalar fLambda = f * lambda;
        for (int i = 0; i < ncAxial_; ++i) out[phi(i)] += (weights[k] * slopes(k, i)) * fLambda;
        for (int d = 0; d + 1 < Dim; ++d) {
            const Scalar fTau = f * tau[d];
            for (int i = 0; i < ncTransverse_; ++i)
                out[phi(ncAxial_ + d * ncTransverse_ + i)] += (weights[k] * slopes(k, i)) * fTau;
        }
        axialLength += weights[k] * (law_.F(eps, e0) - f * (2.0 * eps + Scalar(1.0)));
    }
    // Gravity: U_g = -rhoA l (g . r_mean + sum_d (g . A_e col d) ubar_d).
    Scalar gravityOnModes(0.0);
    for (int i = 0; i < na_; ++i) gravityOnModes += sinMean_[i] * (gravityOnFrame[0] * axial[i]);
    for (int d = 0; d + 1 < Dim; ++d)
        for (int i = 0; i < nt_; ++i) gravityOnModes += sinMean_[i] * (gravityOnFrame[d + 1] * transverse[d * nt_ + i]);
    for (int i = 0; i < ncAxial_; ++i)
        out[phi(i)] = EA_ * (invL * out[phi(i)]) - (rhoA_ * sinMean_[i]) * (spanLength * gravityOnFrame[0]);
    // Condensed transverse: Phi_dj = EA / l int f tau_d S_j' - rhoA l m_j (g . A_e col d) + EI f_j b_dj / l^3.
    for (int d = 0; d + 1 < Dim; ++d)
        for (int i = 0; i < ncTransverse_; ++i) {
            const int row = phi(ncAxial_ + d * ncTransverse_ + i);
            out[row] = EA_ * (invL * out[row]) - (rhoA_ * sinMean_[i]) * (spanLength * gravityOnFrame[d + 1]);
            if (EI_ > 0) out[row] += (EI_ * bendFactor_[i]) * (transverse[d * nt_ + i] * (invL2 * invL));
        }
    // Bending (transverse modes only, Consistent): U_b = EI / (2 l^3) sum f_i b_i^2, dU_b/dl = -3 U_b / l.
    Scalar bending(0.0);
    if (EI_ > 0)
        for (int d = 0; d + 1 < Dim; ++d)
            for (int i = 0; i < nt_; ++i)
                bending += bendFactor_[i] * (transverse[d * nt_ + i] * transverse[d * nt_ + i]);
    out[lengthDerivative()] = EA_ * axialLength + (-1.5 * EI_) * (bending * (invL2 * invL2)) -
                              rhoA_ * (gravityOnMean + gravityOnModes);
    // Slack regularisation: Phi_i += delta EA k_i^2 a_i / (2 l), dU/dl -= delta EA / (4 l^2) sum k_i^2 a_i^2.
    if (slackStiffness_ > 0) {
        Scalar sum(0.0);
        for (int i = 0; i < ncAxial_; ++i) {
            const double k2 = SpanModel<Dim>::axialModeWavenumberSquared(i);
            out[phi(i)] += (slackStiffness_ * k2) * (axial[i] * invL);
            sum += k2 * (axial[i] * axial[i]);
        }
        out[lengthDerivative()] += (-0.5 * slackStiffness_) * (sum * invL2);
    }
    if (transverseSlackStiffness_ > 0) {
        Scalar sum(0.0);
        for (int d = 0; d + 1 < Dim; ++d)
            for (int i = 0; i < ncTransverse_; ++i) {
                const double k2 = SpanModel<Dim>::axialModeWavenumberSquared(i);
                const Scalar& bi = transverse[d * nt_ + i];
                out[phi(ncAxial_ + d * ncTransverse_ + i)] += (transverseSlackStiffness_ * k2) * (bi * invL);
                sum += k2 * (bi * bi);
            }
        out[lengthDerivative()] += (-0.5 * transverseSlackStiffness_) * (sum * invL2);
    }
    // End strains and their slopes.
    for (int end = 0; end < 2; ++end) {
        const SpanEnd E = end == 0 ? SpanEnd::First : SpanEnd::Second;
        Scalar lambda = chordLength;
        for (int i = 0; i < na_; ++i) lambda += endSlope_[end][i] * axial[i];
        Scalar t2 = lambda * lambda;
        Scalar tau[Dim];
        for (int d = 0; d + 1 < Dim; ++d) {
            tau[d] = Scalar(0.0);
            for (int i = 0; i < nt_; ++i) tau[d] += endSlope_[end][i] * transverse[d * nt_ + i];
            t2 += tau[d] * tau[d];
        }
        const Scalar eps = 0.5 * (t2 * invL2) - Scalar(0.5);
        out[endStrain(E)] = eps;
        const Scalar lambdaOverL2 = lambda * invL2;
        for (int i = 0; i < ncAxial_; ++i) out[endStrainModeSlope(E, i)] = endSlope_[end][i] * lambdaOverL2;
        for (int d = 0; d + 1 < Dim; ++d) {
            const Scalar tauOverL2 = tau[d] * invL2;
            for (int i = 0; i < ncTransverse_; ++i)
                out[endStrainModeSlope(E, ncAxial_ + d * ncTransverse_ + i)] = endSlope_[end][i] * tauOverL2;
        }
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

    // Values and gradients with respect to the reduced inputs x = [|e|, l, g.A_e col 0..Dim-1,
    // g.r_mean, q_m] in one pass (closed-form derivatives of the expressions in quantities()),
    // then chained to the span coordinates.
    const int P = 3 + Dim + numModal_;
    const int xChord = 0, xLength = 1, xFrame = 2, xMean = 2 + Dim, xModal = 3 + Dim;
    // G(k, x) = d quantity_k / d x_x, row-major with stride P (rows contiguous: one fill clears it).
    constexpr int kMaxInputs = 3 + Dim + Dim * kMaxModesPerDirection;
    double Gbuf[AxialCondensationData<Dim>::kMaxQuantities * kMaxInputs];
    std::fill(Gbuf, Gbuf + nQ * P, 0.0);
    auto G = [&Gbuf, P](int k, int x) -> double& { return Gbuf[k * P + x]; };
    d.value.setZero(nQ);
    double gA[Dim];
    for (int c = 0; c < Dim; ++c) gA[c] = gravity_.dot(F.A.col(c));
    const double* a = q.data() + iM;        // axial amplitudes
    const double* b = q.data() + iM + na_;  // transverse amplitudes, direction by direction
    const double l2 = l * l, l3 = l2 * l;
    // Strain integrals: P_i = int eps lambda S_i' and A = int (-3/2 eps^2 - eps).
    const StrainRule& rule = strainRule(chord, l, a);
    for (int k = 0; k < rule.weights.size(); ++k) {
        const auto S = rule.slopes.row(k);
        const double w = rule.weights[k];
        double lambda = chord;
        for (int i = 0; i < na_; ++i) lambda += S[i] * a[i];
        double tau[Dim] = {};
        double t2 = lambda * lambda;
        for (int dir = 0; dir + 1 < Dim; ++dir) {
            for (int i = 0; i < nt_; ++i) tau[dir] += S[i] * b[dir * nt_ + i];
            t2 += tau[dir] * tau[dir];
        }
        const double eps = 0.5 * (t2 / l2 - 1.0);
        if (law_.slack(eps)) continue;  // slack point: no axial force, no energy
        const double f = law_.f(eps), fp = law_.fPrime(eps);
        const double fLambda = f * lambda;
        const double dEL = fp * lambda * lambda / l2 + f;          // d(f lambda)/d lambda
        const double dELdl = -fp * lambda * (2.0 * eps + 1.0) / l;  // d(f lambda)/dl
        for (int i = 0; i < ncAxial_; ++i) {
            const double c = w * S[i];
            d.value[phi(i)] += c * fLambda;
            G(phi(i), xChord) += c * dEL;
            G(phi(i), xLength) += c * dELdl;
            for (int j = 0; j < na_; ++j) G(phi(i), xModal + j) += c * dEL * S[j];
            for (int dir = 0; dir + 1 < Dim; ++dir) {
                const double ft = c * fp * lambda * tau[dir] / l2;
                for (int j = 0; j < nt_; ++j) G(phi(i), xModal + na_ + dir * nt_ + j) += ft * S[j];
            }
        }
        // Condensed transverse: T_dj = int f tau_d S_j', d(f tau_d) = f' tau_d d eps + f d tau_d.
        for (int dir = 0; dir + 1 < Dim; ++dir)
            for (int i = 0; i < ncTransverse_; ++i) {
                const int row = phi(ncAxial_ + dir * ncTransverse_ + i);
                const double c = w * S[i];
                const double cft = c * fp * tau[dir];  // times d eps
                d.value[row] += c * f * tau[dir];
                G(row, xChord) += cft * lambda / l2;
                G(row, xLength) += -cft * (2.0 * eps + 1.0) / l;
                for (int j = 0; j < na_; ++j) G(row, xModal + j) += cft * lambda * S[j] / l2;
                for (int dir2 = 0; dir2 + 1 < Dim; ++dir2) {
                    const double coef = cft * tau[dir2] / l2;
                    for (int j = 0; j < nt_; ++j) G(row, xModal + na_ + dir2 * nt_ + j) += coef * S[j];
                }
                for (int j = 0; j < nt_; ++j) G(row, xModal + na_ + dir * nt_ + j) += c * f * S[j];
            }
        // A = sum w (F - f (2 eps + 1)): dA = w (-f - f' (2 eps + 1)) d eps (linear law: -3/2 eps^2 - eps
        // and -3 eps - 1).
        const int u = lengthDerivative();
        d.value[u] += EA_ * w * (law_.F(eps) - f * (2.0 * eps + 1.0));
        const double c = EA_ * w * (-f - fp * (2.0 * eps + 1.0));
        G(u, xChord) += c * lambda / l2;
        G(u, xLength) += c * (-(2.0 * eps + 1.0) / l);
        for (int j = 0; j < na_; ++j) G(u, xModal + j) += c * lambda * S[j] / l2;
        for (int dir = 0; dir + 1 < Dim; ++dir)
            for (int j = 0; j < nt_; ++j) G(u, xModal + na_ + dir * nt_ + j) += c * tau[dir] * S[j] / l2;
    }
    // Phi_i = EA P_i / l - rhoA m_i l (g . i_e).
    for (int i = 0; i < ncAxial_; ++i) {
        const double Pi = d.value[phi(i)];
        for (int x = 0; x < P; ++x) G(phi(i), x) *= EA_ / l;
        G(phi(i), xLength) += -EA_ * Pi / l2 - rhoA_ * sinMean_[i] * gA[0];
        G(phi(i), xFrame) += -rhoA_ * sinMean_[i] * l;
        d.value[phi(i)] = EA_ * Pi / l - rhoA_ * sinMean_[i] * l * gA[0];
    }
    // Phi_dj = EA T_dj / l - rhoA m_j l (g . A_e col d) + EI f_j b_dj / l^3.
    for (int dir = 0; dir + 1 < Dim; ++dir)
        for (int i = 0; i < ncTransverse_; ++i) {
            const int row = phi(ncAxial_ + dir * ncTransverse_ + i);
            const double T = d.value[row];
            for (int x = 0; x < P; ++x) G(row, x) *= EA_ / l;
            G(row, xLength) += -EA_ * T / l2 - rhoA_ * sinMean_[i] * gA[dir + 1];
            G(row, xFrame + dir + 1) += -rhoA_ * sinMean_[i] * l;
            d.value[row] = EA_ * T / l - rhoA_ * sinMean_[i] * l * gA[dir + 1];
            if (EI_ > 0) {
                const double bi = b[dir * nt_ + i], kb = EI_ * bendFactor_[i] / l3;
                d.value[row] += kb * bi;
                G(row, xModal + na_ + dir * nt_ + i) += kb;
                G(row, xLength) += -3.0 * kb * bi / l;
            }
        }
    // Slack regularisation U_delta = (delta EA / 2) / (2 l) sum k_i^2 a_i^2 (k_i = i pi):
    // Phi_i += mu_i a_i with mu_i = (delta EA / 2) k_i^2 / l; dU/dl -= U_delta / l.
    if (slackStiffness_ > 0) {
        const int u = lengthDerivative();
        double Ud = 0;
        for (int i = 0; i < ncAxial_; ++i) {
            const double mu = slackStiffness_ * SpanModel<Dim>::axialModeWavenumberSquared(i) / l;
            d.value[phi(i)] += mu * a[i];
            G(phi(i), xModal + i) += mu;
            G(phi(i), xLength) += -mu * a[i] / l;
            Ud += 0.5 * mu * a[i] * a[i];
            G(u, xModal + i) += -mu * a[i] / l;
        }
        d.value[u] += -Ud / l;
        G(u, xLength) += 2.0 * Ud / l2;
    }
    if (transverseSlackStiffness_ > 0) {  // the same on condensed transverse amplitudes, with delta_t
        const int u = lengthDerivative();
        double Ud = 0;
        for (int dir = 0; dir + 1 < Dim; ++dir)
            for (int i = 0; i < ncTransverse_; ++i) {
                const int row = phi(ncAxial_ + dir * ncTransverse_ + i), col = xModal + na_ + dir * nt_ + i;
                const double mu = transverseSlackStiffness_ * SpanModel<Dim>::axialModeWavenumberSquared(i) / l;
                const double bi = b[dir * nt_ + i];
                d.value[row] += mu * bi;
                G(row, col) += mu;
                G(row, xLength) += -mu * bi / l;
                Ud += 0.5 * mu * bi * bi;
                G(u, col) += -mu * bi / l;
            }
        d.value[u] += -Ud / l;
        G(u, xLength) += 2.0 * Ud / l2;
    }
    // dU/dl: bending -3 U_b / l = -3/2 EI B / l^4 with B = sum f_i b_i^2; gravity -rhoA (g.r_mean + sum g.A_d ubar_d).
    {
        const int u = lengthDerivative();
        double B = 0;
        if (EI_ > 0)
            for (int dir = 0; dir + 1 < Dim; ++dir)
                for (int i = 0; i < nt_; ++i) {
                    const double bi = b[dir * nt_ + i];
                    B += bendFactor_[i] * bi * bi;
                    G(u, xModal + na_ + dir * nt_ + i) += -3.0 * EI_ * bendFactor_[i] * bi / (l2 * l2);
                }
        d.value[u] += -1.5 * EI_ * B / (l2 * l2);
        G(u, xLength) += 6.0 * EI_ * B / (l3 * l2);
        double ubar[Dim] = {};
        for (int i = 0; i < na_; ++i) ubar[0] += sinMean_[i] * a[i];
        for (int dir = 0; dir + 1 < Dim; ++dir)
            for (int i = 0; i < nt_; ++i) ubar[dir + 1] += sinMean_[i] * b[dir * nt_ + i];
        double gOnModes = 0;
        for (int c = 0; c < Dim; ++c) {
            gOnModes += gA[c] * ubar[c];
            G(u, xFrame + c) += -rhoA_ * ubar[c];
        }
        d.value[u] += -rhoA_ * (gMean + gOnModes);
        G(u, xMean) += -rhoA_;
        for (int i = 0; i < na_; ++i) G(u, xModal + i) += -rhoA_ * gA[0] * sinMean_[i];
        for (int dir = 0; dir + 1 < Dim; ++dir)
            for (int i = 0; i < nt_; ++i) G(u, xModal + na_ + dir * nt_ + i) += -rhoA_ * gA[dir + 1] * sinMean_[i];
    }
    // End strains and their slopes.
    for (int end = 0; end < 2; ++end) {
        const SpanEnd E = end == 0 ? SpanEnd::First : SpanEnd::Second;
        const auto& S = endSlope_[end];
        double lambda = chord;
        for (int i = 0; i < na_; ++i) lambda += S[i] * a[i];
        double tau[Dim] = {};
        double t2 = lambda * lambda;
        for (int dir = 0; dir + 1 < Dim; ++dir) {
            for (int i = 0; i < nt_; ++i) tau[dir] += S[i] * b[dir * nt_ + i];
            t2 += tau[dir] * tau[dir];
        }
        const double eps = 0.5 * (t2 / l2 - 1.0);
        const int ie = endStrain(E), il = endStrainLengthSlope(E);
        d.value[ie] = eps;
        G(ie, xChord) = lambda / l2;
        G(ie, xLength) = -(2.0 * eps + 1.0) / l;
        for (int j = 0; j < na_; ++j) G(ie, xModal + j) = lambda * S[j] / l2;
        for (int dir = 0; dir + 1 < Dim; ++dir)
            for (int j = 0; j < nt_; ++j) G(ie, xModal + na_ + dir * nt_ + j) = tau[dir] * S[j] / l2;
        // d eps_E / dl = -(2 eps_E + 1) / l
        d.value[il] = -(2.0 * eps + 1.0) / l;
        for (int x = 0; x < P; ++x) G(il, x) = -2.0 * G(ie, x) / l;
        G(il, xLength) += (2.0 * eps + 1.0) / l2;
        // d eps_E / da_i = lambda_E S_i'(E) / l^2
        for (int i = 0; i < ncAxial_; ++i) {
            const int ia = endStrainModeSlope(E, i);
            d.value[ia] = lambda * S[i] / l2;
            G(ia, xChord) = S[i] / l2;
            G(ia, xLength) = -2.0 * lambda * S[i] / l3;
            for (int j = 0; j < na_; ++j) G(ia, xModal + j) = S[i] * S[j] / l2;
        }
        // d eps_E / db_di = tau_d,E S_i'(E) / l^2
        for (int dir = 0; dir + 1 < Dim; ++dir)
            for (int i = 0; i < ncTransverse_; ++i) {
                const int ib = endStrainModeSlope(E, ncAxial_ + dir * ncTransverse_ + i);
                d.value[ib] = tau[dir] * S[i] / l2;
                G(ib, xLength) = -2.0 * tau[dir] * S[i] / l3;
                for (int j = 0; j < nt_; ++j) G(ib, xModal + na_ + dir * nt_ + j) = S[i] * S[j] / l2;
            }
    }
    // Chain to the span coordinates: |e| and g.A_e through e = r2 - r1, g.r_mean through both
    // nodes, l = s2 - s1.
    const Vec unit = e / chord;
    double gdA[Dim][Dim];  // g . dA/de_m col c
    for (int m = 0; m < Dim; ++m)
        for (int c = 0; c < Dim; ++c) gdA[m][c] = gravity_.dot(F.dA[m].col(c));
    d.gradient.resize(nQ, numCoordinates_);
    for (int k = 0; k < nQ; ++k) {
        const double* Gk = Gbuf + k * P;
        for (int m = 0; m < Dim; ++m) {
            double de = Gk[xChord] * unit[m];
            for (int c = 0; c < Dim; ++c) de += Gk[xFrame + c] * gdA[m][c];
            const double dm = 0.5 * gravity_[m] * Gk[xMean];
            d.gradient(k, m) = dm - de;
            d.gradient(k, Dim + m) = dm + de;
        }
        d.gradient(k, iS1) = -Gk[xLength];
        d.gradient(k, iS2) = Gk[xLength];
    }
    using RowMajorView = Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>, 0,
                                    Eigen::OuterStride<>>;
    d.gradient.block(0, iM, nQ, numModal_) = RowMajorView(Gbuf + xModal, nQ, numModal_, Eigen::OuterStride<>(P));
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
    Taylor2 gA[Dim], modal[Dim * kMaxModesPerDirection], out[AxialCondensationData<Dim>::kMaxQuantities];
    const Taylor2 chordT = sqrt(Taylor2(e.squaredNorm(), 2.0 * e.dot(ed), 2.0 * ed.squaredNorm()));
    const Taylor2 lT(l, qdot[iS2] - qdot[iS1], 0.0);
    const Taylor2 gMeanT(gMean, 0.5 * gravity_.dot(qdot.template segment<Dim>(0) + qdot.template segment<Dim>(Dim)),
                         0.0);
    for (int c = 0; c < Dim; ++c)
        gA[c] = Taylor2(gravity_.dot(F.A.col(c)), gravity_.dot(F.Adot.col(c)), gravity_.dot(F.Addot.col(c)));
    for (int j = 0; j < numModal_; ++j) modal[j] = Taylor2(q[iM + j], qdot[iM + j], 0.0);
    quantities(strainRule(e.norm(), l, q.data() + iM), chordT, lT, gA, gMeanT, modal, out);
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
