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
SpanModel<Dim>::SpanModel(const RopeProperties& properties, const SpanOptions& options, const Vec& gravity,
                          const Mat& referenceFrame)
    : properties_(properties), options_(options), gravity_(gravity), referenceFrame_(referenceFrame) {
    validate(properties_);
    checkModeCount("SpanOptions::axialModes (n_a)", options_.axialModes);
    checkModeCount("SpanOptions::transverseModes (n_t)", options_.transverseModes);
    if (options_.quadraturePoints < 0 || options_.quadraturePoints > 200)
        throwInvalid("SpanModel", "SpanOptions::quadraturePoints", options_.quadraturePoints,
                     "is outside 0..200 (0 = automatic)");
    if (!(options_.quasiStaticSlackStiffness >= 1e-9 && options_.quasiStaticSlackStiffness <= 1.0))
        throwInvalid("SpanModel", "SpanOptions::quasiStaticSlackStiffness (delta)", options_.quasiStaticSlackStiffness,
                     "must be in [1e-9, 1]");
    if (!(options_.quasiStaticSlackTransitionStrain >= 1e-12 && options_.quasiStaticSlackTransitionStrain <= 1e-3))
        throwInvalid("SpanModel", "SpanOptions::quasiStaticSlackTransitionStrain (eps_s)",
                     options_.quasiStaticSlackTransitionStrain, "must be in [1e-12, 1e-3]");
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

    d.massMatrix.setZero(n, n);
    d.velocityForces.setZero(n);
    d.elasticForces.setZero(n);  // accumulates dU/dq, negated at the end
    d.gravityForces.setZero(n);
    d.kineticEnergy = d.axialEnergy = d.bendingEnergy = d.stringEnergy = d.gravityEnergy = 0;
    auto& B = d.velocityJacobian;
    B.setZero(Dim, n);
    auto& Qv = d.velocityForces;
    auto& gradU = d.elasticForces;

    double sumV2 = 0;  // sum_k w_k |v_k|^2
    // ---- kinetic terms: M, Q_v, T ------------------------------------------------------------
    for (int k = 0; k < kineticTable_.xi.size(); ++k) {
        const double xi = kineticTable_.xi[k], w = kineticTable_.w[k];
        const auto sinRow = kineticTable_.sin.row(k);
        const auto dsinRow = kineticTable_.dsin.row(k);
        const Vec u = modesToLocal<Dim>(sinRow, qm, na, nt);      // u(xi) in the element frame
        const Vec up = modesToLocal<Dim>(dsinRow, qm, na, nt);    // du/dxi
        const Vec ud = modesToLocal<Dim>(sinRow, qmd, na, nt);    // S qdot_m
        const Vec upd = modesToLocal<Dim>(dsinRow, qmd, na, nt);  // S' qdot_m
        const Vec t = e + A * up;  // r_xi, the (unnormalised) tangent
        const double g1 = -(1.0 - xi) / l, g2 = -xi / l;  // xi_dot = g1 s1dot + g2 s2dot
        const double g1d = -g1 * ld / l, g2d = -g2 * ld / l;
        const double xid = g1 * s1d + g2 * s2d;
        const Vec& tv = complete ? t : e;  // what the material flow xi_dot convects
        Vec v, a;                           // material velocity and B_dot qdot
        Vec dR1;                            // D-vector entries for r1 (r2 gets the negative)
        Vec tvd;                            // d/dt of tv at fixed xi
        if (complete) {
            Mat W;
            for (int m = 0; m < Dim; ++m) W.col(m) = F.dA[m] * u;
            v = (1.0 - xi) * r1d + xi * r2d + F.Adot * u + A * ud + xid * t;
            tvd = ed + F.Adot * up + A * upd;
            a = F.Addot * u + 2.0 * (F.Adot * ud) - xid * ld / l * t + xid * tvd;
            B.template block<Dim, Dim>(0, 0) = (1.0 - xi) * Mat::Identity() - W;
            B.template block<Dim, Dim>(0, Dim) = xi * Mat::Identity() + W;
            Mat Wp;  // d(A u')/de
            for (int m = 0; m < Dim; ++m) Wp.col(m) = F.dA[m] * up;
            dR1 = xid * (v + Wp.transpose() * v);
            // D_m = -xi_dot S'^T A^T v
            addLocalToModes<Dim>(dsinRow, Vec(A.transpose() * v), rhoA * w * l * xid, na, nt, Qv.segment(iM, nm));
        } else {
            v = (1.0 - xi) * r1d + xi * r2d + A * ud + xid * e;
            tvd = ed;
            a = F.Adot * ud - xid * ld / l * e + xid * ed;
            B.template block<Dim, Dim>(0, 0) = (1.0 - xi) * Mat::Identity();
            B.template block<Dim, Dim>(0, Dim) = xi * Mat::Identity();
            for (int m = 0; m < Dim; ++m) dR1[m] = v.dot(F.dA[m] * ud);
            dR1 += xid * v;
            // D_m = S^T Adot^T v
            addLocalToModes<Dim>(sinRow, Vec(F.Adot.transpose() * v), -rhoA * w * l, na, nt, Qv.segment(iM, nm));
        }
        for (int i = 0; i < na; ++i) B.col(iM + i) = sinRow[i] * A.col(0);
        for (int dir = 1; dir < Dim; ++dir)
            for (int i = 0; i < nt; ++i) B.col(iM + na + (dir - 1) * nt + i) = sinRow[i] * A.col(dir);
        B.col(iS1) = g1 * tv;
        B.col(iS2) = g2 * tv;

        const double wm = rhoA * l * w;
        // Lower triangle of M += wm B^T B (B is Dim x n: a plain loop beats a rank update here).
        for (int b = 0; b < n; ++b) {
            const Vec Bb = B.col(b);
            for (int a = b; a < n; ++a) d.massMatrix(a, b) += wm * B.col(a).dot(Bb);
        }

        // Q_v -= rhoA w [ B^T (ldot v + l a) + l D ];  + 1/2 rhoA delta sum w |v|^2
        const Vec x = ld * v + l * a;
        Qv.noalias() -= (rhoA * w) * (B.transpose() * x);
        Qv.template segment<Dim>(0) -= (rhoA * w * l) * dR1;
        Qv.template segment<Dim>(Dim) += (rhoA * w * l) * dR1;
        const double tv_v = tv.dot(v);
        Qv[iS1] -= rhoA * w * l * ((g1d * tv + g1 * tvd).dot(v) - xid * tv_v / l);
        Qv[iS2] -= rhoA * w * l * ((g2d * tv + g2 * tvd).dot(v) + xid * tv_v / l);
        const double v2 = v.squaredNorm();
        sumV2 += w * v2;

    }
    d.massMatrix.template triangularView<Eigen::StrictlyUpper>() = d.massMatrix.transpose();
    Qv[iS1] -= 0.5 * rhoA * sumV2;
    Qv[iS2] += 0.5 * rhoA * sumV2;
    d.kineticEnergy = 0.5 * rhoA * l * sumV2;

    // ---- axial strain energy: U_ax = 1/2 EA l sum w eps^2, eps = 1/2(|t|^2/l^2 - 1) ------------
    for (int k = 0; k < strainTable_.xi.size(); ++k) {
        const double w = strainTable_.w[k];
        const auto dsinRow = strainTable_.dsin.row(k);
        const Vec up = modesToLocal<Dim>(dsinRow, qm, na, nt);  // du/dxi
        const Vec t = e + A * up;
        Mat Wp;  // d(A u')/de
        for (int m = 0; m < Dim; ++m) Wp.col(m) = F.dA[m] * up;
        const double t2 = t.squaredNorm();
        const double eps = 0.5 * (t2 / (l * l) - 1.0);
        // Tension-only law: a slack point (eps <= 0) stores no energy and feels no axial force.
        if (law_.slack(eps)) continue;
        const double energyDensity = law_.F(eps);  // U_ax = EA l sum w F(eps), F' = f (AxialLaw)
        d.axialEnergy += EA * l * w * energyDensity;
        // d eps/dr2 = (I + W')^T t / l^2, d eps/dq_m = S'^T A^T t / l^2, d eps/dl = -|t|^2 / l^3
        const Vec deps_de = (t + Wp.transpose() * t) / (l * l);
        const Vec At = A.transpose() * t / (l * l);
        const double deps_dl = -t2 / (l * l * l);
        double coef = EA * l * w * law_.f(eps);  // dU/deps at this point
        double dU_dl = EA * w * energyDensity;
        if (literal) {
            // U_str = EA/(2 l) w eps |u'_perp|^2
            double h = 0;
            for (int dd = 1; dd < Dim; ++dd) h += up[dd] * up[dd];
            d.stringEnergy += 0.5 * EA / l * w * eps * h;
            coef += 0.5 * EA / l * w * h;
            dU_dl += -0.5 * EA / (l * l) * w * eps * h;
            Vec uperp = up;
            uperp[0] = 0;
            addLocalToModes<Dim>(dsinRow, uperp, EA / l * w * eps, na, nt, gradU.segment(iM, nm));
        }
        gradU.template segment<Dim>(0) -= coef * deps_de;
        gradU.template segment<Dim>(Dim) += coef * deps_de;
        addLocalToModes<Dim>(dsinRow, Vec(At), coef, na, nt, gradU.segment(iM, nm));
        dU_dl += coef * deps_dl;
        gradU[iS1] -= dU_dl;
        gradU[iS2] += dU_dl;
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
        for (int i = 0; i < na; ++i) {
            const double k2 = axialModeWavenumberSquared(i);
            sum += k2 * qm[i] * qm[i];
            gradU[iM + i] += 2.0 * c * k2 * qm[i];
        }
        d.slackRegularisationEnergy = c * sum;
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

    // Finite inputs can still overflow (e.g. EA = 1e300 with a large strain): never return inf/NaN.
    if (!(std::isfinite(d.kineticEnergy + d.strainEnergy() + d.gravityEnergy) &&
          d.massMatrix.allFinite() && d.velocityForces.allFinite() && d.elasticForces.allFinite() &&
          d.gravityForces.allFinite()))
        throw std::domain_error("SpanModel::evaluate: the result overflowed (non-finite energy, mass matrix or "
                                "forces) for finite inputs; the state or the rope parameters are out of range");
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
