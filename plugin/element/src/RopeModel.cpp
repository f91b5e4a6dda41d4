#include "SimbodyReeving/element/RopeModel.h"

#include "RopeWorkspace.h"

#include <Eigen/LU>

#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

namespace SimbodyReeving {

template <int Dim>
RopeModel<Dim>::RopeModel(std::vector<SpanModel<Dim>> spans, double unstretchedLength,
                          std::vector<MaterialNode> nodeKinds)
    : spans_(std::move(spans)), nodeKind_(std::move(nodeKinds)), length_(unstretchedLength) {
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
            p.bendingStiffness != p0.bendingStiffness || p.tensionOnly != p0.tensionOnly)
            throw std::invalid_argument("RopeModel: all spans of a rope must have the same RopeProperties");
    }
    const int N = numSpans();
    if (nodeKind_.empty()) {
        nodeKind_.assign(N + 1, MaterialNode::Sliding);
        nodeKind_.front() = nodeKind_.back() = MaterialNode::Fixed;
    }
    if (static_cast<int>(nodeKind_.size()) != N + 1) {
        std::ostringstream msg;
        msg << "RopeModel: " << nodeKind_.size() << " node kinds given for " << N + 1 << " nodes";
        throw std::invalid_argument(msg.str());
    }
    slidingIndex_.assign(N + 1, -1);
    drivenIndex_.assign(N + 1, -1);
    for (int k = 0; k <= N; ++k) {
        const bool end = k == 0 || k == N;
        if (end && nodeKind_[k] == MaterialNode::Sliding)
            throw std::invalid_argument("RopeModel: end node " + std::to_string(k) +
                                        " cannot be Sliding (a sheave needs a span on both sides)");
        if (!end && nodeKind_[k] == MaterialNode::Fixed)
            throw std::invalid_argument("RopeModel: interior node " + std::to_string(k) +
                                        " cannot be Fixed (a rope fastened mid-path is two ropes)");
        if (nodeKind_[k] == MaterialNode::Sliding) {
            slidingIndex_[k] = numSliding_++;
            slidingNode_.push_back(k);
        } else if (nodeKind_[k] == MaterialNode::Driven) {
            drivenIndex_[k] = numDriven_++;
        }
    }
    condensedOffset_.assign(N, -1);
    for (int j = 0; j < N; ++j) {
        const SpanModel<Dim>& sp = spans_[j];
        modalOffset_.push_back(numModal_);
        if (sp.options().axialDynamics == AxialDynamics::QuasiStatic && sp.axialModes() > 0) {
            condensedOffset_[j] = numCondensed_;
            numCondensed_ += sp.axialModes();
            numModal_ += sp.numModalCoordinates() - sp.axialModes();
        } else {
            numModal_ += sp.numModalCoordinates();
        }
    }
    if (numCondensed_ > 0) {
        numMultipliers_ = numSliding_;
        for (int j = 0; j < N; ++j) kernels_.emplace_back(spans_[j]);  // throws for PaperLiteral spans
    }
    // z = [r_0..r_N, s_driven | q_free | q_condensed, s_sliding, nu | s_fixed]
    const int nn = Dim * (N + 1), nx = nn + numDriven_, nw = nx + numModal_, nd = numDependent();
    std::vector<int> fixedIndex(N + 1, -1);
    for (int k = 0, f = 0; k <= N; ++k)
        if (nodeKind_[k] == MaterialNode::Fixed) fixedIndex[k] = f++;
    auto materialIndex = [&](int node) {
        switch (nodeKind_[node]) {
            case MaterialNode::Driven: return nn + drivenIndex_[node];
            case MaterialNode::Sliding: return nw + numCondensed_ + slidingIndex_[node];
            case MaterialNode::Fixed: break;
        }
        return nw + nd + fixedIndex[node];
    };
    for (int j = 0; j < N; ++j) {
        const auto& sp = spans_[j];
        std::vector<int> map(sp.numCoordinates());
        for (int d = 0; d < Dim; ++d) {
            map[d] = Dim * j + d;
            map[Dim + d] = Dim * (j + 1) + d;
        }
        const int na = sp.axialModes();
        for (int i = 0; i < sp.numModalCoordinates(); ++i) {
            if (isCondensed(j))
                map[2 * Dim + i] = i < na ? nw + condensedOffset_[j] + i : nx + modalOffset_[j] + i - na;
            else
                map[2 * Dim + i] = nx + modalOffset_[j] + i;
        }
        map[sp.s1Index()] = materialIndex(j);
        map[sp.s2Index()] = materialIndex(j + 1);
        spanToRope_.push_back(std::move(map));
    }
}

template <int Dim>
void RopeModel<Dim>::setStoredRope(int node, double lengthAtZero) {
    const int N = numSpans();
    if ((node != 0 && node != N) || nodeKind_[node] != MaterialNode::Driven)
        throw std::invalid_argument("RopeModel::setStoredRope: node " + std::to_string(node) +
                                    " is not a Driven end node (rope is stored on drums at the rope's ends)");
    if (!std::isfinite(lengthAtZero))
        throw std::invalid_argument("RopeModel::setStoredRope: lengthAtZero must be finite");
    for (Storage& st : storage_)
        if (st.node == node) {
            st.lengthAtZero = lengthAtZero;
            return;
        }
    storage_.push_back({node, lengthAtZero, node == 0 ? 1.0 : -1.0});
}

