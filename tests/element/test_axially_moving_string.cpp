// The axially moving string: a taut span of material length L between fixed
// nodes, with rope flowing through it at speed v (both end material coordinates Driven,
// s_0 = s_00 + v t, s_1 = s_00 + L + v t), EI = 0, gravity 0. The classical result (Wickert & Mote
// 1990): with c = sqrt(P / rhoA), the transverse natural frequencies are
//     omega_n = (n pi c / L) (1 - v^2 / c^2),
// and the modes travel (complex). The span's material velocity with VelocityModel::Complete (paper
// eq 12) is that of the moving string exactly, so its sine modes are the string's Galerkin
// discretisation and converge to omega_n as n_t grows; VelocityModel::Simplified (eq 13) drops the
// convection of the modes (A_e Sdot q_m) and vibrates at the frequencies of a rope at rest.
//
// Method: the rope (RopeModel, one span, Driven ends) linearised about the steady flow by central
// differences of its modal accelerations (q_m, qdot_m), eigenvalues of the first-order system;
// cross-checked by integrating the nonlinear rope in time from a small disturbance. The numbers of
// the whole study: bench/moving_string (bench-moving-string) and docs/verification.md.
//
// Units: SI. P is the axial force EA eps (material-length measure), v and c material speeds
// [m of unstretched rope / s]; the same ratio v / c holds in physical (stretched) measure.
#include "SimbodyReeving/element/RopeModel.h"
#include "support/ExpectThrowMessage.h"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>
#include <vector>

using namespace SimbodyReeving;

namespace {

const double kPi = std::acos(-1.0);
// Table 1 rope's rhoA and EA (EA / P = 1 682: the tension stays constant to first order), EI = 0:
// a pure string. Tension-only (the default law): taut everywhere here.
const RopeProperties kString{0.6205, 16.5e6, 0.0};
constexpr double kL = 20.0;    // material length of the span [m]
constexpr double kP = 9810.0;  // axial force [N] (a 1 t payload)
const double kC = std::sqrt(kP / kString.massPerLength);  // wave speed [m/s], 125.7 m/s
const double kLambda = std::sqrt(1.0 + 2.0 * kP / kString.axialStiffness);  // stretch for eps = P / EA

struct MovingString {
    RopeModel<2> rope;
    Eigen::Matrix2Xd nodes, nodeVelocities;
    double v;    // flow speed [m/s]
    double s00;  // material coordinate at node 0 at t = 0 [m]

