#include "SimbodyReeving/RopeModel.h"

#include <Eigen/LU>

#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

namespace SimbodyReeving {

template <int Dim>
RopeModel<Dim>::RopeModel(std::vector<SpanModel<Dim>> spans, double unstretchedLength)
    : spans_(std::move(spans)), length_(unstretchedLength) {
    if (spans_.empty()) throw std::invalid_argument("RopeModel: a rope needs at least one span (got 0)");
    if (!std::isfinite(length_) || !(length_ > 0)) {
        std::ostringstream msg;
        msg << "RopeModel: unstretchedLength [m] = " << length_ << " must be finite and > 0";
        throw std::invalid_argument(msg.str());
    }
    const RopeProperties& p0 = spans_.front().properties();
    for (const auto& sp : spans_) {
        const RopeProperties& p = sp.properties();
        if (p.massPerLength != p0.massPerLength || p.axialStiffness != p0.axialStiffness ||
            p.bendingStiffness != p0.bendingStiffness)
            throw std::invalid_argument("RopeModel: all spans of a rope must have the same RopeProperties");
    }
    const int N = numSpans();
    for (int j = 0; j < N; ++j) {
        modalOffset_.push_back(numModal_);
        numModal_ += spans_[j].numModalCoordinates();
    }
    const int nn = Dim * (N + 1);
    for (int j = 0; j < N; ++j) {
        const auto& sp = spans_[j];
        std::vector<int> map(sp.numCoordinates());
        for (int d = 0; d < Dim; ++d) {
            map[d] = Dim * j + d;
            map[Dim + d] = Dim * (j + 1) + d;
        }
        for (int i = 0; i < sp.numModalCoordinates(); ++i) map[2 * Dim + i] = nn + modalOffset_[j] + i;
        map[sp.s1Index()] = nn + numModal_ + j;
        map[sp.s2Index()] = nn + numModal_ + j + 1;
        spanToRope_.push_back(std::move(map));
    }
}

template <int Dim>
void RopeModel<Dim>::spanCoordinates(int j, const NodeMatrix& nodes, const Eigen::VectorXd& qm,
                                     const Eigen::VectorXd& s, Eigen::VectorXd& q) const {
    const auto& sp = spans_[j];
    q.resize(sp.numCoordinates());
    q.template segment<Dim>(0) = nodes.col(j);
    q.template segment<Dim>(Dim) = nodes.col(j + 1);
    q.segment(2 * Dim, sp.numModalCoordinates()) = qm.segment(modalOffset_[j], sp.numModalCoordinates());
    q[sp.s1Index()] = s[j];
    q[sp.s2Index()] = s[j + 1];
}

template <int Dim>
void RopeModel<Dim>::endStrains(const NodeMatrix& nodes, const Eigen::VectorXd& qm, const Eigen::VectorXd& s,
                                RopeData<Dim>& data) const {
    const int N = numSpans();
    data.spanQ.resize(N);
    data.spanQdot.resize(N);
    data.firstEnd.resize(N);
    data.secondEnd.resize(N);
    for (int j = 0; j < N; ++j) {
        spanCoordinates(j, nodes, qm, s, data.spanQ[j]);
        if (data.spanQdot[j].size() != data.spanQ[j].size()) data.spanQdot[j].setZero(data.spanQ[j].size());
        spans_[j].endStrain(data.spanQ[j], data.spanQdot[j], SpanEnd::First, data.firstEnd[j]);
        spans_[j].endStrain(data.spanQ[j], data.spanQdot[j], SpanEnd::Second, data.secondEnd[j]);
    }
}

template <int Dim>
void RopeModel<Dim>::solveMaterialCoordinates(const NodeMatrix& nodes, const Eigen::VectorXd& qm,
                                              RopeData<Dim>& data) const {
    const int N = numSpans();
    Eigen::VectorXd& s = data.materialCoordinates;
    bool admissible = s.size() == N + 1 && s[0] == 0.0 && s[N] == length_;
    for (int k = 0; admissible && k < N; ++k) admissible = s[k + 1] > s[k];
    if (!admissible) {
        s.resize(N + 1);
        double total = 0;
        for (int j = 0; j < N; ++j) total += (nodes.col(j + 1) - nodes.col(j)).norm();
        s[0] = 0;
        double acc = 0;
        for (int j = 0; j < N; ++j) {
            acc += (nodes.col(j + 1) - nodes.col(j)).norm();
            s[j + 1] = (j + 1 == N) ? length_ : length_ * acc / total;
        }
    }
    data.newtonIterations = 0;
    for (auto& v : data.spanQdot) v.setZero();
    if (N == 1) {
        endStrains(nodes, qm, s, data);
        return;
    }
    Eigen::VectorXd& C = data.newtonResidual;
    Eigen::MatrixXd& J = data.newtonJacobian;
    C.resize(N - 1);
    J.resize(N - 1, N - 1);
    double previous = std::numeric_limits<double>::infinity();
    for (int iter = 0; iter <= 50; ++iter) {
        endStrains(nodes, qm, s, data);
        J.setZero();
        for (int k = 1; k < N; ++k) {
            const auto& a = data.secondEnd[k - 1];  // span k-1 at its node 2 (= sheave k)
            const auto& b = data.firstEnd[k];       // span k at its node 1
            C[k - 1] = a.strain - b.strain;
            const int as1 = spans_[k - 1].s1Index(), as2 = spans_[k - 1].s2Index();
            const int bs1 = spans_[k].s1Index(), bs2 = spans_[k].s2Index();
            if (k - 1 >= 1) J(k - 1, k - 2) += a.gradient[as1];
            J(k - 1, k - 1) += a.gradient[as2] - b.gradient[bs1];
            if (k + 1 <= N - 1) J(k - 1, k) -= b.gradient[bs2];
        }
        // Converged at 1e-15 in strain, or stagnating at round-off below 1e-12 (eps = 1/2(|t|^2/l^2 - 1)
        // carries about 1e-16 absolute error).
        const double err = C.cwiseAbs().maxCoeff();
        if (err <= 1e-15 || (err <= 1e-12 && err > 0.5 * previous)) {
            data.newtonIterations = iter;
            return;
        }
        previous = err;
        if (iter == 50) break;
        data.newtonLu.compute(J);
        Eigen::VectorXd& step = data.newtonStep;
        step = data.newtonLu.solve(C);
        step *= -1.0;
        double alpha = 1.0;
        for (int halve = 0; halve < 30; ++halve, alpha *= 0.5) {
            bool ok = true;
            for (int k = 1; k < N && ok; ++k) {
                const double sk = s[k] + alpha * step[k - 1];
                const double prev = k - 1 >= 1 ? s[k - 1] + alpha * step[k - 2] : s[0];
                ok = sk > prev;
            }
            if (ok && s[N - 1] + alpha * step[N - 2] < s[N]) break;
        }
        for (int k = 1; k < N; ++k) s[k] += alpha * step[k - 1];
    }
    std::ostringstream msg;
    msg << "RopeModel: the sheave tension-equality constraint did not converge in 50 Newton iterations "
           "(max |eps_a - eps_b| = "
        << C.cwiseAbs().maxCoeff() << "); the rope may be slack or the configuration infeasible";
    throw std::runtime_error(msg.str());
}

template <int Dim>
void RopeModel<Dim>::computeDynamics(const NodeMatrix& nodes, const NodeMatrix& nodeVelocities,
                                     const Eigen::VectorXd& qm, const Eigen::VectorXd& qmdot,
                                     RopeData<Dim>& data) const {
    const int N = numSpans(), nn = Dim * (N + 1), nm = numModal_, nw = nn + nm, nz = nw + N + 1;
    const int nc = N - 1;  // dependent material coordinates s_1..s_{N-1} (z indices nw+1..nw+nc)
    const Eigen::VectorXd& s = data.materialCoordinates;
    // solveMaterialCoordinates left the span coordinates and the end-strain gradients (velocity
    // independent) of this configuration in data; they are reused when they belong to these positions,
    // and solved afresh otherwise.
    bool current = static_cast<int>(data.spanQ.size()) == N && s.size() == N + 1;
    for (int j = 0; current && j < N; ++j)
        current = data.spanQ[j].template segment<Dim>(0) == nodes.col(j) &&
                  data.spanQ[j].template segment<Dim>(Dim) == nodes.col(j + 1) &&
                  data.spanQ[j].segment(2 * Dim, spans_[j].numModalCoordinates()) ==
                      qm.segment(modalOffset_[j], spans_[j].numModalCoordinates());
    if (!current) solveMaterialCoordinates(nodes, qm, data);

    // Independent velocities w = [rdot; qdot_m].
    data.w.resize(nw);
    for (int k = 0; k <= N; ++k) data.w.template segment<Dim>(Dim * k) = nodeVelocities.col(k);
    data.w.tail(nm) = qmdot;

    data.spans.resize(N);
    data.materialRates.setZero(N + 1);
    auto fillSpanVelocities = [&] {
        for (int j = 0; j < N; ++j) {
            const auto& sp = spans_[j];
            Eigen::VectorXd& qd = data.spanQdot[j];
            qd.resize(sp.numCoordinates());
            qd.template segment<Dim>(0) = nodeVelocities.col(j);
            qd.template segment<Dim>(Dim) = nodeVelocities.col(j + 1);
            qd.segment(2 * Dim, sp.numModalCoordinates()) = qmdot.segment(modalOffset_[j], sp.numModalCoordinates());
            qd[sp.s1Index()] = data.materialRates[j];
            qd[sp.s2Index()] = data.materialRates[j + 1];
        }
    };
    data.spanQdot.resize(N);
    // Velocity transformation zdot = G w, zddot = G wdot + c: G is the identity on w, zero for the
    // fixed s_0 and s_N, and Gs = -C_s^-1 C_w for the dependent s; c is nonzero only there.
    if (nc > 0) {
        // Constraint Jacobian C_z = [C_w, C_s] from the end-strain gradients.
        data.Cw.setZero(nc, nw);
        data.Cs.setZero(nc, nc);
        for (int k = 1; k < N; ++k) {
            for (int side = 0; side < 2; ++side) {
                const int j = side == 0 ? k - 1 : k;
                const double sign = side == 0 ? 1.0 : -1.0;
                const auto& g = side == 0 ? data.secondEnd[j].gradient : data.firstEnd[j].gradient;
                const auto& map = spanToRope_[j];
                for (int i = 0; i < g.size(); ++i) {
                    const int zi = map[i];
                    if (zi < nw) {
                        data.Cw(k - 1, zi) += sign * g[i];
                    } else {
                        const int sk = zi - nw;  // node index of this material coordinate
                        if (sk >= 1 && sk <= N - 1) data.Cs(k - 1, sk - 1) += sign * g[i];
                    }
                }
            }
        }
        data.constraintLu.compute(data.Cs);
        data.Gs = data.constraintLu.solve(data.Cw);
        data.Gs *= -1.0;  // sdot_dep = Gs w
        data.materialRates.segment(1, nc).noalias() = data.Gs * data.w;
        // Biases with the complete velocities (sdot included).
        fillSpanVelocities();
        endStrains(nodes, qm, s, data);
        data.bias.resize(nc);
        for (int k = 1; k < N; ++k)
            data.bias[k - 1] = data.secondEnd[k - 1].accelerationBias - data.firstEnd[k].accelerationBias;
        data.cd = data.constraintLu.solve(data.bias);
        data.cd *= -1.0;
    } else {
        fillSpanVelocities();
    }

    // Span evaluations scattered into the rope's M and Q.
    data.Mz.setZero(nz, nz);
    data.Qz.setZero(nz);
    data.kineticEnergy = data.strainEnergy = data.gravityEnergy = 0;
    for (int j = 0; j < N; ++j) {
        SpanData<Dim>& d = data.spans[j];
        spans_[j].evaluate(data.spanQ[j], data.spanQdot[j], d);
        const auto& map = spanToRope_[j];
        const int n = spans_[j].numCoordinates();
        for (int a = 0; a < n; ++a) {
            data.Qz[map[a]] += d.velocityForces[a] + d.elasticForces[a] + d.gravityForces[a];
            for (int b = 0; b < n; ++b) data.Mz(map[a], map[b]) += d.massMatrix(a, b);
        }
        data.kineticEnergy += d.kineticEnergy;
        data.strainEnergy += d.strainEnergy();
        data.gravityEnergy += d.gravityEnergy;
    }
    // Mbar = G^T Mz G = M_ww + M_wd Gs + Gs^T M_dw + Gs^T M_dd Gs,
    // Qbar = G^T (Qz - Mz c) = Q_w - M_wd c_d + Gs^T (Q_d - M_dd c_d).
    data.Mbar = data.Mz.topLeftCorner(nw, nw);
    data.Qbar = data.Qz.head(nw);
    if (nc > 0) {
        const auto Mwd = data.Mz.block(0, nw + 1, nw, nc);
        const auto Mdd = data.Mz.block(nw + 1, nw + 1, nc, nc);
        data.MwdGs.noalias() = Mwd * data.Gs;  // nw x nw
        data.Mbar += data.MwdGs;
        data.Mbar += data.MwdGs.transpose();
        data.MddGs.noalias() = Mdd * data.Gs;  // nc x nw
        data.Mbar.noalias() += data.Gs.transpose() * data.MddGs;
        data.Qbar.noalias() -= Mwd * data.cd;
        data.Qd = data.Qz.segment(nw + 1, nc);
        data.Qd.noalias() -= Mdd * data.cd;
        data.Qbar.noalias() += data.Gs.transpose() * data.Qd;
    }

    // Reduce to the nodes: S = Mbar_nn - Mbar_nm Mbar_mm^-1 Mbar_mn, h = Qbar_n - Mbar_nm Mbar_mm^-1 Qbar_m.
    data.nodeMass = data.Mbar.topLeftCorner(nn, nn);
    data.nodeForce = data.Qbar.head(nn);
    if (nm > 0) {
        data.modalMass.compute(data.Mbar.bottomRightCorner(nm, nm));
        data.modalCoupling = data.modalMass.solve(data.Mbar.bottomLeftCorner(nm, nn));
        data.modalFree = data.modalMass.solve(data.Qbar.tail(nm));
        data.nodeMass.noalias() -= data.Mbar.topRightCorner(nn, nm) * data.modalCoupling;
        data.nodeForce.noalias() -= data.Mbar.topRightCorner(nn, nm) * data.modalFree;
    }
}

template <int Dim>
void RopeModel<Dim>::modalAccelerations(const RopeData<Dim>& data, const Eigen::VectorXd& nodeAccelerations,
                                        Eigen::VectorXd& qmddot) const {
    if (numModal_ == 0) {
        qmddot.resize(0);
        return;
    }
    qmddot = data.modalFree;
    qmddot.noalias() -= data.modalCoupling * nodeAccelerations;
}

template <int Dim>
double RopeModel<Dim>::constraintError(const RopeData<Dim>& data, int k) const {
    return properties().axialStiffness * (data.secondEnd[k - 1].strain - data.firstEnd[k].strain);
}

template class RopeModel<2>;
template class RopeModel<3>;

}  // namespace SimbodyReeving