template <int Dim>
double RopeModel<Dim>::storedRopeGravityEnergy(const NodeMatrix& nodes, const RopeData<Dim>& data) const {
    double u = 0;
    const double rhoA = properties().massPerLength;
    for (const Storage& st : storage_) {
        const double l = st.lengthAtZero + st.slope * data.materialCoordinates[st.node];
        u -= rhoA * l * spans_.front().gravity().dot(nodes.col(st.node));
    }
    return u;
}

template <int Dim>
void RopeModel<Dim>::spanCoordinates(int j, const NodeMatrix& nodes, const Eigen::VectorXd& qm,
                                     const RopeData<Dim>& data, Eigen::VectorXd& q) const {
    const auto& sp = spans_[j];
    q.resize(sp.numCoordinates());
    q.template segment<Dim>(0) = nodes.col(j);
    q.template segment<Dim>(Dim) = nodes.col(j + 1);
    const int nmSpan = sp.numModalCoordinates();
    if (isCondensed(j)) {
        const int na = sp.axialModes();
        q.segment(2 * Dim, na) = data.condensedAmplitudes.segment(condensedOffset_[j], na);
        q.segment(2 * Dim + na, nmSpan - na) = qm.segment(modalOffset_[j], nmSpan - na);
    } else {
        q.segment(2 * Dim, nmSpan) = qm.segment(modalOffset_[j], nmSpan);
    }
    q[sp.s1Index()] = data.materialCoordinates[j];
    q[sp.s2Index()] = data.materialCoordinates[j + 1];
}

template <int Dim>
void RopeModel<Dim>::fillSpanCoordinates(const NodeMatrix& nodes, const Eigen::VectorXd& qm,
                                         RopeData<Dim>& data) const {
    const int N = numSpans();
    data.ws().spanQ.resize(N);
    data.ws().spanQdot.resize(N);
    for (int j = 0; j < N; ++j) {
        spanCoordinates(j, nodes, qm, data, data.ws().spanQ[j]);
        if (data.ws().spanQdot[j].size() != data.ws().spanQ[j].size()) data.ws().spanQdot[j].setZero(data.ws().spanQ[j].size());
    }
}

