#include "SimbodyReeving/element/SpanModel.h"

#include "SimbodyReeving/element/GaussLegendre.h"

#include <Eigen/LU>

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>
#include <stdexcept>
#include <string>

namespace SimbodyReeving {
namespace {
// Taut spans (SpanModel::strainTautEverywhere) evaluate their strain integrals by the exact
// midpoint rule of automaticStrainPoints: 7 points instead of Gauss-Legendre's 26 at n_max = 3,
// 3 instead of 17 at n_max = 1, the same integrals to round-off.
}  // namespace

namespace {

template <class T>
[[noreturn]] void throwInvalid(const std::string& where, const std::string& what, const T& value,
                               const std::string& requirement) {
    std::ostringstream msg;
    msg << where << ": " << what << " = " << value << " " << requirement;
    throw std::invalid_argument(msg.str());
}

void checkModeCount(const char* name, int n) {
    if (n < 0 || n > kMaxModesPerDirection)
        throwInvalid("SpanModel", name, n, "is outside 0.." + std::to_string(kMaxModesPerDirection));
}

}  // namespace

void validate(const RopeProperties& p) {
    if (!std::isfinite(p.massPerLength) || !(p.massPerLength > 0))
        throwInvalid("RopeProperties", "massPerLength (rhoA) [kg/m]", p.massPerLength, "must be finite and > 0");
    if (!std::isfinite(p.axialStiffness) || !(p.axialStiffness > 0))
        throwInvalid("RopeProperties", "axialStiffness (EA) [N]", p.axialStiffness, "must be finite and > 0");
    if (!std::isfinite(p.bendingStiffness) || !(p.bendingStiffness >= 0))
        throwInvalid("RopeProperties", "bendingStiffness (EI) [N m^2]", p.bendingStiffness,
                     "must be finite and >= 0");
    if (!std::isfinite(p.axialRetardationTime) || !(p.axialRetardationTime >= 0))
        throwInvalid("RopeProperties", "axialRetardationTime (c) [s]", p.axialRetardationTime, "must be finite and >= 0");
}

double retardationTimeForDampingRatio(double zeta, double omega) {
    if (!std::isfinite(zeta) || !(zeta >= 0))
        throwInvalid("retardationTimeForDampingRatio", "zeta [-]", zeta, "must be finite and >= 0");
    if (!std::isfinite(omega) || !(omega > 0))
        throwInvalid("retardationTimeForDampingRatio", "omega [rad/s]", omega, "must be finite and > 0");
    return 2.0 * zeta / omega;
}

template <int Dim>
int SpanModel<Dim>::automaticQuadraturePoints(int axialModes, int transverseModes, Integrand integrand) {
    // Gauss-Legendre with N points integrates xi^p cos(k pi xi) and xi^p sin(k pi xi), p <= 3, on
    // [0, 1] to round-off (absolute error < 1e-15) once N >= ceil(1.15 k) + 12; measured for
    // k = 0..64 in tests/element/test_gauss_legendre.cpp. With n_max = max(n_a, n_t):
    // - kinetic integrands (B^T B, B^T a, |v|^2): products of two mode functions, k <= 2 n_max,
    //   polynomial factors of degree <= 3 (from N and xi_dot);
    // - strain integrands (eps d eps/dq, eps |u'|^2): eps has k <= 2 n_max and its gradient
    //   another 2 n_max, so k <= 4 n_max, no polynomial factor.
    // Without modes the integrands are polynomials of degree <= 3 (kinetic: 2 points) or
    // constants (strain: 1 point).
    const int nMax = std::max(axialModes, transverseModes);
    if (nMax == 0) return integrand == Integrand::Kinetic ? 2 : 1;
    const int k = (integrand == Integrand::Kinetic ? 2 : 4) * nMax;
    return static_cast<int>(std::ceil(1.15 * k)) + 12;
}

template <int Dim>
int SpanModel<Dim>::automaticStrainPoints(int axialModes, int transverseModes) {
    // Strain integrands are cosine series with at most 4 n_max half-waves; the N-point midpoint
    // rule is exact for k < 2N (see the header).
    return 2 * std::max(axialModes, transverseModes) + 1;
}

template <int Dim>
SpanModel<Dim>::SpanModel(const RopeProperties& properties, const SpanOptions& options, const Vec& gravity,
                          const Mat& referenceFrame)
    : properties_(properties), options_(options), gravity_(gravity), referenceFrame_(referenceFrame) {
    validate(properties_);
    checkModeCount("SpanOptions::axialModes (n_a)", options_.axialModes);
    checkModeCount("SpanOptions::transverseModes (n_t)", options_.transverseModes);
    if (options_.quadraturePoints < 0 || options_.quadraturePoints > 200)
        throwInvalid("SpanModel", "SpanOptions::quadraturePoints", options_.quadraturePoints,
                     "is outside 0..200 (0 = automatic)");
    if (!(options_.transverseDampingRatio >= 0 && options_.transverseDampingRatio <= 1.0))
        throwInvalid("SpanModel", "SpanOptions::transverseDampingRatio (zeta_t)", options_.transverseDampingRatio,
                     "must be in [0, 1]");
    if (!(options_.quasiStaticSlackStiffness >= 1e-9 && options_.quasiStaticSlackStiffness <= 1.0))
        throwInvalid("SpanModel", "SpanOptions::quasiStaticSlackStiffness (delta)", options_.quasiStaticSlackStiffness,
                     "must be in [1e-9, 1]");
    if (!(options_.quasiStaticSlackTransitionStrain >= 1e-12 && options_.quasiStaticSlackTransitionStrain <= 1e-3))
        throwInvalid("SpanModel", "SpanOptions::quasiStaticSlackTransitionStrain (eps_s)",
                     options_.quasiStaticSlackTransitionStrain, "must be in [1e-12, 1e-3]");
    if (!(options_.quasiStaticTransverseSlackStiffness >= 1e-12 && options_.quasiStaticTransverseSlackStiffness <= 1e-3))
        throwInvalid("SpanModel", "SpanOptions::quasiStaticTransverseSlackStiffness (delta_t)",
                     options_.quasiStaticTransverseSlackStiffness, "must be in [1e-12, 1e-3]");
    if (condensesTransverseModes()) {
        if (options_.elasticModel == ElasticEnergyModel::PaperLiteral)
            throw std::invalid_argument(
                "SpanModel: SpanOptions::transverseDynamics = QuasiStatic requires elasticModel = Consistent (got "
                "PaperLiteral)");
        if (options_.axialDynamics == AxialDynamics::Dynamic && options_.axialModes > 0)
            throw std::invalid_argument(
                "SpanModel: SpanOptions::transverseDynamics = QuasiStatic requires axialDynamics = QuasiStatic when "
                "n_a > 0 (the axial modes are the stiffer ones: condense them too, or keep the transverse modes "
                "Dynamic)");
        if (options_.transverseDampingRatio > 0)
            throwInvalid("SpanModel", "SpanOptions::transverseDampingRatio (zeta_t)", options_.transverseDampingRatio,
                         "must be 0 with transverseDynamics = QuasiStatic (condensed modes do not vibrate)");
    }
    law_ = AxialLaw(properties_, slackRegularised() ? options_.quasiStaticSlackTransitionStrain : 0.0);
    if (properties_.tensionOnly && options_.elasticModel == ElasticEnergyModel::PaperLiteral)
        throw std::invalid_argument(
            "SpanModel: RopeProperties::tensionOnly requires elasticModel = Consistent (PaperLiteral's string "
            "energy is linear in the strain: clamped at zero it would not be differentiable)");
    if (options_.axialDynamics == AxialDynamics::QuasiStatic && options_.axialModes > 0 &&
        options_.elasticModel == ElasticEnergyModel::PaperLiteral)
        throw std::invalid_argument(
            "SpanModel: SpanOptions::axialDynamics = QuasiStatic (the default) with axial modes requires "
            "elasticModel = Consistent (got PaperLiteral); set axialDynamics = Dynamic for the paper's energy");
    // mutation-site: rope-weight
    if (!gravity_.allFinite()) {
        std::ostringstream v;
        v << "(" << gravity_.transpose() << ")";
        throwInvalid("SpanModel", "gravity [m/s^2]", v.str(), "must be finite");
    }
    if (Dim == 3) {
        const double orthErr = (referenceFrame_.transpose() * referenceFrame_ - Mat::Identity()).norm();
        if (!referenceFrame_.allFinite() || !(orthErr < 1e-9) || !(referenceFrame_.determinant() > 0)) {
            std::ostringstream v;
            v << "[" << referenceFrame_.row(0) << "; ...] (|A0^T A0 - I| = " << orthErr << ")";
            throwInvalid("SpanModel", "referenceFrame", v.str(), "must be orthonormal and right-handed");
        }
    } else {
        referenceFrame_.setIdentity();
    }
    numModal_ = options_.axialModes + (Dim - 1) * options_.transverseModes;
    maxMode_ = std::max(options_.axialModes, options_.transverseModes);

    const double pi = std::acos(-1.0);
    auto makeTable = [&](Integrand integrand, QuadratureTable& table) {
        const int nq = options_.quadraturePoints > 0
                           ? options_.quadraturePoints
                           : automaticQuadraturePoints(options_.axialModes, options_.transverseModes, integrand);
        const GaussLegendreRule rule = makeGaussLegendreRule(nq);
        table.xi = Eigen::Map<const Eigen::VectorXd>(rule.nodes.data(), nq);
        table.w = Eigen::Map<const Eigen::VectorXd>(rule.weights.data(), nq);
        table.sin.resize(nq, maxMode_);
        table.dsin.resize(nq, maxMode_);
        for (int k = 0; k < nq; ++k)
            for (int i = 0; i < maxMode_; ++i) {
                const double kw = (i + 1) * pi;
                table.sin(k, i) = std::sin(kw * table.xi[k]);
                table.dsin(k, i) = kw * std::cos(kw * table.xi[k]);
            }
    };
    makeTable(Integrand::Kinetic, kineticTable_);
    makeTable(Integrand::Strain, strainTable_);
    if (options_.quadraturePoints == 0) {
        const int nq = automaticStrainPoints(options_.axialModes, options_.transverseModes);
        const GaussLegendreRule rule = makeMidpointRule(nq);
        tautStrainTable_.xi = Eigen::Map<const Eigen::VectorXd>(rule.nodes.data(), nq);
        tautStrainTable_.w = Eigen::Map<const Eigen::VectorXd>(rule.weights.data(), nq);
        tautStrainTable_.sin.resize(nq, maxMode_);
        tautStrainTable_.dsin.resize(nq, maxMode_);
        for (int k = 0; k < nq; ++k)
            for (int i = 0; i < maxMode_; ++i) {
                const double kw = (i + 1) * pi;
                tautStrainTable_.sin(k, i) = std::sin(kw * tautStrainTable_.xi[k]);
                tautStrainTable_.dsin(k, i) = kw * std::cos(kw * tautStrainTable_.xi[k]);
            }
    }
    // Moments of the kinetic rule for the closed-form mass matrix.
    {
        const int m = maxMode_;
        KineticMoments& km = moments_;
        km.alpha.setZero(m);
        km.beta.setZero(m);
        km.sinSin.setZero(m, m);
        for (int p = 0; p < 3; ++p) {
            km.slope[p].setZero(m);
            km.slopeSlope[p].setZero(m, m);
        }
        for (int p = 0; p < 2; ++p) km.slopeSin[p].setZero(m, m);
        const QuadratureTable& t = kineticTable_;
        for (int k = 0; k < t.xi.size(); ++k) {
            const double xi = t.xi[k], w = t.w[k];
            const double omega[3] = {(1.0 - xi) * (1.0 - xi), xi * (1.0 - xi), xi * xi};
            const double lin[2] = {1.0 - xi, xi};
            for (int p = 0; p < 3; ++p) km.poly[p] += w * omega[p];
            for (int i = 0; i < m; ++i) {
                km.alpha[i] += w * lin[0] * t.sin(k, i);
                km.beta[i] += w * lin[1] * t.sin(k, i);
                for (int p = 0; p < 3; ++p) km.slope[p][i] += w * omega[p] * t.dsin(k, i);
                for (int j = 0; j < m; ++j) {
                    for (int p = 0; p < 2; ++p) km.slopeSin[p](i, j) += w * lin[p] * t.dsin(k, i) * t.sin(k, j);
                    if (j < i) continue;  // symmetric moments: upper triangle, mirrored below
                    km.sinSin(i, j) += w * t.sin(k, i) * t.sin(k, j);
                    for (int p = 0; p < 3; ++p) km.slopeSlope[p](i, j) += w * omega[p] * t.dsin(k, i) * t.dsin(k, j);
                }
            }
        }
        for (int i = 0; i < m; ++i)
            for (int j = 0; j < i; ++j) {
                km.sinSin(i, j) = km.sinSin(j, i);
                for (int p = 0; p < 3; ++p) km.slopeSlope[p](i, j) = km.slopeSlope[p](j, i);
            }
    }
    sinMean_.resize(maxMode_);
    bendFactor_.resize(maxMode_);
    for (int i = 0; i < maxMode_; ++i) {
        const double kw = (i + 1) * pi;
        sinMean_[i] = ((i + 1) % 2 == 1) ? 2.0 / kw : 0.0;  // int_0^1 sin(k pi xi) dxi
        bendFactor_[i] = 0.5 * kw * kw * kw * kw;             // int_0^1 (S_i'')^2 dxi
    }
}

template <int Dim>
void SpanModel<Dim>::checkState(const Eigen::Ref<const Eigen::VectorXd>& q, const char* name) const {
    if (q.size() != numCoordinates())
        throwInvalid("SpanModel", std::string("size of ") + name, q.size(),
                     "differs from numCoordinates() = " + std::to_string(numCoordinates()));
    // x * 0 is 0 for finite x and NaN for inf or NaN: one vectorised sum tests every entry.
    if (std::isfinite((q.array() * 0.0).sum())) return;
    for (int k = 0; k < q.size(); ++k)
        if (!std::isfinite(q[k]))
            throwInvalid("SpanModel", std::string(name) + "[" + std::to_string(k) + "]", q[k], "must be finite");
}

template <int Dim>
double SpanModel<Dim>::checkMaterialPoint(const Eigen::Ref<const Eigen::VectorXd>& q, double s) const {
    checkState(q, "q");
    const double s1 = q[s1Index()], s2 = q[s2Index()];
    const double l = s2 - s1;
    if (!(l > 0)) throwInvalid("SpanModel", "span length l = s2 - s1 [m]", l, "must be > 0");
    // Points computed as s1 + (s2 - s1) k / n may round a few ulp past an end: accept 1e-12 l.
    const double slack = 1e-12 * l;
    if (!std::isfinite(s) || s < s1 - slack || s > s2 + slack) {
        std::ostringstream range;
        range << std::setprecision(17) << "is outside the span [s1, s2] = [" << s1 << ", " << s2 << "]";
        std::ostringstream value;
        value << std::setprecision(17) << s;
        throwInvalid("SpanModel", "material coordinate s [m]", value.str(), range.str());
    }
    return std::clamp((s - s1) / l, 0.0, 1.0);
}

namespace {

/// u = S(xi) q_m in the element frame, from one row of mode values (sin or its xi-derivative).
template <int Dim, class Row, class Modal>
Eigen::Matrix<double, Dim, 1> modesToLocal(const Row& row, const Modal& qm, int na, int nt) {
    Eigen::Matrix<double, Dim, 1> u = Eigen::Matrix<double, Dim, 1>::Zero();
    for (int i = 0; i < na; ++i) u[0] += row[i] * qm[i];
    for (int d = 1; d < Dim; ++d)
        for (int i = 0; i < nt; ++i) u[d] += row[i] * qm[na + (d - 1) * nt + i];
    return u;
}

/// out[modal] += scale * S(xi)^T y (y a local-frame vector).
template <int Dim, class Row, class Out>
void addLocalToModes(const Row& row, const Eigen::Matrix<double, Dim, 1>& y, double scale, int na, int nt,
                     Out&& out) {
    for (int i = 0; i < na; ++i) out[i] += scale * row[i] * y[0];
    for (int d = 1; d < Dim; ++d)
        for (int i = 0; i < nt; ++i) out[na + (d - 1) * nt + i] += scale * row[i] * y[d];
}

}  // namespace

template <int Dim>
void SpanModel<Dim>::evaluate(const Eigen::Ref<const Eigen::VectorXd>& q,
                              const Eigen::Ref<const Eigen::VectorXd>& qdot, Data& d) const {
    checkState(q, "q");
    checkState(qdot, "qdot");
    const int n = numCoordinates();
    const int na = options_.axialModes, nt = options_.transverseModes, nm = numModal_;
    const int iM = 2 * Dim, iS1 = s1Index(), iS2 = s2Index();
    const bool complete = options_.velocityModel == VelocityModel::Complete;
    const bool literal = options_.elasticModel == ElasticEnergyModel::PaperLiteral;
    const double rhoA = properties_.massPerLength, EA = properties_.axialStiffness;
    const double EI = properties_.bendingStiffness;

    const Vec r1 = q.template segment<Dim>(0), r2 = q.template segment<Dim>(Dim);
    const Vec r1d = qdot.template segment<Dim>(0), r2d = qdot.template segment<Dim>(Dim);
    const auto qm = q.segment(iM, nm);
    const auto qmd = qdot.segment(iM, nm);
    const double s1 = q[iS1], s2 = q[iS2], s1d = qdot[iS1], s2d = qdot[iS2];
    const double l = s2 - s1, ld = s2d - s1d;
    if (!(l > 0)) throwInvalid("SpanModel::evaluate", "span length l = s2 - s1 [m]", l, "must be > 0");
    const Vec e = r2 - r1, ed = r2d - r1d;
    if (!(e.norm() > 1e-12 * l)) {
        std::ostringstream v;
        v << "(" << e.transpose() << ")";
        throwInvalid("SpanModel::evaluate", "chord r2 - r1 [m]", v.str(), "is zero: end nodes coincide");
    }

    ChordFrame<Dim>& F = d.frame;
    computeChordFrame<Dim>(e, ed, referenceFrame_, F);
    const Mat& A = F.A;

    d.massMatrix.resize(n, n);
    d.velocityForces.setZero(n);
    d.elasticForces.setZero(n);  // accumulates dU/dq, negated at the end
    d.gravityForces.setZero(n);
    d.kineticEnergy = d.axialEnergy = d.bendingEnergy = d.stringEnergy = d.gravityEnergy = 0;
    auto& Qv = d.velocityForces;
    auto& gradU = d.elasticForces;

    // Modal amplitudes and rates as local vectors per mode number: U.col(i) = (a_i, b_i[, c_i])
    // (zero where mode i + 1 exceeds n_a or n_t), so that u(xi) = sum_i S_i(xi) U.col(i).
    const int m = maxMode_;
    ModeVectors U, Ud;
    U.leftCols(m).setZero();
    Ud.leftCols(m).setZero();
    for (int i = 0; i < na; ++i) {
        U(0, i) = qm[i];
        Ud(0, i) = qmd[i];
    }
    for (int dir = 1; dir < Dim; ++dir)
        for (int i = 0; i < nt; ++i) {
            U(dir, i) = qm[na + (dir - 1) * nt + i];
            Ud(dir, i) = qmd[na + (dir - 1) * nt + i];
        }
    // Coordinate index of mode i in local direction dir, or -1 if the span has no such mode.
    auto modalIndex = [&](int dir, int i) {
        if (dir == 0) return i < na ? iM + i : -1;
        return i < nt ? iM + na + (dir - 1) * nt + i : -1;
    };

    // ---- mass matrix M = rhoA l sum_k w_k B_k^T B_k, in closed form over the rule's moments ----
    // B's columns are r1: (1 - xi) e_m - dA[m] u, r2: xi e_m + dA[m] u, mode (dir, i): S_i A_dir,
    // s1: -(1 - xi) tv / l, s2: -xi tv / l, with tv = e + A u' (Complete; Simplified drops the
    // dA[m] u terms and has tv = e). Every product is a sum of the moments of KineticMoments times
    // coefficients of this state, so M is the quadrature sum rearranged (no per-point work).
    {
        const KineticMoments& km = moments_;
        auto& M = d.massMatrix;
        const double c = rhoA * l;
        const Vec eLocal = A.transpose() * e;  // |e| (1, 0[, 0])
        // Mode-mode block: delta_dir,dir' sum w S_i S_j.
        for (int dir = 0; dir < Dim; ++dir)
            for (int i = 0; i < m; ++i) {
                const int a = modalIndex(dir, i);
                if (a < 0) continue;
                for (int dir2 = 0; dir2 < Dim; ++dir2)
                    for (int j = 0; j < m; ++j) {
                        const int b = modalIndex(dir2, j);
                        if (b >= 0) M(a, b) = dir == dir2 ? c * km.sinSin(i, j) : 0.0;
                    }
            }
        if (complete) {
            Vec uA = Vec::Zero(), uB = Vec::Zero();                   // sum w (1 - xi) u, sum w xi u
            Vec cs[3] = {Vec::Zero(), Vec::Zero(), Vec::Zero()};      // sum w omega_p u'
            Mat Ut = Mat::Zero(), V0 = Mat::Zero(), V1 = Mat::Zero();  // sum w u u^T, sum w (1-xi) u u'^T, ...xi
            double P[3] = {0, 0, 0};                                  // sum w omega_p |u'|^2
            ModeVectors Um, H0, H1;  // Um.col(j) = sum w u S_j, H_p.col(j) = sum w lin_p u' S_j
            for (int j = 0; j < m; ++j) {
                const Vec uj = U.col(j);
                uA += km.alpha[j] * uj;
                uB += km.beta[j] * uj;
                for (int p = 0; p < 3; ++p) cs[p] += km.slope[p][j] * uj;
                Vec um = Vec::Zero(), h0 = Vec::Zero(), h1 = Vec::Zero();
                for (int i = 0; i < m; ++i) {
                    um += km.sinSin(i, j) * U.col(i);
                    h0 += km.slopeSin[0](i, j) * U.col(i);
                    h1 += km.slopeSin[1](i, j) * U.col(i);
                    const double ui_uj = U.col(i).dot(uj);
                    for (int p = 0; p < 3; ++p) P[p] += km.slopeSlope[p](i, j) * ui_uj;
                }
                Um.col(j) = um;
                H0.col(j) = h0;
                H1.col(j) = h1;
                Ut.noalias() += um * uj.transpose();
                V0.noalias() += uj * h0.transpose();
                V1.noalias() += uj * h1.transpose();
            }
            Vec WA[Dim], WB[Dim];  // dA[m] sum w (1 - xi) u, dA[m] sum w xi u (global)
            Mat DU[Dim];           // dA[m] Ut
            double trV0[Dim], trV1[Dim];  // sum w (1 - xi) (A u') . (dA[m] u), ... xi
            for (int mm = 0; mm < Dim; ++mm) {
                WA[mm] = F.dA[mm] * uA;
                WB[mm] = F.dA[mm] * uB;
                DU[mm] = F.dA[mm] * Ut;
                const Mat K = A.transpose() * F.dA[mm];
                trV0[mm] = (K * V0).trace();
                trV1[mm] = (K * V1).trace();
            }
            for (int mm = 0; mm < Dim; ++mm)
                for (int nn = 0; nn < Dim; ++nn) {
                    const double tr = DU[mm].cwiseProduct(F.dA[nn]).sum();  // sum w (dA[m] u) . (dA[n] u)
                    const double delta = mm == nn ? 1.0 : 0.0;
                    M(mm, Dim + nn) = c * (km.poly[1] * delta + WA[nn][mm] - WB[mm][nn] - tr);
                    M(Dim + nn, mm) = M(mm, Dim + nn);
                    if (nn < mm) continue;  // the diagonal blocks are symmetric: mirrored exactly
                    M(mm, nn) = M(nn, mm) = c * (km.poly[0] * delta - WA[nn][mm] - WA[mm][nn] + tr);
                    M(Dim + mm, Dim + nn) = M(Dim + nn, Dim + mm) =
                        c * (km.poly[2] * delta + WB[nn][mm] + WB[mm][nn] + tr);
                }
            const Vec Ac[3] = {A * cs[0], A * cs[1], A * cs[2]};
            for (int mm = 0; mm < Dim; ++mm) {
                const double eWA = e.dot(WA[mm]), eWB = e.dot(WB[mm]);
                M(iS1, mm) = -rhoA * (km.poly[0] * e[mm] + Ac[0][mm] - eWA - trV0[mm]);
                M(iS1, Dim + mm) = -rhoA * (km.poly[1] * e[mm] + Ac[1][mm] + eWA + trV0[mm]);
                M(iS2, mm) = -rhoA * (km.poly[1] * e[mm] + Ac[1][mm] - eWB - trV1[mm]);
                M(iS2, Dim + mm) = -rhoA * (km.poly[2] * e[mm] + Ac[2][mm] + eWB + trV1[mm]);
            }
            for (int j = 0; j < m; ++j) {
                Vec KU[Dim];  // A^T dA[m] Um_j (local)
                for (int mm = 0; mm < Dim; ++mm) KU[mm] = A.transpose() * (F.dA[mm] * Um.col(j));
                for (int dir = 0; dir < Dim; ++dir) {
                    const int b = modalIndex(dir, j);
                    if (b < 0) continue;
                    for (int mm = 0; mm < Dim; ++mm) {
                        M(mm, b) = c * (A(mm, dir) * km.alpha[j] - KU[mm][dir]);
                        M(Dim + mm, b) = c * (A(mm, dir) * km.beta[j] + KU[mm][dir]);
                    }
                    M(iS1, b) = -rhoA * (eLocal[dir] * km.alpha[j] + H0(dir, j));
                    M(iS2, b) = -rhoA * (eLocal[dir] * km.beta[j] + H1(dir, j));
                }
            }
            const double e2 = e.squaredNorm();
            M(iS1, iS1) = rhoA / l * (km.poly[0] * e2 + 2.0 * eLocal.dot(cs[0]) + P[0]);
            M(iS2, iS1) = rhoA / l * (km.poly[1] * e2 + 2.0 * eLocal.dot(cs[1]) + P[1]);
            M(iS2, iS2) = rhoA / l * (km.poly[2] * e2 + 2.0 * eLocal.dot(cs[2]) + P[2]);
        } else {
            for (int mm = 0; mm < Dim; ++mm)
                for (int nn = 0; nn < Dim; ++nn) {
                    const double delta = mm == nn ? 1.0 : 0.0;
                    M(mm, nn) = c * km.poly[0] * delta;
                    M(mm, Dim + nn) = M(Dim + nn, mm) = c * km.poly[1] * delta;
                    M(Dim + mm, Dim + nn) = c * km.poly[2] * delta;
                }
            for (int mm = 0; mm < Dim; ++mm) {
                M(iS1, mm) = -rhoA * km.poly[0] * e[mm];
                M(iS1, Dim + mm) = -rhoA * km.poly[1] * e[mm];
                M(iS2, mm) = -rhoA * km.poly[1] * e[mm];
                M(iS2, Dim + mm) = -rhoA * km.poly[2] * e[mm];
            }
            for (int j = 0; j < m; ++j)
                for (int dir = 0; dir < Dim; ++dir) {
                    const int b = modalIndex(dir, j);
                    if (b < 0) continue;
                    for (int mm = 0; mm < Dim; ++mm) {
                        M(mm, b) = c * A(mm, dir) * km.alpha[j];
                        M(Dim + mm, b) = c * A(mm, dir) * km.beta[j];
                    }
                    M(iS1, b) = -rhoA * eLocal[dir] * km.alpha[j];
                    M(iS2, b) = -rhoA * eLocal[dir] * km.beta[j];
                }
            const double e2 = e.squaredNorm();
            M(iS1, iS1) = rhoA / l * km.poly[0] * e2;
            M(iS2, iS1) = rhoA / l * km.poly[1] * e2;
            M(iS2, iS2) = rhoA / l * km.poly[2] * e2;
        }
        // Mirror: the rows of s1, s2 and the node-mode block were written once.
        for (int b = 0; b < iS1; ++b) {
            M(b, iS1) = M(iS1, b);
            M(b, iS2) = M(iS2, b);
        }
        M(iS1, iS2) = M(iS2, iS1);
        for (int a = 0; a < 2 * Dim; ++a)
            for (int b = iM; b < iS1; ++b) M(b, a) = M(a, b);
    }

    // ---- velocity forces and kinetic energy, by quadrature ----------------------------------
    // Q_v = -sum_k rhoA w_k [ B^T (ldot v + l a) + l D ] + 1/2 rhoA sum_k w_k |v|^2 (d/ds2 - d/ds1)
    // with v = B qdot, a = Bdot qdot and D the partial derivative of |v|^2 / 2 (at fixed qdot) that
    // is not B^T-shaped; B^T is applied column block by column block (no B matrix is formed).
    double sumV2 = 0;  // sum_k w_k |v_k|^2
    Vec qR1 = Vec::Zero(), qR2 = Vec::Zero();  // accumulate -Q_v / rhoA on r1, r2
    ModeVectors qModes;                        // ... and on the modes, per mode number
    qModes.leftCols(m).setZero();
    double qS1 = 0, qS2 = 0;
    const Mat At = A.transpose();
    for (int k = 0; k < kineticTable_.xi.size(); ++k) {
        const double xi = kineticTable_.xi[k], w = kineticTable_.w[k];
        const double* sinRow = kineticTable_.sin.data() + k * m;
        const double* dsinRow = kineticTable_.dsin.data() + k * m;
        Vec u = Vec::Zero(), up = Vec::Zero(), ud = Vec::Zero(), upd = Vec::Zero();
        for (int i = 0; i < m; ++i) {
            u += sinRow[i] * U.col(i);
            up += dsinRow[i] * U.col(i);
            ud += sinRow[i] * Ud.col(i);
            upd += dsinRow[i] * Ud.col(i);
        }
        const double g1 = -(1.0 - xi) / l, g2 = -xi / l;  // xi_dot = g1 s1dot + g2 s2dot
        const double g1d = -g1 * ld / l, g2d = -g2 * ld / l;
        const double xid = g1 * s1d + g2 * s2d;
        if (complete) {
            const Vec t = e + A * up;  // r_xi, the (unnormalised) tangent, convected by xi_dot
            const Vec v = (1.0 - xi) * r1d + xi * r2d + F.Adot * u + A * ud + xid * t;
            const Vec tvd = ed + F.Adot * up + A * upd;
            const Vec a = F.Addot * u + 2.0 * (F.Adot * ud) - xid * ld / l * t + xid * tvd;
            const Vec x = ld * v + l * a;
            Vec Wx, Wpv;  // (dA[m] u) . x, (dA[m] u') . v
            for (int mm = 0; mm < Dim; ++mm) {
                Wx[mm] = (F.dA[mm] * u).dot(x);
                Wpv[mm] = (F.dA[mm] * up).dot(v);
            }
            const Vec dR1 = xid * (v + Wpv);
            qR1 += w * ((1.0 - xi) * x - Wx + l * dR1);
            qR2 += w * (xi * x + Wx - l * dR1);
            // modes: B^T x = S_i A^T x; D_m = -xi_dot S'^T A^T v
            const Vec Ax = At * x, Av = (l * xid) * (At * v);
            for (int i = 0; i < m; ++i) qModes.col(i) += w * (sinRow[i] * Ax - dsinRow[i] * Av);
            const double tx = t.dot(x), tv_v = t.dot(v);
            qS1 += w * (g1 * tx + l * ((g1d * t + g1 * tvd).dot(v) - xid * tv_v / l));
            qS2 += w * (g2 * tx + l * ((g2d * t + g2 * tvd).dot(v) + xid * tv_v / l));
            sumV2 += w * v.squaredNorm();
        } else {
            const Vec v = (1.0 - xi) * r1d + xi * r2d + A * ud + xid * e;
            const Vec a = F.Adot * ud - xid * ld / l * e + xid * ed;
            const Vec x = ld * v + l * a;
            Vec dR1;
            for (int mm = 0; mm < Dim; ++mm) dR1[mm] = v.dot(F.dA[mm] * ud);
            dR1 += xid * v;
            qR1 += w * ((1.0 - xi) * x + l * dR1);
            qR2 += w * (xi * x - l * dR1);
            // modes: B^T x = S_i A^T x; D_m = S^T Adot^T v
            const Vec Ax = At * x + l * (F.Adot.transpose() * v);
            for (int i = 0; i < m; ++i) qModes.col(i) += (w * sinRow[i]) * Ax;
            const double tx = e.dot(x), tv_v = e.dot(v);
            qS1 += w * (g1 * tx + l * ((g1d * e + g1 * ed).dot(v) - xid * tv_v / l));
            qS2 += w * (g2 * tx + l * ((g2d * e + g2 * ed).dot(v) + xid * tv_v / l));
            sumV2 += w * v.squaredNorm();
        }
    }
    Qv.template segment<Dim>(0) = -rhoA * qR1;
    Qv.template segment<Dim>(Dim) = -rhoA * qR2;
    for (int dir = 0; dir < Dim; ++dir)
        for (int i = 0; i < m; ++i) {
            const int b = modalIndex(dir, i);
            if (b >= 0) Qv[b] = -rhoA * qModes(dir, i);
        }
    Qv[iS1] = -rhoA * qS1 - 0.5 * rhoA * sumV2;
    Qv[iS2] = -rhoA * qS2 + 0.5 * rhoA * sumV2;
    d.kineticEnergy = 0.5 * rhoA * l * sumV2;  // mutation-site: qv-forces

    // ---- axial strain energy: U_ax = 1/2 EA l sum w eps^2, eps = 1/2(|t|^2/l^2 - 1) ------------
    {
        const double l2 = l * l;
        Vec gE = Vec::Zero();  // sum coef d eps/de (dU/dr2 = gE = -dU/dr1)
        ModeVectors gModes;    // dU/dq_m per mode number, local directions
        gModes.leftCols(m).setZero();
        double gL = 0;         // dU/dl
        // The exact midpoint rule where the bound proves the span taut, else Gauss-Legendre.
        const QuadratureTable& rule = strainTautEverywhere(e.norm(), l, qm.data()) ? tautStrainTable_ : strainTable_;
        for (int k = 0; k < rule.xi.size(); ++k) {
            const double w = rule.w[k];
            const double* dsinRow = rule.dsin.data() + k * m;
            Vec up = Vec::Zero();  // du/dxi
            for (int i = 0; i < m; ++i) up += dsinRow[i] * U.col(i);
            const Vec t = e + A * up;
            const double t2 = t.squaredNorm();
            const double eps = 0.5 * (t2 / l2 - 1.0);
            // Tension-only law: a slack point (eps <= 0) stores no energy and feels no axial force.
            if (law_.slack(eps)) continue;
            const double energyDensity = law_.F(eps);  // U_ax = EA l sum w F(eps), F' = f (AxialLaw)
            d.axialEnergy += EA * l * w * energyDensity;
            // d eps/dr2 = (I + W')^T t / l^2 with W' col m = dA[m] u', d eps/dq_m = S'^T A^T t / l^2,
            // d eps/dl = -|t|^2 / l^3
            Vec deps_de = t;
            for (int mm = 0; mm < Dim; ++mm) deps_de[mm] += (F.dA[mm] * up).dot(t);
            double coef = EA * l * w * law_.f(eps);  // dU/deps at this point
            double dU_dl = EA * w * energyDensity;
            Vec modal = (coef / l2) * (A.transpose() * t);  // local vector multiplying S_i'
            if (literal) {
                // U_str = EA/(2 l) w eps |u'_perp|^2
                double h = 0;
                for (int dd = 1; dd < Dim; ++dd) h += up[dd] * up[dd];
                d.stringEnergy += 0.5 * EA / l * w * eps * h;
                coef += 0.5 * EA / l * w * h;
                dU_dl += -0.5 * EA / l2 * w * eps * h;
                modal = (coef / l2) * (A.transpose() * t);
                for (int dd = 1; dd < Dim; ++dd) modal[dd] += EA / l * w * eps * up[dd];
            }
            gE += (coef / l2) * deps_de;
            for (int i = 0; i < m; ++i) gModes.col(i) += dsinRow[i] * modal;
            gL += dU_dl - coef * t2 / (l2 * l);
        }
        gradU.template segment<Dim>(0) -= gE;
        gradU.template segment<Dim>(Dim) += gE;
        for (int dir = 0; dir < Dim; ++dir)
            for (int i = 0; i < m; ++i) {
                const int b = modalIndex(dir, i);
                if (b >= 0) gradU[b] += gModes(dir, i);
            }
        gradU[iS1] -= gL;
        gradU[iS2] += gL;
    }

    // ---- bending, closed form: U_b = EI/(2 l^3) sum_i (i pi)^4/2 q_i^2 over transverse modes ----
    if (EI > 0) {
        const double c = EI / (l * l * l);
        double sum = 0;
        const int first = literal ? 0 : na;  // PaperLiteral: kappa = |r_ss| includes axial modes
        for (int j = first; j < nm; ++j) {
            const int i = j < na ? j : (j - na) % nt;
            sum += bendFactor_[i] * qm[j] * qm[j];
            gradU[iM + j] += c * bendFactor_[i] * qm[j];
        }
        d.bendingEnergy = 0.5 * c * sum;
        const double dUb_dl = -3.0 * d.bendingEnergy / l;
        gradU[iS1] -= dUb_dl;
        gradU[iS2] += dUb_dl;
    }

    // ---- slack regularisation (tension-only, quasi-static axial modes):
    //      U_delta = delta EA / (4 l) sum_i (i pi)^2 q_a,i^2, dU_delta/dl = -U_delta / l ---------------
    d.slackRegularisationEnergy = 0;
    if (slackRegularised()) {
        const double c = options_.quasiStaticSlackStiffness * EA / (4.0 * l);
        double sum = 0;
        if (condensesAxialModes())
            for (int i = 0; i < na; ++i) {
                const double k2 = axialModeWavenumberSquared(i);
                sum += k2 * qm[i] * qm[i];
                gradU[iM + i] += 2.0 * c * k2 * qm[i];
            }
        d.slackRegularisationEnergy = c * sum;
        // Condensed transverse amplitudes: delta_t EA / (4 l) sum (i pi)^2 |q_t,i|^2.
        if (condensesTransverseModes()) {
            const double ct = options_.quasiStaticTransverseSlackStiffness * EA / (4.0 * l);
            double sumT = 0;
            for (int j = na; j < nm; ++j) {
                const double k2 = axialModeWavenumberSquared((j - na) % nt);
                sumT += k2 * qm[j] * qm[j];
                gradU[iM + j] += 2.0 * ct * k2 * qm[j];
            }
            d.slackRegularisationEnergy += ct * sumT;
        }
        gradU[iS1] += d.slackRegularisationEnergy / l;
        gradU[iS2] -= d.slackRegularisationEnergy / l;
    }
    d.elasticForces = -gradU;

    // ---- gravity, closed form: U_g = -rhoA l g . (r1 + r2)/2 + A ubar), ubar = int S q_m ----
    const Vec ubar = modesToLocal<Dim>(sinMean_, qm, na, nt);
    const Vec rMean = 0.5 * (r1 + r2) + A * ubar;
    const double gr = gravity_.dot(rMean);
    d.gravityEnergy = -rhoA * l * gr;
    Vec dRdE;  // (d(A ubar)/de)^T g
    for (int m = 0; m < Dim; ++m) dRdE[m] = gravity_.dot(F.dA[m] * ubar);
    auto& Qg = d.gravityForces;
    Qg.template segment<Dim>(0) = rhoA * l * (0.5 * gravity_ - dRdE);
    Qg.template segment<Dim>(Dim) = rhoA * l * (0.5 * gravity_ + dRdE);
    addLocalToModes<Dim>(sinMean_, Vec(A.transpose() * gravity_), rhoA * l, na, nt, Qg.segment(iM, nm));
    Qg[iS1] = -rhoA * gr;
    Qg[iS2] = rhoA * gr;

    d.dampingForces.setZero(n);
    d.dampingPower = 0;
    if (properties_.axialRetardationTime > 0) addAxialDamping(q, qdot, U, Ud, d);
    if (options_.transverseDampingRatio > 0 && nt > 0) addTransverseDamping(q, qdot, U, d);

    // Finite inputs can still overflow (e.g. EA = 1e300 with a large strain): never return inf/NaN.
    if (!(std::isfinite(d.kineticEnergy + d.strainEnergy() + d.gravityEnergy) &&
          std::isfinite((d.massMatrix.array() * 0.0).sum() + (d.velocityForces.array() * 0.0).sum() +
                        (d.elasticForces.array() * 0.0).sum() + (d.gravityForces.array() * 0.0).sum())))
        throw std::domain_error("SpanModel::evaluate: the result overflowed (non-finite energy, mass matrix or "
                                "forces) for finite inputs; the state or the rope parameters are out of range");
}

template <int Dim>
void SpanModel<Dim>::addTransverseDamping(const Eigen::Ref<const Eigen::VectorXd>& q,
                                          const Eigen::Ref<const Eigen::VectorXd>& qdot, const ModeVectors& U,
                                          Data& d) const {
    const int m = maxMode_, na = options_.axialModes, nt = options_.transverseModes;
    const Vec e = q.template segment<Dim>(Dim) - q.template segment<Dim>(0);
    const double l = q[s2Index()] - q[s1Index()], l2 = l * l;
    double meanStrain = 0;
    for (int k = 0; k < strainTable_.xi.size(); ++k) {
        const double* dsinRow = strainTable_.dsin.data() + k * m;
        Vec up = Vec::Zero();
        for (int i = 0; i < m; ++i) up += dsinRow[i] * U.col(i);
        meanStrain += strainTable_.w[k] * 0.5 * ((e + d.frame.A * up).squaredNorm() / l2 - 1.0);
    }
    const double rhoA = properties_.massPerLength;
    const double P = properties_.axialStiffness * std::max(meanStrain, 0.0), pi = std::acos(-1.0);
    for (int i = 0; i < nt; ++i) {
        const double k = (i + 1) * pi / l;
        const double omega = std::sqrt((k * k * P + k * k * k * k * properties_.bendingStiffness) / rhoA);
        const double coefficient = 2.0 * options_.transverseDampingRatio * omega * 0.5 * rhoA * l;
        for (int dir = 1; dir < Dim; ++dir) {
            const int b = 2 * Dim + na + (dir - 1) * nt + i;
            d.dampingForces[b] -= coefficient * qdot[b];
            d.dampingPower += coefficient * qdot[b] * qdot[b];
        }
    }
}

// Kelvin-Voigt damping (RopeProperties::axialRetardationTime): at each strain point xi_k,
//     Deps/Dt = b . qdot,  b = d eps/dq at fixed xi + (d eps/dxi) d xi/dqdot,
// with xi = (s - s1) / l moving at fixed material s: xi_dot = -((1 - xi) s1dot + xi s2dot) / l. So
//     l^2 b_r2 = (I + W')^T t = -l^2 b_r1,  l^2 b_(dir,i) = S_i'(xi) (A^T t)_dir,
//     l^2 b_s1 = |t|^2 / l - (1 - xi) t . A u'' / l,  l^2 b_s2 = -|t|^2 / l - xi t . A u'' / l,
// and D = 1/2 EA c l sum_k w_k (b_k . qdot)^2, Q = -EA c l sum_k w_k (b_k . qdot) b_k.
template <int Dim>
void SpanModel<Dim>::addAxialDamping(const Eigen::Ref<const Eigen::VectorXd>& q, const Eigen::Ref<const Eigen::VectorXd>& qdot,
                                     const ModeVectors& U, const ModeVectors& Ud, Data& d) const {
    const int m = maxMode_, iS1 = s1Index(), iS2 = s2Index(), na = options_.axialModes, nt = options_.transverseModes;
    const ChordFrame<Dim>& F = d.frame;
    const Mat& A = F.A;
    const Vec e = q.template segment<Dim>(Dim) - q.template segment<Dim>(0);
    const Vec ed = qdot.template segment<Dim>(Dim) - qdot.template segment<Dim>(0);
    const double l = q[iS2] - q[iS1], l2 = l * l, s1d = qdot[iS1], s2d = qdot[iS2];
    const double pi = std::acos(-1.0);
    const double scale = properties_.axialStiffness * properties_.axialRetardationTime * l;
    for (int k = 0; k < strainTable_.xi.size(); ++k) {
        const double xi = strainTable_.xi[k], w = strainTable_.w[k];
        const double* sinRow = strainTable_.sin.data() + k * m;
        const double* dsinRow = strainTable_.dsin.data() + k * m;
        Vec up = Vec::Zero(), upp = Vec::Zero(), upd = Vec::Zero();  // u', u'', u' rate (local)
        for (int i = 0; i < m; ++i) {
            up += dsinRow[i] * U.col(i);
            upp -= ((i + 1) * pi) * ((i + 1) * pi) * sinRow[i] * U.col(i);
            upd += dsinRow[i] * Ud.col(i);
        }
        const Vec t = e + A * up;
        if (law_.slack(0.5 * (t.squaredNorm() / l2 - 1.0))) continue;
        Vec bE = t;  // l^2 d eps/de
        for (int mm = 0; mm < Dim; ++mm) bE[mm] += (F.dA[mm] * up).dot(t);
        const Vec At = A.transpose() * t;
        const double tApp = t.dot(A * upp), t2 = t.squaredNorm();
        const double bS1 = (t2 - (1.0 - xi) * tApp) / l, bS2 = (-t2 - xi * tApp) / l;
        const double rate = (bE.dot(ed) + At.dot(upd) + bS1 * s1d + bS2 * s2d) / l2;  // Deps/Dt
        const double f = scale * w * rate;  // dD/d(b . qdot)
        d.dampingPower += f * rate;
        d.dampingForces.template segment<Dim>(0) += (f / l2) * bE;
        d.dampingForces.template segment<Dim>(Dim) -= (f / l2) * bE;
        for (int dir = 0; dir < Dim; ++dir)
            for (int i = 0; i < m; ++i) {
                const int b = dir == 0 ? (i < na ? 2 * Dim + i : -1) : (i < nt ? 2 * Dim + na + (dir - 1) * nt + i : -1);
                if (b >= 0) d.dampingForces[b] -= (f / l2) * dsinRow[i] * At[dir];
            }
        d.dampingForces[iS1] -= (f / l2) * bS1;
        d.dampingForces[iS2] -= (f / l2) * bS2;
    }
}

template <int Dim>
typename SpanModel<Dim>::Vec SpanModel<Dim>::position(const Eigen::Ref<const Eigen::VectorXd>& q, double s) const {
    const double xi = checkMaterialPoint(q, s);
    const Vec r1 = q.template segment<Dim>(0), r2 = q.template segment<Dim>(Dim);
    ChordFrame<Dim> F;
    computeChordFrame<Dim>(Vec(r2 - r1), Vec::Zero(), referenceFrame_, F);
    const double pi = std::acos(-1.0);
    Eigen::Matrix<double, 1, kMaxModesPerDirection> row;
    for (int i = 0; i < maxMode_; ++i) row[i] = std::sin((i + 1) * pi * xi);
    const Vec u = modesToLocal<Dim>(row, q.segment(2 * Dim, numModal_), options_.axialModes, options_.transverseModes);
    return (1.0 - xi) * r1 + xi * r2 + F.A * u;
}

template <int Dim>
double SpanModel<Dim>::strain(const Eigen::Ref<const Eigen::VectorXd>& q, double s) const {
    const double xi = checkMaterialPoint(q, s);
    const Vec r1 = q.template segment<Dim>(0), r2 = q.template segment<Dim>(Dim);
    const Vec e = r2 - r1;
    ChordFrame<Dim> F;
    computeChordFrame<Dim>(e, Vec::Zero(), referenceFrame_, F);
    const double pi = std::acos(-1.0);
    Eigen::Matrix<double, 1, kMaxModesPerDirection> row;
    for (int i = 0; i < maxMode_; ++i) row[i] = (i + 1) * pi * std::cos((i + 1) * pi * xi);
    const Vec up = modesToLocal<Dim>(row, q.segment(2 * Dim, numModal_), options_.axialModes, options_.transverseModes);
    const double l = q[s2Index()] - q[s1Index()];
    return 0.5 * ((e + F.A * up).squaredNorm() / (l * l) - 1.0);
}

template <int Dim>
double SpanModel<Dim>::maxStrain(const Eigen::Ref<const Eigen::VectorXd>& q) const {
    checkState(q, "q");
    const double l = q[s2Index()] - q[s1Index()];
    double m = std::max(strain(q, q[s1Index()]), strain(q, q[s2Index()]));
    const Vec e = q.template segment<Dim>(Dim) - q.template segment<Dim>(0);
    ChordFrame<Dim> F;
    computeChordFrame<Dim>(e, Vec::Zero(), referenceFrame_, F);
    const auto qm = q.segment(2 * Dim, numModal_);
    for (int k = 0; k < strainTable_.xi.size(); ++k) {
        const Vec up = modesToLocal<Dim>(strainTable_.dsin.row(k), qm, options_.axialModes, options_.transverseModes);
        m = std::max(m, 0.5 * ((e + F.A * up).squaredNorm() / (l * l) - 1.0));
    }
    return m;
}

template <int Dim>
void SpanModel<Dim>::endStrain(const Eigen::Ref<const Eigen::VectorXd>& q, const Eigen::Ref<const Eigen::VectorXd>& qdot,
                               SpanEnd end, EndStrain<Dim>& out) const {
    checkState(q, "q");
    checkState(qdot, "qdot");
    const int na = options_.axialModes, nt = options_.transverseModes, nm = numModal_;
    const int iM = 2 * Dim, iS1 = s1Index(), iS2 = s2Index();
    const Vec e = q.template segment<Dim>(Dim) - q.template segment<Dim>(0);
    const Vec ed = qdot.template segment<Dim>(Dim) - qdot.template segment<Dim>(0);
    const double l = q[iS2] - q[iS1], ld = qdot[iS2] - qdot[iS1];
    if (!(l > 0)) throwInvalid("SpanModel::endStrain", "span length l = s2 - s1 [m]", l, "must be > 0");
    ChordFrame<Dim> F;
    computeChordFrame<Dim>(e, ed, referenceFrame_, F);
    // dS_i/dxi at xi = 0 is i pi, at xi = 1 it is i pi (-1)^i.
    const double pi = std::acos(-1.0);
    Eigen::Matrix<double, 1, kMaxModesPerDirection> row;
    for (int i = 0; i < maxMode_; ++i) row[i] = (i + 1) * pi * (end == SpanEnd::Second && (i % 2 == 0) ? -1.0 : 1.0);
    const Vec up = modesToLocal<Dim>(row, q.segment(iM, nm), na, nt);
    const Vec upd = modesToLocal<Dim>(row, qdot.segment(iM, nm), na, nt);
    const Vec t = e + F.A * up;
    const Vec td = ed + F.Adot * up + F.A * upd;
    const Vec tdd = F.Addot * up + 2.0 * (F.Adot * upd);  // with qddot = 0
    const double l2 = l * l, t2 = t.squaredNorm(), ttd = t.dot(td);
    out.strain = 0.5 * (t2 / l2 - 1.0);
    out.rate = ttd / l2 - t2 * ld / (l2 * l);
    out.accelerationBias = (td.squaredNorm() + t.dot(tdd)) / l2 - 4.0 * ttd * ld / (l2 * l) +
                           3.0 * t2 * ld * ld / (l2 * l2);
    out.gradient.setZero(numCoordinates());
    Vec deps_de = t;
    for (int m = 0; m < Dim; ++m) deps_de[m] += t.dot(F.dA[m] * up);
    deps_de /= l2;
    out.gradient.template segment<Dim>(0) = -deps_de;
    out.gradient.template segment<Dim>(Dim) = deps_de;
    addLocalToModes<Dim>(row, Vec(F.A.transpose() * t), 1.0 / l2, na, nt, out.gradient.segment(iM, nm));
    out.gradient[iS1] = t2 / (l2 * l);
    out.gradient[iS2] = -t2 / (l2 * l);
}

template class SpanModel<2>;
template class SpanModel<3>;

}  // namespace SimbodyReeving