    MovingString(const SpanOptions& o, double speed, double s0 = 3.7)
        : rope({SpanModel<2>(kString, o, Eigen::Vector2d::Zero())}, kL + 100.0,
               {MaterialNode::Driven, MaterialNode::Driven}),
          nodes(2, 2), nodeVelocities(Eigen::Matrix2Xd::Zero(2, 2)), v(speed), s00(s0) {
        nodes << 0, kLambda * kL, 0, 0;
    }
    Eigen::VectorXd drivenS(double t) const { return Eigen::Vector2d(s00 + v * t, s00 + kL + v * t); }
    Eigen::VectorXd drivenSdot() const { return Eigen::Vector2d(v, v); }
    int numModal() const { return rope.numModalCoordinates(); }
    /// Index in q_m of transverse mode i (0-based).
    int transverseIndex(int i) const {
        const SpanModel<2>& sp = rope.span(0);
        return rope.modalOffset(0) + (rope.isCondensed(0) ? 0 : sp.axialModes()) + i;
    }
    /// qddot_m at time t for the modal state (qm, qmd), nodes held, material flowing at v.
    Eigen::VectorXd accelerations(double t, const Eigen::VectorXd& qm, const Eigen::VectorXd& qmd,
                                  RopeData<2>& d) const {
        rope.computeDynamics(nodes, nodeVelocities, drivenS(t), drivenSdot(), qm, qmd, d);
        Eigen::VectorXd qdd;
        rope.modalAccelerations(d, Eigen::VectorXd::Zero(rope.numExternalCoordinates()), qdd);
        return qdd;
    }
};

struct Spectrum {
    std::vector<double> omega;   // transverse natural frequencies [rad/s], ascending
    double maxRealPart = 0;      // max |Re lambda| / max |Im lambda| (0 for a conservative system)
    double maxCoupling = 0;      // transverse <-> other modal coordinates, relative
    Eigen::VectorXcd firstMode;  // eigenvector of omega[0] on [q_t; qdot_t]
};

/// Linearised transverse spectrum about the steady flow (q_m = 0, qdot_m = 0).
Spectrum linearisedSpectrum(const MovingString& m) {
    const int n = m.numModal(), nt = m.rope.span(0).transverseModes();
    const double hq = 1e-6, hv = 1e-6;  // [m], [m/s]
    RopeData<2> d;
    Eigen::MatrixXd Kq(n, n), Kv(n, n);
    const Eigen::VectorXd zero = Eigen::VectorXd::Zero(n);
    for (int j = 0; j < n; ++j) {
        Eigen::VectorXd p = zero, q = zero;
        p[j] = hq;
        q[j] = -hq;
        Kq.col(j) = (m.accelerations(0, p, zero, d) - m.accelerations(0, q, zero, d)) / (2 * hq);
        Kv.col(j) = (m.accelerations(0, zero, p * (hv / hq), d) - m.accelerations(0, zero, q * (hv / hq), d)) / (2 * hv);
    }
    std::vector<int> t(nt);
    for (int i = 0; i < nt; ++i) t[i] = m.transverseIndex(i);
    Spectrum out;
    const double scaleQ = Kq.cwiseAbs().maxCoeff(), scaleV = std::max(Kv.cwiseAbs().maxCoeff(), 1e-300);
    for (int a = 0; a < n; ++a)
        for (int b = 0; b < n; ++b) {
            const bool ta = std::find(t.begin(), t.end(), a) != t.end(), tb = std::find(t.begin(), t.end(), b) != t.end();
            if (ta != tb)
                out.maxCoupling = std::max({out.maxCoupling, std::abs(Kq(a, b)) / scaleQ, std::abs(Kv(a, b)) / scaleV});
        }
    Eigen::MatrixXd A = Eigen::MatrixXd::Zero(2 * nt, 2 * nt);
    A.topRightCorner(nt, nt).setIdentity();
    for (int a = 0; a < nt; ++a)
        for (int b = 0; b < nt; ++b) {
            A(nt + a, b) = Kq(t[a], t[b]);
            A(nt + a, nt + b) = Kv(t[a], t[b]);
        }
    Eigen::EigenSolver<Eigen::MatrixXd> es(A);
    double maxIm = 0, maxRe = 0, best = INFINITY;
    for (int k = 0; k < 2 * nt; ++k) {
        const std::complex<double> lam = es.eigenvalues()[k];
        maxIm = std::max(maxIm, std::abs(lam.imag()));
        maxRe = std::max(maxRe, std::abs(lam.real()));
        if (lam.imag() > 0) {
            out.omega.push_back(lam.imag());
            if (lam.imag() < best) {
                best = lam.imag();
                out.firstMode = es.eigenvectors().col(k);
            }
        }
    }
    std::sort(out.omega.begin(), out.omega.end());
    out.maxRealPart = maxRe / maxIm;
    return out;
}

/// The moving string's Galerkin discretisation on the same sine modes, in closed form:
///     rhoA L/2 qdd_i + 2 rhoA v sum_j C_ij qd_j + (P - rhoA v^2) (i pi)^2 / (2 L) q_i = 0,
/// C_ij = int_0^1 S_i S_j' dxi = 2 i j / (i^2 - j^2) for i + j odd, else 0 (antisymmetric).
std::vector<double> galerkinFrequencies(int nt, double v) {
    const double rhoA = kString.massPerLength;
    Eigen::MatrixXd A = Eigen::MatrixXd::Zero(2 * nt, 2 * nt);
    A.topRightCorner(nt, nt).setIdentity();
    const double m = rhoA * kL / 2;
    for (int i = 1; i <= nt; ++i) {
        A(nt + i - 1, i - 1) = -(kP - rhoA * v * v) * (i * kPi) * (i * kPi) / (2 * kL) / m;
        for (int j = 1; j <= nt; ++j)
            if ((i + j) % 2) A(nt + i - 1, nt + j - 1) = -2 * rhoA * v * (2.0 * i * j / (i * i - j * j)) / m;
    }
    Eigen::EigenSolver<Eigen::MatrixXd> es(A);
    std::vector<double> w;
    for (int k = 0; k < 2 * nt; ++k)
        if (es.eigenvalues()[k].imag() > 0) w.push_back(es.eigenvalues()[k].imag());
    std::sort(w.begin(), w.end());
    return w;
}

double wickertMote(int n, double v) { return n * kPi * kC / kL * (1.0 - v * v / (kC * kC)); }
double atRest(int n) { return n * kPi * kC / kL; }

SpanOptions options(VelocityModel vm, int nt, int na = 0, AxialDynamics ad = AxialDynamics::Dynamic) {
    SpanOptions o;
    o.axialModes = na;
    o.transverseModes = nt;
    o.velocityModel = vm;
    o.axialDynamics = ad;
    return o;
}

const double kSpeeds[] = {0.0, 0.1, 0.3, 0.5, 0.7};  // v / c

}  // namespace