template <int Dim>
void RopeModel<Dim>::evaluateConstraints(const NodeMatrix& nodes, const Eigen::VectorXd& qm, RopeData<Dim>& data,
                                         bool withRates) const {
    const int N = numSpans(), nw = numExternalCoordinates() + numModal_, nd = numDependent();
    const int nqc = numCondensed_, nc = numSliding_;
    fillSpanCoordinates(nodes, qm, data);
    Eigen::VectorXd& C = data.ws().newtonResidual;
    data.ws().bias.setZero(nd);
    if (!withRates || kernels_.empty()) {
        C.setZero(nd);
        data.ws().Cw.setZero(nd, nw);
        data.ws().Cd.setZero(nd, nd);
    }
    auto scatter = [&](int row, int j, const auto& gradient, double coef) {
        const auto& map = spanToRope_[j];
        for (int i = 0; i < static_cast<int>(map.size()); ++i) {
            const int zi = map[i];
            if (zi < nw)
                data.ws().Cw(row, zi) += coef * gradient[i];
            else if (zi < nw + nd)
                data.ws().Cd(row, zi - nw) += coef * gradient[i];
        }
    };

    if (kernels_.empty()) {
        // The paper's rows: eps_{k-1}(s_k) - eps_k(s_k) from the spans' analytic end strains.
        data.ws().firstEnd.resize(N);
        data.ws().secondEnd.resize(N);
        for (int j = 0; j < N; ++j) {
            spans_[j].endStrain(data.ws().spanQ[j], data.ws().spanQdot[j], SpanEnd::First, data.ws().firstEnd[j]);
            spans_[j].endStrain(data.ws().spanQ[j], data.ws().spanQdot[j], SpanEnd::Second, data.ws().secondEnd[j]);
        }
        for (int row = 0; row < nc; ++row) {
            const int k = slidingNode_[row];
            C[row] = data.ws().secondEnd[k - 1].strain - data.ws().firstEnd[k].strain;
            scatter(row, k - 1, data.ws().secondEnd[k - 1].gradient, 1.0);
            scatter(row, k, data.ws().firstEnd[k].gradient, -1.0);
            if (withRates)
                data.ws().bias[row] = data.ws().secondEnd[k - 1].accelerationBias - data.ws().firstEnd[k].accelerationBias;
        }
        return;
    }

    // Condensation rows (see the class comment): [stationarity in q_condensed | tension equality |
    // stationarity in s], the stationarity rows scaled by 1/EA.
    data.ws().condensation.resize(N);
    // Position level: values and Jacobians; velocity level (withRates): the biases only (the
    // values and Jacobians at these positions are already in data).
    static const Eigen::VectorXd noRates;
    for (int j = 0; j < N; ++j) {
        if (withRates)
            kernels_[j].evaluateRates(data.ws().spanQ[j], data.ws().spanQdot[j], data.ws().condensation[j]);
        else
            kernels_[j].evaluate(data.ws().spanQ[j], noRates, data.ws().condensation[j]);
    }
    const double invEA = 1.0 / properties().axialStiffness;
    auto addTerm = [&](int row, int j, int quantity, double coef) {
        const auto& K = data.ws().condensation[j];
        if (withRates) {
            data.ws().bias[row] += coef * K.accelerationBias[quantity];
            return;
        }
        C[row] += coef * K.value[quantity];
        scatter(row, j, K.gradient.row(quantity), coef);
    };
    // coef * nu_m * f with f a span quantity: nu is a dependent coordinate too. Only Sliding nodes
    // m have a constraint C_m and a multiplier; the terms of other nodes vanish.
    auto addProduct = [&](int row, int m, int j, int quantity, double coef) {
        if (m < 1 || m > N - 1 || slidingIndex_[m] < 0) return;
        const int mi = slidingIndex_[m];
        const auto& K = data.ws().condensation[j];
        const double nu = data.multipliers[mi];
        if (withRates) {
            data.ws().bias[row] += coef * (nu * K.accelerationBias[quantity] +
                                      2.0 * data.multiplierRates[mi] * K.rate[quantity]);
            return;
        }
        C[row] += coef * nu * K.value[quantity];
        scatter(row, j, K.gradient.row(quantity), coef * nu);
        data.ws().Cd(row, nqc + nc + mi) += coef * K.value[quantity];
    };
    for (int j = 0; j < N; ++j) {
        if (!isCondensed(j)) continue;
        const AxialCondensation<Dim>& kj = kernels_[j];
        for (int i = 0; i < spans_[j].axialModes(); ++i) {
            const int row = condensedOffset_[j] + i;
            addTerm(row, j, kj.phi(i), invEA);
            addProduct(row, j, j, kj.endStrainAxialSlope(SpanEnd::First, i), -1.0);
            addProduct(row, j + 1, j, kj.endStrainAxialSlope(SpanEnd::Second, i), 1.0);
        }
    }
    for (int ki = 0; ki < nc; ++ki) {
        const int k = slidingNode_[ki], row = nqc + ki;
        addTerm(row, k - 1, kernels_[k - 1].endStrain(SpanEnd::Second), 1.0);
        addTerm(row, k, kernels_[k].endStrain(SpanEnd::First), -1.0);
    }
    for (int ki = 0; ki < nc; ++ki) {
        const int k = slidingNode_[ki], row = nqc + nc + ki;
        // dU/ds_k = dU_{k-1}/dl_{k-1} - dU_k/dl_k (s_k ends span k-1 and starts span k).
        addTerm(row, k - 1, kernels_[k - 1].lengthDerivative(), invEA);
        addTerm(row, k, kernels_[k].lengthDerivative(), -invEA);
        // sum_m nu_m dC_m/ds_k with C_m = eps2_{m-1}(l_{m-1}) - eps1_m(l_m), l_j = s_{j+1} - s_j.
        addProduct(row, k, k - 1, kernels_[k - 1].endStrainLengthSlope(SpanEnd::Second), 1.0);
        addProduct(row, k, k, kernels_[k].endStrainLengthSlope(SpanEnd::First), 1.0);
        addProduct(row, k + 1, k, kernels_[k].endStrainLengthSlope(SpanEnd::Second), -1.0);
        addProduct(row, k - 1, k - 1, kernels_[k - 1].endStrainLengthSlope(SpanEnd::First), -1.0);
    }
}

template <int Dim>
void RopeModel<Dim>::setKnownMaterialCoordinates(const NodeMatrix& nodes, const Eigen::VectorXd& drivenS,
                                                 RopeData<Dim>& data) const {
    const int N = numSpans();
    if (drivenS.size() != numDriven_) {
        std::ostringstream msg;
        msg << "RopeModel: " << drivenS.size() << " driven material coordinates given for " << numDriven_
            << " Driven nodes";
        throw std::invalid_argument(msg.str());
    }
    Eigen::VectorXd& s = data.materialCoordinates;
    bool warm = s.size() == N + 1 && s.allFinite();
    if (!warm) s.setZero(N + 1);
    auto known = [&](int k) { return nodeKind_[k] != MaterialNode::Sliding; };
    auto knownValue = [&](int k) {
        return nodeKind_[k] == MaterialNode::Fixed ? (k == 0 ? 0.0 : length_) : drivenS[drivenIndex_[k]];
    };
    // Warm start: where the known coordinates on either side of a stretch of Sliding nodes moved
    // (drums turned), the old Sliding values are mapped proportionally into the new stretch.
    for (int a = 0; warm && a < N;) {
        int b = a + 1;
        while (!known(b)) ++b;
        const double oldA = s[a], oldB = s[b], newA = knownValue(a), newB = knownValue(b);
        if ((oldA != newA || oldB != newB) && oldB > oldA && newB > newA)
            for (int k = a + 1; k < b; ++k) s[k] = newA + (s[k] - oldA) * ((newB - newA) / (oldB - oldA));
        a = b;
    }
    for (int k = 0; k <= N; ++k)
        if (known(k)) s[k] = knownValue(k);
    // Every stretch between consecutive known nodes must hold material.
    for (int a = 0; a < N;) {
        int b = a + 1;
        while (!known(b)) ++b;
        if (!(s[b] > s[a])) {
            std::ostringstream msg;
            msg << "RopeModel: no rope material between node " << a << " (s = " << s[a] << " m) and node " << b
                << " (s = " << s[b] << " m): the " << (b - a == 1 ? "span " + std::to_string(a) : "spans")
                << " between them would have a non-positive unstretched length";
            throw std::runtime_error(msg.str());
        }
        a = b;
    }
    for (int k = 0; warm && k < N; ++k) warm = s[k + 1] > s[k];
    if (warm) return;
    // Chord-proportional guess for the Sliding nodes between consecutive known nodes.
    for (int a = 0; a < N;) {
        int b = a + 1;
        while (!known(b)) ++b;
        double total = 0;
        for (int j = a; j < b; ++j) total += (nodes.col(j + 1) - nodes.col(j)).norm();
        double acc = 0;
        for (int j = a; j + 1 < b; ++j) {
            acc += (nodes.col(j + 1) - nodes.col(j)).norm();
            s[j + 1] = total > 0 ? s[a] + (s[b] - s[a]) * acc / total : s[a] + (s[b] - s[a]) * (j + 1 - a) / (b - a);
        }
        a = b;
    }
}

template <int Dim>
void RopeModel<Dim>::solveDependentCoordinates(const NodeMatrix& nodes, const Eigen::VectorXd& qm,
                                               RopeData<Dim>& data) const {
    static const Eigen::VectorXd none;
    solveDependentCoordinates(nodes, none, qm, data);
}