// The steady flow is taut at the intended tension: P = EA eps = 9 810 N along the span, the
// tension T = P |dr/ds| = P lambda, and the modal state q_m = 0 is an equilibrium (no modal
// acceleration) at every speed, for both velocity models.
TEST(AxiallyMovingString, SteadyFlowCarriesTheIntendedTension) {
    for (auto vm : {VelocityModel::Simplified, VelocityModel::Complete})
        for (double r : kSpeeds) {
            const MovingString m(options(vm, 3), r * kC);
            RopeData<2> d;
            const Eigen::VectorXd zero = Eigen::VectorXd::Zero(m.numModal());
            const Eigen::VectorXd qdd = m.accelerations(0, zero, zero, d);
            Eigen::VectorXd q;
            m.rope.spanCoordinates(0, m.nodes, zero, d, q);
            double worstP = 0, worstT = 0;
            const SpanModel<2>& span = m.rope.span(0);
            for (int k = 0; k <= 10; ++k) {
                const double s = std::min(q[span.s1Index()] + 0.1 * k * kL, q[span.s2Index()]);
                worstP = std::max(worstP, std::abs(span.axialForce(q, s) - kP));
                worstT = std::max(worstT, std::abs(span.tension(q, s) - kP * kLambda));
            }
            std::printf("[ steady ] %s v/c=%.1f: max |P - %.0f N| = %.2e N, max |T - P lambda| = %.2e N, "
                        "max |qdd_m| = %.2e m/s^2\n",
                        vm == VelocityModel::Complete ? "complete  " : "simplified", r, kP, worstP, worstT,
                        qdd.cwiseAbs().maxCoeff());
            // measured: 9.8e-10 N and 9.9e-10 N (1e-13 of P, round-off of lambda), qdd_m exactly 0
            EXPECT_LT(worstP, 1e-12 * kP);
            EXPECT_LT(worstT, 1e-12 * kP);
            EXPECT_LT(qdd.cwiseAbs().maxCoeff(), 1e-12);
        }
}

// At v = 0 both velocity models give the taut string's frequencies n pi c / L (Wickert & Mote at
// v = 0), for every mode in the basis.
TEST(AxiallyMovingString, AtRestBothModelsGiveTheTautString) {
    for (auto vm : {VelocityModel::Simplified, VelocityModel::Complete}) {
        const Spectrum sp = linearisedSpectrum(MovingString(options(vm, 4), 0.0));
        ASSERT_EQ(sp.omega.size(), 4u);
        for (int n = 1; n <= 4; ++n) {
            const double e = sp.omega[n - 1] / atRest(n) - 1;
            std::printf("[ rest ] %s n=%d: omega = %.9f rad/s, n pi c / L = %.9f, rel %.2e\n",
                        vm == VelocityModel::Complete ? "complete  " : "simplified", n, sp.omega[n - 1], atRest(n), e);
            EXPECT_LT(std::abs(e), 1e-8);  // measured <= 1.3e-10 (n = 4; central differences)
        }
    }
}