template <int Dim>
void RopeModel<Dim>::solveDependentCoordinates(const NodeMatrix& nodes, const Eigen::VectorXd& drivenS,
                                               const Eigen::VectorXd& qm, RopeData<Dim>& data) const {
    const int N = numSpans(), nqc = numCondensed_, nd = numDependent();
    Eigen::VectorXd& s = data.materialCoordinates;
    const bool warm = s.size() == N + 1 && s.allFinite();
    setKnownMaterialCoordinates(nodes, drivenS, data);
    if (data.condensedAmplitudes.size() != nqc || !data.condensedAmplitudes.allFinite())
        data.condensedAmplitudes.setZero(nqc);
    if (data.multipliers.size() != numMultipliers_ || !data.multipliers.allFinite())
        data.multipliers.setZero(numMultipliers_);
    data.multiplierRates.setZero(numMultipliers_);
    data.newtonIterations = 0;
    for (auto& v : data.ws().spanQdot) v.setZero();
    const Eigen::VectorXd& C = data.ws().newtonResidual;
    double previous = std::numeric_limits<double>::infinity();
    // Newton from the previous solution (warm start). If that fails, once more from the cold
    // start (chord-proportional material coordinates, zero amplitudes and multipliers): a warm start
    // far from the new solution (a report interpolated a long way from the last evaluation, the
    // rope having run metres over its sheaves) may lie outside Newton's basin.
    bool coldRetry = warm;
    constexpr int kMaxIterations = 100;  // damped steps count as iterations
    double previousMerit = std::numeric_limits<double>::infinity(), alpha = 0, alphaCap = 1.0;
    int backtracks = 0;
    // The dependent coordinates y = [q_condensed | s_sliding | nu]: newtonStart holds y before the
    // current step, applyStep sets y = start + a * step.
    auto saveStart = [&]() {
        Eigen::VectorXd& y = data.ws().newtonStart;
        y.resize(nd);
        y.head(nqc) = data.condensedAmplitudes;
        for (int ki = 0; ki < numSliding_; ++ki) y[nqc + ki] = s[slidingNode_[ki]];
        y.tail(numMultipliers_) = data.multipliers;
    };
    auto applyStep = [&](const Eigen::VectorXd& start, double a) {
        const Eigen::VectorXd& step = data.ws().newtonStep;
        data.condensedAmplitudes = start.head(nqc) + a * step.head(nqc);
        for (int ki = 0; ki < numSliding_; ++ki) s[slidingNode_[ki]] = start[nqc + ki] + a * step[nqc + ki];
        data.multipliers = start.tail(numMultipliers_) + a * step.tail(numMultipliers_);
    };
    for (int iter = 0; iter <= kMaxIterations; ++iter) {
        if (iter == kMaxIterations && coldRetry) {
            coldRetry = false;
            iter = 0;
            previousMerit = std::numeric_limits<double>::infinity();
            backtracks = 0;
            alpha = 0;
            alphaCap = 1.0;
            previous = std::numeric_limits<double>::infinity();
            s.resize(0);
            setKnownMaterialCoordinates(nodes, drivenS, data);
            data.condensedAmplitudes.setZero(nqc);
            data.multipliers.setZero(numMultipliers_);
        }
        evaluateConstraints(nodes, qm, data, false);
        if (nd == 0) return;
        // Converged at 1e-15 in strain, or stagnating at round-off below 1e-12 (eps = 1/2(|t|^2/l^2 - 1)
        // carries about 1e-16 absolute error, the stationarity sums a few times that). States with
        // very large strains (an impact, an integrator's far trial state) have a higher round-off
        // floor: after 4 iterations, stagnation below 1e-9 is accepted too (the equations then hold
        // to 1e-9 in strain units), rather than failing an evaluation that has converged.
        const double err = C.cwiseAbs().maxCoeff();
        const bool stagnating = err > 0.5 * previous;
        if (err <= 1e-15 || (stagnating && err <= 1e-12) || (stagnating && iter >= 4 && err <= 1e-9)) {
            data.newtonIterations = iter;
            return;
        }
        // Damping: if the last step did not reduce |C|_2 (Newton overshooting a sharp change of
        // curvature, e.g. where a tension-only span's points go slack: undamped, Newton can cycle
        // between two iterates), go back to where it started and take half of it (the Newton
        // direction descends on |C|_2^2), up to 30 halvings. The next step then starts from twice
        // the damping that worked, so the full step returns once the iterates are close.
        const double merit = C.squaredNorm();
        if (iter > 0 && merit >= previousMerit && backtracks < 30 && alpha > 0) {
            ++backtracks;
            alpha *= 0.5;
            applyStep(data.ws().newtonStart, alpha);
            continue;
        }
        if (alpha > 0) alphaCap = std::min(1.0, 2.0 * alpha);
        backtracks = 0;
        previous = err;
        previousMerit = merit;
        if (iter == kMaxIterations && !coldRetry) break;
        if (iter == kMaxIterations) continue;  // the cold retry starts at the top of the loop
        data.ws().newtonLu.compute(data.ws().Cd);
        Eigen::VectorXd& step = data.ws().newtonStep;
        step = data.ws().newtonLu.solve(C);
        step *= -1.0;
        // Halve the step until the material coordinates stay ordered (every span keeps l > 0).
        auto stepped = [&](int k, double a) {
            return slidingIndex_[k] >= 0 ? s[k] + a * step[nqc + slidingIndex_[k]] : s[k];
        };
        alpha = alphaCap;
        for (int halve = 0; halve < 30; ++halve, alpha *= 0.5) {
            bool ok = true;
            for (int k = 1; k <= N && ok; ++k) ok = stepped(k, alpha) > stepped(k - 1, alpha);
            if (ok) break;
        }
        saveStart();
        applyStep(data.ws().newtonStart, alpha);
    }
    // Name the equation with the largest residual: rows [condensed amplitudes | tension equality
    // at sheaves 1..N-1 | (QuasiStatic) stationarity in s at sheaves 1..N-1].
    Eigen::Index worst = 0;
    C.cwiseAbs().maxCoeff(&worst);
    const int row = static_cast<int>(worst);
    std::ostringstream where;
    if (row < nqc) {
        int span = 0;
        for (int j = 0; j < N; ++j)
            if (condensedOffset_[j] >= 0 && row >= condensedOffset_[j] && row < condensedOffset_[j] + spans_[j].axialModes())
                span = j;
        where << "span " << span << " (quasi-static axial amplitudes)";
    } else if (row < nqc + numSliding_) {
        const int k = slidingNode_[row - nqc];
        where << "sheave node " << k << " (tension equality of spans " << k - 1 << " and " << k << ")";
    } else {
        where << "sheave node " << slidingNode_[row - nqc - numSliding_]
              << " (stationarity in its material coordinate)";
    }
    std::ostringstream msg;
    msg << "RopeModel: the dependent coordinates (sheave tension equality"
        << (nqc > 0 ? ", quasi-static axial modes" : "") << ") did not converge in " << kMaxIterations << " Newton iterations "
        << "(max residual " << C.cwiseAbs().maxCoeff() << " in strain units, at " << where.str()
        << "); the configuration may be infeasible (a span shorter than its chord allows, nodes crossing)";
    throw std::runtime_error(msg.str());
}