// Complete: the span's linearised modal equations are exactly the moving string's Galerkin system
// on the same sine modes (closed form above), at every speed: the element carries the transport
// terms (Coriolis 2 v w_xt and centripetal v^2 w_xx) exactly; the system stays conservative
// (eigenvalues on the imaginary axis) and the transverse modes decouple from nothing else.
TEST(AxiallyMovingString, CompleteEqualsTheGalerkinMovingString) {
    for (int nt : {1, 2, 3, 8}) {
        for (double r : kSpeeds) {
            const Spectrum sp = linearisedSpectrum(MovingString(options(VelocityModel::Complete, nt), r * kC));
            const std::vector<double> g = galerkinFrequencies(nt, r * kC);
            ASSERT_EQ(sp.omega.size(), g.size());
            double worst = 0;
            for (size_t k = 0; k < g.size(); ++k) worst = std::max(worst, std::abs(sp.omega[k] / g[k] - 1));
            std::printf("[ Galerkin ] n_t=%d v/c=%.1f: max rel. difference %.2e, max |Re| / max |Im| %.2e\n", nt, r,
                        worst, sp.maxRealPart);
            // measured: <= 9.6e-10 (n_t = 8, v/c = 0.7; central differences), |Re| / |Im| <= 6.6e-15
            EXPECT_LT(worst, 1e-7) << "n_t = " << nt << " v/c = " << r;
            EXPECT_LT(sp.maxRealPart, 1e-13) << "n_t = " << nt << " v/c = " << r;
        }
    }
}

// Complete against Wickert & Mote: with n_t = 16 (the most the element allows) the first three
// frequencies are within 6.3e-5 / 2.4e-4 / 5.4e-4 of (n pi c / L)(1 - v^2/c^2) at v/c = 0.7
// (all lower speeds closer): the sine basis' truncation error, which falls about like n_t^-3
// (docs/verification.md, "The axially moving string"). Simplified stays at the rest frequencies, 1 / (1 -
// v^2/c^2) too high: +1 % at v/c = 0.1, +33 % at 0.5, +96 % at 0.7.
TEST(AxiallyMovingString, CompleteFollowsWickertMoteSimplifiedStaysAtRest) {
    for (double r : kSpeeds) {
        const double v = r * kC;
        const Spectrum complete = linearisedSpectrum(MovingString(options(VelocityModel::Complete, 16), v));
        const Spectrum simplified = linearisedSpectrum(MovingString(options(VelocityModel::Simplified, 16), v));
        for (int n = 1; n <= 3; ++n) {
            const double wm = wickertMote(n, v);
            const double ec = complete.omega[n - 1] / wm - 1, es = simplified.omega[n - 1] / wm - 1;
            std::printf("[ W&M ] v/c=%.1f n=%d: W&M %.4f rad/s, complete %+.2e, simplified %+.4e (rest %+.4e)\n", r, n,
                        wm, ec, es, atRest(n) / wm - 1);
            EXPECT_LT(std::abs(ec), 5.4e-3) << "v/c = " << r << " n = " << n;  // measured <= 5.38e-4 (n = 3, v/c = 0.7)
            // Simplified: the rest frequency at every speed (the drop is missing entirely).
            EXPECT_LT(std::abs(simplified.omega[n - 1] / atRest(n) - 1), 5e-9);  // measured <= 7.0e-11 (n = 3)
            if (r > 0) {
                EXPECT_GT(es, 0.5 * (atRest(n) / wm - 1));
            }
        }
    }
}

// The library's defaults (SpanOptions{}: QuasiStatic axial modes, Complete velocity) give the moving
// string's drop too, also with axial modes: at the steady flow the condensed (or dynamic) axial
// amplitudes do not couple to the transverse modes to first order, so the transverse spectrum with
// n_a = 2 equals the n_a = 0 one.
TEST(AxiallyMovingString, DefaultOptionsWithAxialModesGiveTheSameSpectrum) {
    const SpanOptions defaults;
    EXPECT_EQ(defaults.velocityModel, VelocityModel::Complete);
    EXPECT_EQ(defaults.axialDynamics, AxialDynamics::QuasiStatic);
    for (double r : {0.3, 0.7}) {
        SpanOptions o;  // the defaults
        o.transverseModes = 8;
        const Spectrum reference = linearisedSpectrum(MovingString(o, r * kC));
        for (auto ad : {AxialDynamics::QuasiStatic, AxialDynamics::Dynamic}) {
            o.axialModes = 2;
            o.axialDynamics = ad;
            const Spectrum sp = linearisedSpectrum(MovingString(o, r * kC));
            ASSERT_EQ(sp.omega.size(), reference.omega.size());
            double worst = 0;
            for (size_t k = 0; k < sp.omega.size(); ++k)
                worst = std::max(worst, std::abs(sp.omega[k] / reference.omega[k] - 1));
            std::printf("[ n_a = 2 ] %s v/c=%.1f: max rel. difference to n_a = 0 %.2e, coupling %.2e\n",
                        ad == AxialDynamics::QuasiStatic ? "QuasiStatic" : "Dynamic    ", r, worst, sp.maxCoupling);
            // measured: QuasiStatic <= 3.0e-12 (the condensation's Newton), Dynamic 0; coupling exactly 0
            EXPECT_LT(worst, 1e-10) << "v/c = " << r;
            EXPECT_LT(sp.maxCoupling, 1e-12);
        }
    }
}

// The nonlinear rope integrated in time (RK4, 400 steps per period, 6 periods), material flowing
// through the span (the Driven coordinates advance by v t: 4.9 m of rope passes at v/c = 0.5), from
// the first linearised mode at 2e-6 L amplitude: the first transverse mode coordinate oscillates
// at the linearised frequency (so the drop is the dynamics', not an artefact of the
// linearisation), for both models.
TEST(AxiallyMovingString, IntegratedFlowOscillatesAtTheLinearisedFrequency) {
    const double r = 0.5, v = r * kC;
    for (auto vm : {VelocityModel::Complete, VelocityModel::Simplified}) {
        const MovingString m(options(vm, 3), v);
        const Spectrum sp = linearisedSpectrum(m);
        const int n = m.numModal(), nt = 3;
        Eigen::VectorXd x = Eigen::VectorXd::Zero(2 * n);
        const double amplitude = 2e-6 * kL;  // [m]
        const double scale = amplitude / sp.firstMode.head(nt).cwiseAbs().maxCoeff();
        for (int i = 0; i < nt; ++i) {
            x[m.transverseIndex(i)] = scale * sp.firstMode[i].real();
            x[n + m.transverseIndex(i)] = scale * sp.firstMode[nt + i].real();
        }
        RopeData<2> d;
        auto f = [&](double t, const Eigen::VectorXd& y) {
            Eigen::VectorXd out(2 * n);
            out.head(n) = y.tail(n);
            out.tail(n) = m.accelerations(t, y.head(n), y.tail(n), d);
            return out;
        };
        const double period = 2 * kPi / sp.omega[0], dt = period / 400;
        const int i1 = m.transverseIndex(0);
        std::vector<double> crossings;  // upward zero crossings of q_1, linearly interpolated
        double t = 0;
        for (int k = 0; k < 6 * 400; ++k) {
            const Eigen::VectorXd k1 = f(t, x), k2 = f(t + dt / 2, x + dt / 2 * k1), k3 = f(t + dt / 2, x + dt / 2 * k2),
                                  k4 = f(t + dt, x + dt * k3);
            const Eigen::VectorXd next = x + dt / 6 * (k1 + 2 * k2 + 2 * k3 + k4);
            if (x[i1] < 0 && next[i1] >= 0) crossings.push_back(t + dt * x[i1] / (x[i1] - next[i1]));
            x = next;
            t += dt;
        }
        ASSERT_GE(crossings.size(), 5u);
        const double measured = 2 * kPi * (crossings.size() - 1) / (crossings.back() - crossings.front());
        const double e = measured / sp.omega[0] - 1;
        std::printf("[ integrated ] %s v/c=%.1f: omega = %.6f rad/s, linearised %.6f (rel %+.2e), W&M %.6f, rest %.6f\n",
                    vm == VelocityModel::Complete ? "complete  " : "simplified", r, measured, sp.omega[0], e,
                    wickertMote(1, v), atRest(1));
        EXPECT_LT(std::abs(e), 1e-6);  // measured: 1.5e-8 (Complete), 8.8e-9 (Simplified)
    }
}