template <int Dim>
bool RopeModel<Dim>::positionsMatch(const NodeMatrix& nodes, const Eigen::VectorXd& drivenS, const Eigen::VectorXd& qm,
                                    const RopeData<Dim>& data) const {
    const int N = numSpans();
    if (static_cast<int>(data.ws().spanQ.size()) != N || data.materialCoordinates.size() != N + 1 ||
        data.condensedAmplitudes.size() != numCondensed_ || data.multipliers.size() != numMultipliers_ ||
        drivenS.size() != numDriven_)
        return false;
    for (int k = 0; k <= N; ++k)
        if (drivenIndex_[k] >= 0 && data.materialCoordinates[k] != drivenS[drivenIndex_[k]]) return false;
    for (int j = 0; j < N; ++j) {
        const auto& q = data.ws().spanQ[j];
        const int nmSpan = spans_[j].numModalCoordinates();
        const int na = isCondensed(j) ? spans_[j].axialModes() : 0;
        if (q.size() != spans_[j].numCoordinates() || q.template segment<Dim>(0) != nodes.col(j) ||
            q.template segment<Dim>(Dim) != nodes.col(j + 1) ||
            q.segment(2 * Dim + na, nmSpan - na) != qm.segment(modalOffset_[j], nmSpan - na))
            return false;
    }
    return true;
}

template <int Dim>
void RopeModel<Dim>::computeDynamics(const NodeMatrix& nodes, const NodeMatrix& nodeVelocities,
                                     const Eigen::VectorXd& qm, const Eigen::VectorXd& qmdot,
                                     RopeData<Dim>& data) const {
    static const Eigen::VectorXd none;
    computeDynamics(nodes, nodeVelocities, none, none, qm, qmdot, data);
}