// The QuasiStatic default has no effect without axial modes: a span with n_a = 0 evaluates to the
// same numbers (bit for bit) as with Dynamic, for the linear and the tension-only law and both
// energies (PaperLiteral is accepted with n_a = 0); with axial modes, QuasiStatic + PaperLiteral is
// rejected with a message that names the way out (Dynamic).
TEST(SpanOptionsDefaults, QuasiStaticIsInertWithoutAxialModes) {
    for (bool tensionOnly : {false, true})
        for (auto em : {ElasticEnergyModel::Consistent, ElasticEnergyModel::PaperLiteral}) {
            if (tensionOnly && em == ElasticEnergyModel::PaperLiteral) continue;  // rejected by the law
            RopeProperties p{0.6205, 16.5e6, 30.9};
            p.tensionOnly = tensionOnly;
            SpanOptions quasi;  // the defaults: QuasiStatic, Complete, n_a = 0
            quasi.transverseModes = 2;
            quasi.elasticModel = em;
            SpanOptions dynamic = quasi;
            dynamic.axialDynamics = AxialDynamics::Dynamic;
            const PlanarSpanModel a(p, quasi, Eigen::Vector2d(0.3, -9.81)), b(p, dynamic, Eigen::Vector2d(0.3, -9.81));
            EXPECT_FALSE(a.slackRegularised());
            Eigen::VectorXd q = Eigen::VectorXd::Zero(a.numCoordinates()), qd(a.numCoordinates());
            q.segment<2>(2) = Eigen::Vector2d(0.4, -3.01);
            q[4] = 0.01;
            q[5] = -0.003;
            q[a.s1Index()] = 1.0;
            q[a.s2Index()] = 4.0;
            for (int k = 0; k < qd.size(); ++k) qd[k] = 0.1 * (k + 1) * (k % 2 ? -1 : 1);
            SpanData<2> da, db;
            a.evaluate(q, qd, da);
            b.evaluate(q, qd, db);
            EXPECT_EQ((da.massMatrix - db.massMatrix).cwiseAbs().maxCoeff(), 0.0);
            EXPECT_EQ((da.velocityForces - db.velocityForces).cwiseAbs().maxCoeff(), 0.0);
            EXPECT_EQ((da.elasticForces - db.elasticForces).cwiseAbs().maxCoeff(), 0.0);
            EXPECT_EQ(da.strainEnergy(), db.strainEnergy());
        }
    SpanOptions o;
    o.axialModes = 2;
    o.elasticModel = ElasticEnergyModel::PaperLiteral;
    EXPECT_THROW_MESSAGE(PlanarSpanModel({0.6205, 16.5e6, 30.9, false}, o, Eigen::Vector2d(0, -9.81)),
                         std::invalid_argument,
                         "SpanModel: SpanOptions::axialDynamics = QuasiStatic (the default) with axial modes requires "
                         "elasticModel = Consistent (got PaperLiteral); set axialDynamics = Dynamic");
    o.axialDynamics = AxialDynamics::Dynamic;
    EXPECT_NO_THROW(PlanarSpanModel({0.6205, 16.5e6, 30.9, false}, o, Eigen::Vector2d(0, -9.81)));
}