template <int Dim>
void RopeModel<Dim>::computeDynamics(const NodeMatrix& nodes, const NodeMatrix& nodeVelocities,
                                     const Eigen::VectorXd& drivenS, const Eigen::VectorXd& drivenSdot,
                                     const Eigen::VectorXd& qm, const Eigen::VectorXd& qmdot,
                                     RopeData<Dim>& data) const {
    const int N = numSpans(), nn = Dim * (N + 1), nx = nn + numDriven_, nm = numModal_, nw = nx + nm;
    const int nqc = numCondensed_, nc = numSliding_, nd = numDependent(), nz = nw + nd + (N + 1 - nc - numDriven_);
    // solveDependentCoordinates left the span coordinates and the constraint Jacobians (velocity
    // independent) of this configuration in data; they are reused when they belong to these
    // positions, and solved afresh otherwise.
    if (!positionsMatch(nodes, drivenS, qm, data)) solveDependentCoordinates(nodes, drivenS, qm, data);
    if (drivenSdot.size() != numDriven_)
        throw std::invalid_argument("RopeModel::computeDynamics: drivenSdot has the wrong size");

    // Independent velocities w = [rdot; sdot_driven; qdot_m].
    data.ws().w.resize(nw);
    for (int k = 0; k <= N; ++k) data.ws().w.template segment<Dim>(Dim * k) = nodeVelocities.col(k);
    data.ws().w.segment(nn, numDriven_) = drivenSdot;
    data.ws().w.tail(nm) = qmdot;

    data.ws().spans.resize(N);
    data.materialRates.setZero(N + 1);
    for (int k = 0; k <= N; ++k)
        if (drivenIndex_[k] >= 0) data.materialRates[k] = drivenSdot[drivenIndex_[k]];
    data.condensedRates.setZero(nqc);
    data.multiplierRates.setZero(numMultipliers_);
    auto fillSpanVelocities = [&] {
        for (int j = 0; j < N; ++j) {
            const auto& sp = spans_[j];
            Eigen::VectorXd& qd = data.ws().spanQdot[j];
            qd.resize(sp.numCoordinates());
            qd.template segment<Dim>(0) = nodeVelocities.col(j);
            qd.template segment<Dim>(Dim) = nodeVelocities.col(j + 1);
            const int nmSpan = sp.numModalCoordinates();
            if (isCondensed(j)) {
                const int na = sp.axialModes();
                qd.segment(2 * Dim, na) = data.condensedRates.segment(condensedOffset_[j], na);
                qd.segment(2 * Dim + na, nmSpan - na) = qmdot.segment(modalOffset_[j], nmSpan - na);
            } else {
                qd.segment(2 * Dim, nmSpan) = qmdot.segment(modalOffset_[j], nmSpan);
            }
            qd[sp.s1Index()] = data.materialRates[j];
            qd[sp.s2Index()] = data.materialRates[j + 1];
        }
    };
    data.ws().spanQdot.resize(N);
    // Velocity transformation zdot = G w, zddot = G wdot + c: G is the identity on w, zero for the
    // Fixed material coordinates, and Gd = -C_d^-1 C_w for the dependents d; c is nonzero only there.
    if (nd > 0) {
        data.ws().constraintLu.compute(data.ws().Cd);
        data.ws().Gd = data.ws().constraintLu.solve(data.ws().Cw);
        data.ws().Gd *= -1.0;  // ddot = Gd w
        data.ws().cd.noalias() = data.ws().Gd * data.ws().w;  // (scratch: ddot)
        data.condensedRates = data.ws().cd.head(nqc);
        for (int ki = 0; ki < nc; ++ki) data.materialRates[slidingNode_[ki]] = data.ws().cd[nqc + ki];
        data.multiplierRates = data.ws().cd.tail(numMultipliers_);
        // Biases (second time derivatives of the constraints at wdot = 0) with the complete
        // velocities, dependent rates included.
        fillSpanVelocities();
        evaluateConstraints(nodes, qm, data, true);
        data.ws().cd = data.ws().constraintLu.solve(data.ws().bias);
        data.ws().cd *= -1.0;
    } else {
        fillSpanVelocities();
    }

    // Span evaluations scattered into the rope's M and Q (the multipliers carry no mass).
    data.ws().Mz.setZero(nz, nz);
    data.ws().Qz.setZero(nz);
    data.inertialCorrectionValid = false;
    if (nqc > 0) data.ws().velocityForcesZ.setZero(nz);
    data.kineticEnergy = data.strainEnergy = data.gravityEnergy = 0;
    for (int j = 0; j < N; ++j) {
        SpanData<Dim>& d = data.ws().spans[j];
        spans_[j].evaluate(data.ws().spanQ[j], data.ws().spanQdot[j], d);
        const auto& map = spanToRope_[j];
        const int n = spans_[j].numCoordinates();
        for (int a = 0; a < n; ++a) {
            data.ws().Qz[map[a]] += d.velocityForces[a] + d.elasticForces[a] + d.gravityForces[a];
            if (nqc > 0) data.ws().velocityForcesZ[map[a]] += d.velocityForces[a];
            for (int b = 0; b < n; ++b) data.ws().Mz(map[a], map[b]) += d.massMatrix(a, b);
        }
        data.kineticEnergy += d.kineticEnergy;
        data.strainEnergy += d.strainEnergy();
        data.gravityEnergy += d.gravityEnergy;
    }
    // Mbar = G^T Mz G = M_ww + M_wd Gd + Gd^T M_dw + Gd^T M_dd Gd,
    // Qbar = G^T (Qz - Mz c) = Q_w - M_wd c_d + Gd^T (Q_d - M_dd c_d).
    data.ws().Mbar = data.ws().Mz.topLeftCorner(nw, nw);
    data.ws().Qbar = data.ws().Qz.head(nw);
    if (nd > 0) {
        const auto Mwd = data.ws().Mz.block(0, nw, nw, nd);
        const auto Mdd = data.ws().Mz.block(nw, nw, nd, nd);
        data.ws().MwdGd.noalias() = Mwd * data.ws().Gd;  // nw x nw
        data.ws().Mbar += data.ws().MwdGd;
        data.ws().Mbar += data.ws().MwdGd.transpose();
        data.ws().MddGd.noalias() = Mdd * data.ws().Gd;  // nd x nw
        data.ws().Mbar.noalias() += data.ws().Gd.transpose() * data.ws().MddGd;
        data.ws().Qbar.noalias() -= Mwd * data.ws().cd;
        data.ws().Qd = data.ws().Qz.segment(nw, nd);
        data.ws().Qd.noalias() -= Mdd * data.ws().cd;
        data.ws().Qbar.noalias() += data.ws().Gd.transpose() * data.ws().Qd;
    }

    // Reduce to the external coordinates: S = Mbar_xx - Mbar_xm Mbar_mm^-1 Mbar_mx,
    // h = Qbar_x - Mbar_xm Mbar_mm^-1 Qbar_m.
    data.nodeMass = data.ws().Mbar.topLeftCorner(nx, nx);
    data.nodeForce = data.ws().Qbar.head(nx);
    if (nm > 0) {
        data.ws().modalMass.compute(data.ws().Mbar.bottomRightCorner(nm, nm));
        data.ws().modalCoupling = data.ws().modalMass.solve(data.ws().Mbar.bottomLeftCorner(nm, nx));
        data.ws().modalFree = data.ws().modalMass.solve(data.ws().Qbar.tail(nm));
        data.nodeMass.noalias() -= data.ws().Mbar.topRightCorner(nx, nm) * data.ws().modalCoupling;
        data.nodeForce.noalias() -= data.ws().Mbar.topRightCorner(nx, nm) * data.ws().modalFree;
    }

    // Rope stored on drums (setStoredRope): L_st = 1/2 rhoA l(s) (|rdot|^2 + sdot^2) + rhoA l(s) g.r,
    // l = l0 + c s, gives
    //     rhoA l rddot = rhoA l g - rhoA c sdot rdot + f_r,
    //     rhoA l sddot = rhoA c (1/2 |rdot|^2 - 1/2 sdot^2 + g.r) + f_s,
    // i.e. mass rhoA l on the node's position and on s, and these forces in h. It involves only the
    // external coordinates, so it adds to S and h after the modal reduction.
    const double rhoA = properties().massPerLength;
    for (const Storage& st : storage_) {
        const int k = st.node, xs = nn + drivenIndex_[k];
        const double l = st.lengthAtZero + st.slope * data.materialCoordinates[k];
        const double sdot = data.materialRates[k];
        const Vec rdot = nodeVelocities.col(k);
        const Vec& g = spans_.front().gravity();
        for (int d = 0; d < Dim; ++d) {
            data.nodeMass(Dim * k + d, Dim * k + d) += rhoA * l;
            data.nodeForce[Dim * k + d] += rhoA * l * g[d] - rhoA * st.slope * sdot * rdot[d];
        }
        data.nodeMass(xs, xs) += rhoA * l;
        data.nodeForce[xs] += rhoA * st.slope * (0.5 * rdot.squaredNorm() - 0.5 * sdot * sdot + g.dot(nodes.col(k)));
        data.kineticEnergy += 0.5 * rhoA * l * (rdot.squaredNorm() + sdot * sdot);
        data.gravityEnergy -= rhoA * l * g.dot(nodes.col(k));
    }
}

template <int Dim>
void RopeModel<Dim>::modalAccelerations(const RopeData<Dim>& data, const Eigen::VectorXd& nodeAccelerations,
                                        Eigen::VectorXd& qmddot) const {
    if (numModal_ == 0) {
        qmddot.resize(0);
        return;
    }
    qmddot = data.ws().modalFree;
    qmddot.noalias() -= data.ws().modalCoupling * nodeAccelerations;
}

template <int Dim>
void RopeModel<Dim>::recoverInertialStrain(RopeData<Dim>& data, const Eigen::VectorXd& nodeAccelerations,
                                           const Eigen::VectorXd& qmddot) const {
    if (numCondensed_ == 0) return;
    const int N = numSpans(), nx = numExternalCoordinates(), nw = nx + numModal_, nd = numDependent();
    const int nqc = numCondensed_, nc = numSliding_;
    Eigen::VectorXd& zdd = data.ws().zddot;
    zdd.setZero(nw + nd + (N + 1 - nc - numDriven_));
    zdd.head(nx) = nodeAccelerations;
    zdd.segment(nx, numModal_) = qmddot;
    zdd.segment(nw, nd).noalias() = data.ws().Gd * zdd.head(nw);
    zdd.segment(nw, nd) += data.ws().cd;
    const double invEA = 1.0 / properties().axialStiffness;
    Eigen::VectorXd& load = data.ws().inertialLoad;
    load.setZero(nd);
    for (int r = 0; r < nqc; ++r)
        load[r] = invEA * (data.ws().Mz.row(nw + r).dot(zdd) - data.ws().velocityForcesZ[nw + r]);
    for (int k = 0; k < nc; ++k)
        load[nqc + nc + k] = invEA * (data.ws().Mz.row(nw + nqc + k).dot(zdd) - data.ws().velocityForcesZ[nw + nqc + k]);
    data.inertialCorrection = data.ws().constraintLu.solve(load);
    data.inertialCorrection *= -1.0;
    data.inertialCorrectionValid = true;
}

template <int Dim>
void RopeModel<Dim>::recoveredSpanCoordinates(int j, const NodeMatrix& nodes, const Eigen::VectorXd& qm,
                                              const RopeData<Dim>& data, Eigen::VectorXd& q) const {
    spanCoordinates(j, nodes, qm, data, q);
    if (numCondensed_ == 0 || !data.inertialCorrectionValid) return;
    const auto& sp = spans_[j];
    if (isCondensed(j))
        q.segment(2 * Dim, sp.axialModes()) += data.inertialCorrection.segment(condensedOffset_[j], sp.axialModes());
    if (slidingIndex_[j] >= 0) q[sp.s1Index()] += data.inertialCorrection[numCondensed_ + slidingIndex_[j]];
    if (slidingIndex_[j + 1] >= 0) q[sp.s2Index()] += data.inertialCorrection[numCondensed_ + slidingIndex_[j + 1]];
}

template <int Dim>
double RopeModel<Dim>::constraintError(const RopeData<Dim>& data, int k) const {
    if (!kernels_.empty())
        return properties().axialStiffness * (data.ws().condensation[k - 1].value[kernels_[k - 1].endStrain(SpanEnd::Second)] -
                                              data.ws().condensation[k].value[kernels_[k].endStrain(SpanEnd::First)]);
    return properties().axialStiffness * (data.ws().secondEnd[k - 1].strain - data.ws().firstEnd[k].strain);
}

template <int Dim>
RopeData<Dim>::RopeData() : workspace_(std::make_unique<detail::RopeWorkspace<Dim>>()) {}
template <int Dim>
RopeData<Dim>::~RopeData() = default;
template <int Dim>
RopeData<Dim>::RopeData(const RopeData&) = default;
template <int Dim>
RopeData<Dim>& RopeData<Dim>::operator=(const RopeData&) = default;
template <int Dim>
RopeData<Dim>::RopeData(RopeData&&) noexcept = default;
template <int Dim>
RopeData<Dim>& RopeData<Dim>::operator=(RopeData&&) noexcept = default;
template <int Dim>
const Eigen::MatrixXd& RopeData<Dim>::reducedMass() const { return ws().Mbar; }
template <int Dim>
const Eigen::VectorXd& RopeData<Dim>::reducedForce() const { return ws().Qbar; }
template <int Dim>
const Eigen::VectorXd& RopeData<Dim>::spanCoordinates(int span) const { return ws().spanQ[span]; }

template struct RopeData<2>;
template struct RopeData<3>;
template class RopeModel<2>;
template class RopeModel<3>;

}  // namespace SimbodyReeving
