#include "SimbodyReeving/element/RopeModel.h"

#include "NodeLaw.h"
#include "RopeElements.h"
#include "RopeWorkspace.h"
#include "TensionRow.h"
#include "SimbodyReeving/element/AxialCondensation.h"
#include "SimbodyReeving/element/BandedLU.h"
#include "SimbodyReeving/element/GrooveArc.h"
#include "SimbodyReeving/element/WrapStationMap.h"

#include <Eigen/Geometry>
#include <Eigen/LU>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <variant>

namespace SimbodyReeving {
namespace {
// dst row `dest` (+/-)= M[source] * src row `from` for each term, rows of width P (0: p at run
// time); terms whose source row is not live are skipped (live == nullptr: all are).
template <int P, bool Subtract, class Term>
void applyRowTermsOf(const Term* t, const Term* end, const double* M, const double* src, double* dst, int p,
                     const char* live) {
    const int w = P > 0 ? P : p;
    for (; t != end; ++t) {
        if (live && !live[t->from]) continue;
        const double m = M[t->source];
        const double* __restrict x = src + static_cast<std::ptrdiff_t>(t->from) * w;
        double* __restrict y = dst + static_cast<std::ptrdiff_t>(t->dest) * w;
        for (int c = 0; c < w; ++c) {
            if (Subtract)
                y[c] -= m * x[c];
            else
                y[c] += m * x[c];
        }
    }
}
// y (+/-)= v x over rows of width p, the common widths unrolled.
template <int P, bool Subtract>
inline void axpyRowOf(double v, const double* __restrict x, double* __restrict y, int p) {
    const int w = P > 0 ? P : p;
    for (int c = 0; c < w; ++c) {
        if (Subtract)
            y[c] -= v * x[c];
        else
            y[c] += v * x[c];
    }
}
template <bool Subtract>
inline void axpyRow(double v, const double* x, double* y, int p) {
    switch (p) {
        case 1: return axpyRowOf<1, Subtract>(v, x, y, p);
        case 2: return axpyRowOf<2, Subtract>(v, x, y, p);
        case 3: return axpyRowOf<3, Subtract>(v, x, y, p);
        case 4: return axpyRowOf<4, Subtract>(v, x, y, p);
        case 5: return axpyRowOf<5, Subtract>(v, x, y, p);
        case 6: return axpyRowOf<6, Subtract>(v, x, y, p);
        case 7: return axpyRowOf<7, Subtract>(v, x, y, p);
        case 8: return axpyRowOf<8, Subtract>(v, x, y, p);
        default: return axpyRowOf<0, Subtract>(v, x, y, p);
    }
}
// The same with the common widths (the coupling's mobilities + 1) unrolled.
template <bool Subtract, class Term>
void applyRowTerms(const Term* t, const Term* end, const double* M, const double* src, double* dst, int p,
                   const char* live) {
    switch (p) {
        case 1: return applyRowTermsOf<1, Subtract>(t, end, M, src, dst, p, live);
        case 2: return applyRowTermsOf<2, Subtract>(t, end, M, src, dst, p, live);
        case 3: return applyRowTermsOf<3, Subtract>(t, end, M, src, dst, p, live);
        case 4: return applyRowTermsOf<4, Subtract>(t, end, M, src, dst, p, live);
        case 5: return applyRowTermsOf<5, Subtract>(t, end, M, src, dst, p, live);
        case 6: return applyRowTermsOf<6, Subtract>(t, end, M, src, dst, p, live);
        case 7: return applyRowTermsOf<7, Subtract>(t, end, M, src, dst, p, live);
        case 8: return applyRowTermsOf<8, Subtract>(t, end, M, src, dst, p, live);
        default: return applyRowTermsOf<0, Subtract>(t, end, M, src, dst, p, live);
    }
}
}  // namespace

template <int Dim>
RopeModel<Dim>::~RopeModel() = default;
template <int Dim>
RopeModel<Dim>::RopeModel(const RopeModel&) = default;
template <int Dim>
RopeModel<Dim>& RopeModel<Dim>::operator=(const RopeModel&) = default;
template <int Dim>
RopeModel<Dim>::RopeModel(RopeModel&&) noexcept = default;
template <int Dim>
RopeModel<Dim>& RopeModel<Dim>::operator=(RopeModel&&) noexcept = default;
template <int Dim>
int RopeModel<Dim>::numWrappedNodes() const { return static_cast<int>(elements_->arcs.size()); }

template <int Dim>
RopeModel<Dim>::RopeModel(std::vector<SpanModel<Dim>> spans, double unstretchedLength,
                          std::vector<MaterialNode> nodeKinds, std::vector<NodeWrap> wraps)
    : length_(unstretchedLength) {
    auto elements = std::make_shared<detail::RopeElements<Dim>>();
    elements->spans = std::move(spans);
    elements_ = elements;
    const std::vector<SpanModel<Dim>>& spanModels = elements->spans;
    if (spanModels.empty()) throw std::invalid_argument("RopeModel: a rope needs at least one span (got 0)");
    numSpans_ = static_cast<int>(spanModels.size());
    if (!std::isfinite(length_) || !(length_ > 0)) {
        std::ostringstream msg;
        msg << "RopeModel: unstretchedLength [m] = " << length_ << " must be finite and > 0";
        throw std::invalid_argument(msg.str());
    }
    const RopeProperties& p0 = spanModels.front().properties();
    for (const auto& sp : spanModels) {
        const RopeProperties& p = sp.properties();
        if (p.massPerLength != p0.massPerLength || p.axialStiffness != p0.axialStiffness ||
            p.bendingStiffness != p0.bendingStiffness || p.tensionOnly != p0.tensionOnly ||
            p.axialRetardationTime != p0.axialRetardationTime)
            throw std::invalid_argument("RopeModel: all spans of a rope must have the same RopeProperties");
    }
    const int N = numSpans();
    // The node laws' registration: each MaterialNode tag becomes its law type, here only.
    if (nodeKinds.empty()) {
        nodeKinds.assign(N + 1, MaterialNode::Sliding);
        nodeKinds.front() = nodeKinds.back() = MaterialNode::Fixed;
    }
    if (static_cast<int>(nodeKinds.size()) != N + 1) {
        std::ostringstream msg;
        msg << "RopeModel: " << nodeKinds.size() << " node kinds given for " << N + 1 << " nodes";
        throw std::invalid_argument(msg.str());
    }
    laws_.reserve(N + 1);
    for (int k = 0; k <= N; ++k) laws_.push_back(detail::makeNodeLaw(nodeKinds[k], k, N, length_));
    // Node blocks of the external coordinates: a point's position, or a wrapped node's
    // [c, T_in, T_out, (n), l] with its groove arc.
    if (wraps.empty()) wraps.assign(N + 1, NodeWrap{});
    if (static_cast<int>(wraps.size()) != N + 1) {
        std::ostringstream msg;
        msg << "RopeModel: " << wraps.size() << " node wraps given for " << N + 1 << " nodes";
        throw std::invalid_argument(msg.str());
    }
    arcIndex_.assign(N + 1, -1);
    nodeOffset_.assign(N + 2, 0);
    grooveAxes_.assign(N + 1, Eigen::Vector3d::UnitZ());
    axisStation_.assign(N + 1, -1);
    placements_.assign(N + 1, GroovePlacement{});
    for (int k = 0; k <= N; ++k) {
        const NodeWrap& wrap = wraps[k];
        // The groove placement's registration with its node: the unit checks its parameters; one
        // off the node's centre needs a drum (a wrapped end node is Driven: its single tangent
        // point follows the groove, Y its driven coordinate; a sheave's arc and every node block's
        // centre stay at the node's position).
        try {
            validatePlacement(wrap.groove);
        } catch (const std::invalid_argument& e) {
            throw std::invalid_argument("RopeModel: node " + std::to_string(k) + ": " + e.what());
        }
        if (!isAtCentre(wrap.groove)) {
            if (Dim != 3 || !(wrap.radius > 0) || (k != 0 && k != N) || !detail::isDrum(laws_[k]) ||
                (followsDriven(wrap.groove) && !detail::hasExternalCoordinate(laws_[k])))
                throw std::invalid_argument("RopeModel: node " + std::to_string(k) + ": a " +
                                            placementName(wrap.groove) +
                                            " groove (NodeWrap::groove, off the node's centre) needs a wrapped "
                                            "Driven end node of a spatial rope (RopeModel<3>)");
            placements_[k] = wrap.groove;
        }
        if (!std::isfinite(wrap.radius) || wrap.radius < 0) {
            std::ostringstream msg;
            msg << "RopeModel: node " << k << "'s wrap radius R = " << wrap.radius << " m must be finite and >= 0";
            throw std::invalid_argument(msg.str());
        }
        if (wrap.wrapSense != 1 && wrap.wrapSense != -1)
            throw std::invalid_argument("RopeModel: node " + std::to_string(k) + "'s wrapSense = " +
                                        std::to_string(wrap.wrapSense) + " must be +1 or -1");
        nodeOffset_[k] = numNodeCoordinates_;
        if (wrap.turningAxis && !(wrap.radius > 0))
            throw std::invalid_argument("RopeModel: node " + std::to_string(k) +
                                        ": NodeWrap::turningAxis needs a wrapped node (radius > 0)");
        if (wrap.radius > 0) {
            if ((k == 0 || k == N) && !detail::isDrum(laws_[k]))
                throw std::invalid_argument("RopeModel: end node " + std::to_string(k) +
                                            " can be wrapped only as a Driven node (a winch drum): a fastened "
                                            "end's tangent point is its position");
            if constexpr (Dim == 3) {
                if (!wrap.axis.allFinite() || std::abs(wrap.axis.norm() - 1) > 1e-12) {
                    std::ostringstream msg;
                    msg.precision(17);
                    msg << "RopeModel: node " << k << "'s groove axis (" << wrap.axis.transpose()
                        << ") must be a finite unit vector (|n| = " << wrap.axis.norm() << ")";
                    throw std::invalid_argument(msg.str());
                }
                grooveAxes_[k] = wrap.axis;
                if (wrap.turningAxis) {
                    if (!detail::allowsTurningGroove(laws_[k]))
                        throw std::invalid_argument(
                            "RopeModel: node " + std::to_string(k) +
                            ": a turning groove axis (NodeWrap::turningAxis) is built for Sliding and Driven nodes "
                            "(sheaves and drums), not for a slipping traction sheave");
                    axisStation_[k] = N + 1 + numAxisStations_++;
                }
            } else if (wrap.turningAxis) {
                throw std::invalid_argument("RopeModel: node " + std::to_string(k) +
                                            ": NodeWrap::turningAxis needs a spatial rope (RopeModel<3>)");
            }
            arcIndex_[k] = static_cast<int>(elements->arcs.size());
            elements->arcs.emplace_back(spanModels.front().properties(), wrap.radius, wrap.wrapSense,
                                        spanModels.front().gravity());
            arcNode_.push_back(k);
            numNodeCoordinates_ += wrappedBlockSize();
        } else {
            numNodeCoordinates_ += Dim;
        }
    }
    nodeOffset_[N + 1] = numNodeCoordinates_;
    condensedOffset_.assign(N, -1);
    for (int j = 0; j < N; ++j) {
        const SpanModel<Dim>& sp = spanModels[j];
        modalOffset_.push_back(numModal_);
        if (sp.numCondensedModes() > 0) {
            condensedOffset_[j] = numCondensed_;
            numCondensed_ += sp.numCondensedModes();
            numModal_ += sp.numModalCoordinates() - sp.numCondensedModes();
        } else {
            numModal_ += sp.numModalCoordinates();
        }
    }
    if (numCondensed_ > 0)
        for (int j = 0; j < N; ++j) elements->kernels.emplace_back(spanModels[j]);  // throws for PaperLiteral spans
    layOutNodes();
    stationaryColumn_.assign(numExternalCoordinates(), 0);
}

template <int Dim>
void RopeModel<Dim>::layOutNodes() {
    const int N = numSpans();
    slidingIndex_.assign(N + 1, -1);
    drivenIndex_.assign(N + 1, -1);
    slidingNode_.clear();
    numSliding_ = numDriven_ = numFixed_ = 0;
    for (int k = 0; k <= N; ++k) {
        if (detail::hasDependentCoordinate(laws_[k])) {
            slidingIndex_[k] = numSliding_++;
            slidingNode_.push_back(k);
        }
        if (detail::hasExternalCoordinate(laws_[k])) drivenIndex_[k] = numDriven_++;
        if (!detail::hasDependentCoordinate(laws_[k]) && !detail::hasExternalCoordinate(laws_[k])) ++numFixed_;
    }
    numMultipliers_ = numCondensed_ > 0 ? numSliding_ : 0;
    // z = [node blocks 0..N, s_driven | q_free | q_condensed, s_sliding, nu | s_fixed]
    const int nn = numNodeCoordinates_, nx = nn + numDriven_, nw = nx + numModal_, nd = numDependent();
    std::vector<int> materialColumn(N + 1, -1);
    for (int k = 0, f = 0; k <= N; ++k) {
        detail::NodeColumns c;
        if (drivenIndex_[k] >= 0) c.external = nn + drivenIndex_[k];
        if (slidingIndex_[k] >= 0) c.dependent = nw + numCondensed_ + slidingIndex_[k];
        if (drivenIndex_[k] < 0 && slidingIndex_[k] < 0) c.constant = nw + nd + f++;
        materialColumn[k] = detail::placeLaw(laws_[k], c);
    }
    const std::vector<SpanModel<Dim>>& spanModels = elements_->spans;
    spanToRope_.clear();
    for (int j = 0; j < N; ++j) {
        const auto& sp = spanModels[j];
        std::vector<int> map(sp.numCoordinates());
        for (int d = 0; d < Dim; ++d) {
            map[d] = departureOffset(j) + d;
            map[Dim + d] = arrivalOffset(j + 1) + d;
        }
        const int na = sp.numCondensedModes();
        for (int i = 0; i < sp.numModalCoordinates(); ++i) {
            if (isCondensed(j))
                map[2 * Dim + i] = i < na ? nw + condensedOffset_[j] + i : nx + modalOffset_[j] + i - na;
            else
                map[2 * Dim + i] = nx + modalOffset_[j] + i;
        }
        map[sp.s1Index()] = materialColumn[j];
        map[sp.s2Index()] = materialColumn[j + 1];
        spanToRope_.push_back(std::move(map));
    }
    elementToRope_ = spanToRope_;
    elementExtra_.assign(N, -1);
    elementExtraLocal_.assign(N, -1);
    for (int j = 0; j < N; ++j)
        if (isWrapped(j)) {
            elementExtra_[j] = nodeOffset_[j] + wrappedArcLengthOffset();
            elementExtraLocal_[j] = spanModels[j].s1Index();
        }
    for (int k : arcNode_) {
        using Arc = GrooveArc<Dim>;
        std::vector<int> map(Arc::kNumCoordinates);
        for (int d = 0; d < Dim; ++d) {
            map[Arc::centreIndex() + d] = nodeOffset_[k] + wrappedCentreOffset() + d;
            map[Arc::tangentPointIndex() + d] = nodeOffset_[k] + wrappedArrivalOffset() + d;
        }
        if constexpr (Dim == 3)
            for (int d = 0; d < 3; ++d) map[Arc::axisIndex() + d] = nodeOffset_[k] + wrappedAxisOffset() + d;
        map[Arc::materialIndex()] = materialColumn[k];
        map[Arc::lengthIndex()] = nodeOffset_[k] + wrappedArcLengthOffset();
        elementToRope_.push_back(std::move(map));
        elementExtra_.push_back(-1);
        elementExtraLocal_.push_back(-1);
    }
    buildChainOrder();
    static std::atomic<std::uint64_t> nextStructureId{1};
    structureId_ = nextStructureId.fetch_add(1, std::memory_order_relaxed);
}

template <int Dim>
MaterialNode RopeModel<Dim>::nodeKind(int node) const { return detail::kindOf(laws_[node]); }
template <int Dim>
const SpanModel<Dim>& RopeModel<Dim>::span(int j) const { return elements_->spans[j]; }
template <int Dim>
const RopeProperties& RopeModel<Dim>::properties() const { return elements_->spans.front().properties(); }

namespace {
// The capstan law kappa(alpha) = kappa0 e^(c alpha) of a Slipping node, its parameters checked for
// RopeModel::<who>.
void checkSlipRatio(const char* who, double kappa) {
    if (!std::isfinite(kappa) || !(kappa > 0)) {
        std::ostringstream msg;
        msg << "RopeModel::" << who << ": kappa = " << kappa << " must be finite and > 0";
        throw std::invalid_argument(msg.str());
    }
}
void checkAngleExponent(const char* who, double angleExponent) {
    if (!std::isfinite(angleExponent)) {
        std::ostringstream msg;
        msg << "RopeModel::" << who << ": angleExponent = " << angleExponent << " 1/rad must be finite";
        throw std::invalid_argument(msg.str());
    }
}
}  // namespace

template <int Dim>
RopeModel<Dim> RopeModel<Dim>::withNodeLaw(int node, MaterialNode kind, double kappa0, double angleExponent) const {
    if (node < 1 || node >= numSpans())
        throw std::invalid_argument("RopeModel::withNodeLaw: node " + std::to_string(node) + " is not an interior node");
    detail::NodeLaw law = detail::makeNodeLaw(kind, node, numSpans(), length_);
    // The external coordinates stay: both laws have one at the node (Driven, Slipping).
    if (!detail::hasExternalCoordinate(laws_[node]) || !detail::hasExternalCoordinate(law))
        throw std::invalid_argument(std::string("RopeModel::withNodeLaw: node ") + std::to_string(node) + " is " +
                                    detail::nameOf(laws_[node]) + ", asked to be " + detail::nameOf(law) +
                                    ": a law changes only between Driven and Slipping (both keep the node's "
                                    "external coordinate)");
    if (detail::SlippingLaw* slip = std::get_if<detail::SlippingLaw>(&law.law)) {
        checkAngleExponent("withNodeLaw", angleExponent);
        checkSlipRatio("withNodeLaw", kappa0);
        slip->capstan = detail::CapstanLaw(kappa0, angleExponent);
    } else if (kappa0 != 1.0 || angleExponent != 0.0) {
        std::ostringstream msg;
        msg << "RopeModel::withNodeLaw: a " << detail::nameOf(law) << " node has no capstan law (kappa0 = " << kappa0
            << ", angleExponent = " << angleExponent << " 1/rad given; 1 and 0 expected)";
        throw std::invalid_argument(msg.str());
    }
    if (axisStation_[node] >= 0 && !detail::allowsTurningGroove(law))
        throw std::invalid_argument("RopeModel::withNodeLaw: node " + std::to_string(node) +
                                    ": a turning groove axis (NodeWrap::turningAxis) is built for Sliding and Driven "
                                    "nodes (sheaves and drums), not for a slipping traction sheave");
    RopeModel<Dim> out(*this);  // shares the elements; the node tables are copied, then laid out anew
    out.laws_[node] = law;
    out.layOutNodes();
    return out;
}

template <int Dim>
void RopeModel<Dim>::buildChainOrder() {
    const int N = numSpans(), nx = numExternalCoordinates(), nw = nx + numModal_, nd = numDependent();
    const int nqc = numCondensed_, nc = numSliding_;
    const int nz = nw + nd + numFixed_;
    // Keys along the rope: span j -> 2 j + 1 (its free modes, condensed amplitudes and their
    // stationarity rows), node k -> 2 k (its material coordinate, multiplier and rows).
    std::vector<int> zKey(nz, -1), rowKey(nd, -1), rowSpan(nd, -1), rowNode(nd, -1);
    for (int j = 0; j < N; ++j) {
        const int na = elements_->spans[j].numCondensedModes();
        for (int i = 0; i < elements_->spans[j].numModalCoordinates() - na; ++i) zKey[nx + modalOffset_[j] + i] = 2 * j + 1;
        for (int i = 0; i < na; ++i) {
            zKey[nw + condensedOffset_[j] + i] = 2 * j + 1;
            rowKey[condensedOffset_[j] + i] = 2 * j + 1;
            rowSpan[condensedOffset_[j] + i] = j;
        }
    }
    for (int ki = 0; ki < nc; ++ki) {
        const int k = slidingNode_[ki];
        zKey[nw + nqc + ki] = 2 * k;
        rowKey[nqc + ki] = 2 * k;
        rowNode[nqc + ki] = k;
        if (numMultipliers_ > 0) {
            zKey[nw + nqc + nc + ki] = 2 * k;
            rowKey[nqc + nc + ki] = 2 * k;
            rowNode[nqc + nc + ki] = k;
        }
    }
    // Positions: stable order by key (unknowns before rows within a key).
    struct Item {
        int key, kind, index;
    };
    std::vector<Item> items;
    for (int z = nx; z < nw + nd; ++z) items.push_back({zKey[z], 0, z});
    for (int r = 0; r < nd; ++r) items.push_back({rowKey[r], 1, r});
    auto order = [](const Item& a, const Item& b) {
        return a.key != b.key ? a.key < b.key : (a.kind != b.kind ? a.kind < b.kind : a.index < b.index);
    };
    std::sort(items.begin(), items.end(), order);
    kktPos_.assign(nz, -1);
    kktRowPos_.assign(nd, -1);
    for (int p = 0; p < static_cast<int>(items.size()); ++p)
        (items[p].kind == 0 ? kktPos_[items[p].index] : kktRowPos_[items[p].index]) = p;
    kktSize_ = static_cast<int>(items.size());
    std::vector<Item> cols, rows;
    for (int d = 0; d < nd; ++d) cols.push_back({zKey[nw + d], 0, d});
    for (int r = 0; r < nd; ++r) rows.push_back({rowKey[r], 1, r});
    std::sort(cols.begin(), cols.end(), order);
    std::sort(rows.begin(), rows.end(), order);
    dependentColPos_.assign(nd, -1);
    dependentRowPos_.assign(nd, -1);
    for (int p = 0; p < nd; ++p) {
        dependentColPos_[cols[p].index] = p;
        dependentRowPos_[rows[p].index] = p;
    }
    // Bandwidths from the structure: row r reads the coordinates of its spans (tension equality and
    // stationarity in s_k: spans k - 1 and k; stationarity in a_j: span j) and the multipliers of
    // its neighbouring sheaves (stationarity in a_j: nodes j, j + 1; in s_k: nodes k - 1..k + 1).
    dependentKl_ = dependentKu_ = kktBand_ = 0;
    auto touch = [&](int r, int z) {
        if (z < nx || z >= nw + nd) return;
        kktBand_ = std::max(kktBand_, std::abs(kktRowPos_[r] - kktPos_[z]));
        if (z >= nw) {
            dependentKl_ = std::max(dependentKl_, dependentRowPos_[r] - dependentColPos_[z - nw]);
            dependentKu_ = std::max(dependentKu_, dependentColPos_[z - nw] - dependentRowPos_[r]);
        }
    };
    for (int r = 0; r < nd; ++r) {
        int firstSpan, lastSpan, firstNode = 0, lastNode = -1;
        if (rowSpan[r] >= 0) {
            firstSpan = lastSpan = rowSpan[r];
            firstNode = rowSpan[r];
            lastNode = rowSpan[r] + 1;
        } else {
            const int k = rowNode[r];
            firstSpan = k - 1;
            lastSpan = k;
            if (r >= nqc + nc) {
                firstNode = k - 1;
                lastNode = k + 1;
            }
        }
        for (int j = firstSpan; j <= lastSpan; ++j)
            for (int z : spanToRope_[j]) touch(r, z);
        for (int m = std::max(firstNode, 1); m <= std::min(lastNode, N - 1); ++m)
            if (numMultipliers_ > 0 && slidingIndex_[m] >= 0) touch(r, nw + nqc + nc + slidingIndex_[m]);
    }
    // The elements (spans, then groove arcs) and the z targets of their local coordinates: the map
    // entry, and for a span's s1 after a wrapped node also l_k (s1 = s_k + l_k).
    const int ne = static_cast<int>(elementToRope_.size());
    auto targets = [&](int e, int a, int* t) {
        t[0] = elementToRope_[e][a];
        if (a == elementExtraLocal_[e]) {
            t[1] = elementExtra_[e];
            return 2;
        }
        return 1;
    };
    for (int e = 0; e < ne; ++e)
        for (int a : elementToRope_[e])
            for (int b : elementToRope_[e])
                if (kktPos_[a] >= 0 && kktPos_[b] >= 0) kktBand_ = std::max(kktBand_, std::abs(kktPos_[a] - kktPos_[b]));
    jacobianSpanCoordinates_.assign(N, {});
    for (int j = 0; j < N; ++j) {
        const auto& map = spanToRope_[j];
        for (int i = 0; i < static_cast<int>(map.size()); ++i)
            if (map[i] < nw + nd) jacobianSpanCoordinates_[j].push_back(i);
    }
    // (The extra targets are external coordinates: they have no place in the KKT band.)
    kktMassTargets_.assign(ne, {});
    for (int e = 0; e < ne; ++e) {
        const auto& map = elementToRope_[e];
        const int n = static_cast<int>(map.size());
        for (int b = 0; b < n; ++b) {  // the order computeDynamics adds them in
            if (kktPos_[map[b]] < 0) continue;
            for (int a = 0; a < n; ++a)
                if (kktPos_[map[a]] >= 0)
                    kktMassTargets_[e].push_back(
                        {a + n * b, BandedLU::offset(kktSize_, kktBand_, kktBand_, kktPos_[map[a]], kktPos_[map[b]])});
        }
    }
    // multiplyByNodeMass's terms, element by element, in the order its loops took them (so every
    // row sums its terms in the same order); a term's source indexes its element's mass matrix, and
    // massTermSpanStart_ marks where each element's terms begin in the three lists.
    massTimesExternalIntoKkt_.clear();
    massTimesExternalIntoExternal_.clear();
    massTimesKktIntoExternal_.clear();
    massTermSpanStart_.assign(3 * (ne + 1), 0);
    int ta[2], tb[2];
    for (int e = 0; e < ne; ++e) {
        const int n = static_cast<int>(elementToRope_[e].size());
        massTermSpanStart_[3 * e] = static_cast<int>(massTimesExternalIntoKkt_.size());
        massTermSpanStart_[3 * e + 1] = static_cast<int>(massTimesExternalIntoExternal_.size());
        massTermSpanStart_[3 * e + 2] = static_cast<int>(massTimesKktIntoExternal_.size());
        for (int a = 0; a < n; ++a)
            for (int ia = 0, na = targets(e, a, ta); ia < na; ++ia) {
                if (ta[ia] >= nx) continue;
                for (int b = 0; b < n; ++b)
                    for (int ib = 0, nb = targets(e, b, tb); ib < nb; ++ib) {
                        const int pb = kktPos_[tb[ib]];
                        if (pb >= 0)
                            massTimesExternalIntoKkt_.push_back({b + n * a, pb, ta[ia]});
                        else if (tb[ib] < nx)
                            massTimesExternalIntoExternal_.push_back({b + n * a, tb[ib], ta[ia]});
                    }
            }
        for (int a = 0; a < n; ++a)
            for (int ia = 0, na = targets(e, a, ta); ia < na; ++ia) {
                if (ta[ia] >= nx) continue;
                for (int b = 0; b < n; ++b) {
                    const int pb = kktPos_[elementToRope_[e][b]];
                    if (pb >= 0) massTimesKktIntoExternal_.push_back({a + n * b, ta[ia], pb});
                }
            }
    }
    massTermSpanStart_[3 * ne] = static_cast<int>(massTimesExternalIntoKkt_.size());
    massTermSpanStart_[3 * ne + 1] = static_cast<int>(massTimesExternalIntoExternal_.size());
    massTermSpanStart_[3 * ne + 2] = static_cast<int>(massTimesKktIntoExternal_.size());
    externalSpans_.assign(nx, {-1, -1, -1, -1, -1, -1});
    for (int e = 0; e < ne; ++e)
        for (int a = 0; a < static_cast<int>(elementToRope_[e].size()); ++a)
            for (int ia = 0, na = targets(e, a, ta); ia < na; ++ia) {
                const int z = ta[ia];
                if (z >= nx) continue;
                auto& slots = externalSpans_[z];
                int slot = 0;
                while (slot < 6 && slots[slot] >= 0) slot += 2;
                if (slot == 6) throw std::logic_error("RopeModel: an external coordinate in more than three elements");
                slots[slot] = e;
                slots[slot + 1] = a;
            }
}

template <int Dim>
const GrooveArc<Dim>& RopeModel<Dim>::arc(int node) const {
    if (node < 0 || node > numSpans() || arcIndex_[node] < 0)
        throw std::invalid_argument("RopeModel::arc: node " + std::to_string(node) + " is not a wrapped node");
    return elements_->arcs[arcIndex_[node]];
}

template <int Dim>
const double* RopeModel<Dim>::elementMass(const RopeData<Dim>& data, int e, int& n) const {
    const int N = numSpans();
    if (e < N) {
        n = elements_->spans[e].numCoordinates();
        return data.ws().spans[e].massMatrix.data();
    }
    n = GrooveArc<Dim>::kNumCoordinates;
    return data.ws().arcs[e - N].massMatrix.data();
}

template <int Dim>
template <class Coordinates>
void RopeModel<Dim>::arcCoordinates(int node, const Eigen::VectorXd& x, double s, Coordinates& a) const {
    using Arc = GrooveArc<Dim>;
    const int o = nodeOffset_[node];
    a.template segment<Dim>(Arc::centreIndex()) = x.template segment<Dim>(o + wrappedCentreOffset());
    a.template segment<Dim>(Arc::tangentPointIndex()) = x.template segment<Dim>(o + wrappedArrivalOffset());
    if constexpr (Dim == 3) a.template segment<3>(Arc::axisIndex()) = x.template segment<3>(o + wrappedAxisOffset());
    a[Arc::materialIndex()] = s;
    a[Arc::lengthIndex()] = x[o + wrappedArcLengthOffset()];
}

template <int Dim>
const Eigen::VectorXd& RopeModel<Dim>::packExternal(const NodeMatrix& nodes, const Eigen::VectorXd& drivenS,
                                                    RopeData<Dim>& data, bool rates) const {
    if (nodes.cols() != numStations()) {
        std::ostringstream msg;
        msg << "RopeModel: " << nodes.cols() << " node " << (rates ? "velocities" : "positions") << " given for "
            << numNodes() << " nodes";
        if (numAxisStations_ > 0) msg << " and " << numAxisStations_ << " axis stations";
        throw std::invalid_argument(msg.str());
    }
    if (drivenS.size() != numDriven_) {
        std::ostringstream msg;
        msg << "RopeModel: " << drivenS.size() << " driven material " << (rates ? "rates" : "coordinates")
            << " given for " << numDriven_ << " Driven nodes"
            << (drivenS.size() == 0 ? " (use the overload taking drivenS)" : "");
        throw std::invalid_argument(msg.str());
    }
    Eigen::VectorXd& x = rates ? data.ws().packedXdot : data.ws().packedX;
    x.resize(Dim * numStations() + numDriven_);
    for (int k = 0; k < numStations(); ++k) x.template segment<Dim>(Dim * k) = nodes.col(k);
    x.tail(numDriven_) = drivenS;
    return x;
}

template <int Dim>
const Eigen::VectorXd& RopeModel<Dim>::stationsToExternal(const NodeMatrix& nodes, const NodeMatrix* nodeVelocities,
                                                          const Eigen::VectorXd& drivenS, const Eigen::VectorXd* drivenSdot,
                                                          RopeData<Dim>& data) const {
    detail::RopeWorkspace<Dim>& ws = data.ws();
    const Eigen::VectorXd& Y = packExternal(nodes, drivenS, data, false);
    if (elements_->arcs.empty()) {
        if (nodeVelocities) packExternal(*nodeVelocities, *drivenSdot, data, true);
        return Y;
    }
    // Positions alone (a solve) go to a map of their own: the dynamics' J and b stay valid.
    WrapStationMapData& m = nodeVelocities ? ws.stationMap : ws.stationPositionMap;
    if (m.wrapAngles.size() == 0) {
        const WrapStationMapData& other = nodeVelocities ? ws.stationPositionMap : ws.stationMap;
        m.wrapAngles = other.wrapAngles;
        m.arrivalAngles = other.arrivalAngles;
    }
    if (!gripNodes_.empty()) m.gripCreep = data.gripCreep;  // a walking groove follows the groove, not the rope
    if (nodeVelocities)
        WrapStationMap<Dim>(*this).evaluate(Y, packExternal(*nodeVelocities, *drivenSdot, data, true), m);
    else
        WrapStationMap<Dim>(*this).evaluatePositions(Y, m);
    return m.x;
}

template <int Dim>
void RopeModel<Dim>::dynamicsToStations(RopeData<Dim>& data) const {
    detail::RopeWorkspace<Dim>& ws = data.ws();
    const Eigen::VectorXd& b = ws.stationMap.bias;
    const int nx = numExternalCoordinates();
    // The station-level S_Y, h_Y and modal coupling go into buffers of their own, swapped with
    // data's x-level ones (swapped back by the next evaluation, externalBuffersBack): each
    // buffer keeps its shape, so nothing is allocated once the first evaluation has sized them.
    if (ws.nodeMassFormed) {
        ws.stationMassBias.noalias() = data.nodeMass * b;
        data.nodeForce -= ws.stationMassBias.col(0);
        ws.modalFree.noalias() -= ws.modalCoupling * b;
        multiplyStationJacobianFromLeft(ws.modalCoupling, ws.stationMap, ws.stationModalCoupling);
        ws.modalCoupling.swap(ws.stationModalCoupling);
        multiplyStationJacobianFromLeft(data.nodeMass, ws.stationMap, ws.stationScratch);
        multiplyByStationJacobianTransposed(ws.stationMap, ws.stationScratch, ws.stationNodeMass);
        data.nodeMass.swap(ws.stationNodeMass);
    } else {
        multiplyByExternalMass(data, b, ws.stationMassBias);
        data.nodeForce -= ws.stationMassBias.col(0);
        for (int m = 0; m < numModal_; ++m) ws.modalFree[m] += ws.productBlock[kktPos_[nx + m]];
        ws.productColumns = -1;
    }
    multiplyByStationJacobianTransposed(ws.stationMap, data.nodeForce, ws.stationForce);
    data.nodeForce.swap(ws.stationForce);
    multiplyByStationJacobianTransposed(ws.stationMap, ws.stationMassBias.col(0), data.nodeMassBias);
    ws.stationMode = true;
    ws.stationBuffersSwapped = true;
    ws.stationMassSwapped = ws.nodeMassFormed;
}

template <int Dim>
void RopeModel<Dim>::externalBuffersBack(RopeData<Dim>& data) const {
    detail::RopeWorkspace<Dim>& ws = data.ws();
    if (!ws.stationBuffersSwapped) return;
    data.nodeForce.swap(ws.stationForce);
    if (ws.stationMassSwapped) {
        data.nodeMass.swap(ws.stationNodeMass);
        ws.modalCoupling.swap(ws.stationModalCoupling);
    }
    ws.stationBuffersSwapped = ws.stationMassSwapped = false;
}

template <int Dim>
void RopeModel<Dim>::factorDependentJacobian(RopeData<Dim>& data, BandedLU& lu) const {
    const int nw = numExternalCoordinates() + numModal_, nd = numDependent();
    lu.reset(nd, dependentKl_, dependentKu_);
    const detail::RopeWorkspace<Dim>& w = data.ws();
    if (w.dependentOffset.size() == w.jacobian.size()) {  // offsets recorded with the structure
        for (std::size_t t = 0; t < w.jacobian.size(); ++t)
            if (w.dependentOffset[t] >= 0) lu.addAt(w.dependentOffset[t], w.jacobian[t].value);
    } else {
        for (const detail::JacobianEntry& e : w.jacobian)
            if (e.col >= nw) lu.add(dependentRowPos_[e.row], dependentColPos_[e.col - nw], e.value);
    }
    if (!lu.factor())
        throw std::runtime_error(
            "RopeModel: the Jacobian of the sheave and quasi-static constraints on the dependent coordinates is "
            "singular at this configuration (a rope that carries no axial stiffness anywhere?)");
}

template <int Dim>
void RopeModel<Dim>::solveDependent(RopeData<Dim>& data, const BandedLU& lu, const Eigen::VectorXd& rows,
                                    Eigen::VectorXd& out) const {
    const int nd = numDependent();
    Eigen::VectorXd& t = data.ws().dependentScratch;
    t.resize(nd);
    for (int r = 0; r < nd; ++r) t[dependentRowPos_[r]] = rows[r];
    lu.solve(t.data());
    out.resize(nd);
    for (int d = 0; d < nd; ++d) out[d] = t[dependentColPos_[d]];
}

template <int Dim>
void RopeModel<Dim>::setStoredRope(int node, double lengthAtZero) {
    const int N = numSpans();
    if ((node != 0 && node != N) || !detail::isDrum(laws_[node]))
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
void RopeModel<Dim>::setGrip(int node) {
    const int N = numSpans();
    if ((node != 0 && node != N) || !detail::isDrum(laws_[node]) || !isWrapped(node))
        throw std::invalid_argument("RopeModel::setGrip: node " + std::to_string(node) +
                                    " is not a wrapped Driven end node (a drum whose rope leaves at its tangent point)");
    if (!grips(node)) gripNodes_.push_back(node);
}

template <int Dim>
bool RopeModel<Dim>::grips(int node) const {
    return std::find(gripNodes_.begin(), gripNodes_.end(), node) != gripNodes_.end();
}

namespace {
// The creep c_k of Driven index d (RopeData::gripCreep; 0 if not given).
template <int Dim>
double gripCreepAt(const RopeData<Dim>& data, int d) {
    return data.gripCreep.size() > d ? data.gripCreep[d] : 0.0;
}
// The span at gripping end node k and which of its ends is there.
inline std::pair<int, SpanEnd> gripSpan(int node, int numSpans) {
    return node == 0 ? std::pair<int, SpanEnd>{0, SpanEnd::First} : std::pair<int, SpanEnd>{numSpans - 1, SpanEnd::Second};
}
}  // namespace

// The grip's velocity constraint (setGrip) on the station map of this evaluation: the node's row
// of J and of xdot scaled by 1 / lambda (lambda from the positions, solved here if they are not),
// the surface speed Ydot_s + sigma R phidot kept for the bias and the creep rate.
template <int Dim>
void RopeModel<Dim>::applyGripRates(const Eigen::VectorXd& x, const Eigen::VectorXd& qm, RopeData<Dim>& data) const {
    detail::RopeWorkspace<Dim>& ws = data.ws();
    if (!positionsMatch(x, qm, data)) solveDependentCoordinatesFromExternal(x, qm, data);
    WrapStationMapData& m = ws.stationMap;
    data.gripCreepRates.setZero(numDriven_);
    ws.gripSurfaceSpeeds.resize(static_cast<Eigen::Index>(gripNodes_.size()));
    ws.gripInverseStretch.resize(static_cast<Eigen::Index>(gripNodes_.size()));
    for (std::size_t g = 0; g < gripNodes_.size(); ++g) {
        const int k = gripNodes_[g], d = drivenIndex_[k], row = numNodeCoordinates_ + d;
        const auto [j, end] = gripSpan(k, numSpans());
        const SpanModel<Dim>& span = elements_->spans[j];
        const Eigen::VectorXd& q = ws.spanQ[j];
        const double eps = span.strain(q, q[end == SpanEnd::First ? span.s1Index() : span.s2Index()]);
        const double stretch2 = 1.0 + 2.0 * eps;
        if (!(stretch2 > 0))
            throw std::domain_error("RopeModel: the span at gripping node " + std::to_string(k) +
                                    " is compressed to zero length at its end (stretch^2 = " + std::to_string(stretch2) + ")");
        const double inv = 1.0 / std::sqrt(stretch2);  // mutation-site: grip-stretch
        const double v = m.xdot[row];
        ws.gripSurfaceSpeeds[static_cast<Eigen::Index>(g)] = v;
        ws.gripInverseStretch[static_cast<Eigen::Index>(g)] = inv;
        m.jacobian.row(row) *= inv;
        m.xdot[row] = v * inv;
        m.bias[row] *= inv;
        data.gripCreepRates[d] = v * (inv - 1.0);
    }
}

template <int Dim>
void RopeModel<Dim>::setSlipRatio(int node, double kappa) {
    detail::SlippingLaw* law = node < 0 || node > numSpans() ? nullptr : std::get_if<detail::SlippingLaw>(&laws_[node].law);
    if (!law)
        throw std::invalid_argument("RopeModel::setSlipRatio: node " + std::to_string(node) + " is not a Slipping node");
    checkSlipRatio("setSlipRatio", kappa);
    law->capstan = detail::CapstanLaw(kappa, 0.0);
}

template <int Dim>
void RopeModel<Dim>::setSlipLaw(int node, double kappa0, double angleExponent) {
    checkAngleExponent("setSlipLaw", angleExponent);
    setSlipRatio(node, kappa0);
    std::get<detail::SlippingLaw>(laws_[node].law).capstan = detail::CapstanLaw(kappa0, angleExponent);
}

template <int Dim>
double RopeModel<Dim>::slipRatio(int node) const {
    const detail::SlippingLaw* law = std::get_if<detail::SlippingLaw>(&laws_[node].law);
    return law ? law->capstan.ratio() : 1.0;
}

template <int Dim>
double RopeModel<Dim>::slipAngleExponent(int node) const {
    const detail::SlippingLaw* law = std::get_if<detail::SlippingLaw>(&laws_[node].law);
    return law ? law->capstan.angleExponent() : 0.0;
}

template <int Dim>
detail::SlipAngle<Dim> RopeModel<Dim>::slipAngle(int k, const Eigen::VectorXd& x, const Eigen::VectorXd* xdot) const {
    detail::SlipAngle<Dim> a;
    if (isWrapped(k)) {  // alpha = l / R
        const int lc = nodeOffset_[k] + wrappedArcLengthOffset();
        const double invR = 1.0 / arc(k).radius();
        a.alpha = x[lc] * invR;
        a.count = 1;
        a.cols[0] = lc;
        a.grad[0] = invR;
        if (xdot) a.rate = (*xdot)[lc] * invR;
        return a;
    }
    if constexpr (Dim == 2) {
        // phi = theta(d_out) - theta(d_in), theta(d) = atan2(d_y, d_x): dtheta/dd = perp(d) / |d|^2
        // with perp(d) = (-d_y, d_x), and with ddot = 0 thetaddot = -2 (d . ddot)(d x ddot) / |d|^4.
        // alpha = |phi| (sign sigma).
        const int oa = departureOffset(k - 1), ok = nodeOffset_[k], ob = arrivalOffset(k + 1);
        const Eigen::Vector2d din = x.template segment<2>(ok) - x.template segment<2>(oa);
        const Eigen::Vector2d dout = x.template segment<2>(ob) - x.template segment<2>(ok);
        auto cross = [](const Eigen::Vector2d& u, const Eigen::Vector2d& v) { return u[0] * v[1] - u[1] * v[0]; };
        const double phi = std::atan2(cross(din, dout), din.dot(dout));
        const double sigma = phi < 0 ? -1.0 : 1.0;
        a.alpha = sigma * phi;
        const double nin = din.squaredNorm(), nout = dout.squaredNorm();
        const Eigen::Vector2d gin = sigma * Eigen::Vector2d(-din[1], din[0]) / nin;     // dalpha/dd_in (negated)
        const Eigen::Vector2d gout = sigma * Eigen::Vector2d(-dout[1], dout[0]) / nout;  // dalpha/dd_out
        // d_in = r_k - p_a, d_out = p_b - r_k: dalpha/dp_a = gin, dalpha/dr_k = -gin - gout, dalpha/dp_b = gout.
        a.count = 6;
        for (int d = 0; d < 2; ++d) {
            a.cols[d] = oa + d;
            a.grad[d] = gin[d];
            a.cols[2 + d] = ok + d;
            a.grad[2 + d] = -gin[d] - gout[d];
            a.cols[4 + d] = ob + d;
            a.grad[4 + d] = gout[d];
        }
        if (xdot) {
            const Eigen::Vector2d vin = xdot->template segment<2>(ok) - xdot->template segment<2>(oa);
            const Eigen::Vector2d vout = xdot->template segment<2>(ob) - xdot->template segment<2>(ok);
            a.rate = gout.dot(vout) - gin.dot(vin);
            a.bias = sigma * (-2.0 * dout.dot(vout) * cross(dout, vout) / (nout * nout) +
                              2.0 * din.dot(vin) * cross(din, vin) / (nin * nin));
        }
        return a;
    } else {
        // alpha = atan2(|w|, c) with w = d_in x d_out, c = d_in . d_out: the angle between the
        // chords in their own plane, whose normal is w_hat = w / |w|. Its rate
        //     alphadot = (c sdot - s cdot) / (s^2 + c^2),   s = |w|, sdot = w_hat . wdot,
        // is linear in (ddot_in, ddot_out) with
        //     dalpha/dd_in = (c (d_out x w_hat) - s d_out) / (s^2 + c^2),
        //     dalpha/dd_out = (c (w_hat x d_in) - s d_in) / (s^2 + c^2),
        // and with dddot = 0 (cddot = 2 ddot_in . ddot_out, wddot = 2 ddot_in x ddot_out)
        //     alphaddot = (c sddot - s cddot) / (s^2 + c^2) - 2 (c sdot - s cdot)(s sdot + c cdot) / (s^2 + c^2)^2,
        //     sddot = (|wdot|^2 - sdot^2) / s + w_hat . wddot.
        // In a plane this is the planar branch's |phi|. Where the chords are parallel (s = 0: a
        // straight rope, or one doubling back, alpha = pi) the plane is undefined and alpha has a
        // kink: w_hat is then grooveAxis(k) (+z at a point node: the derivatives in the plane normal to it), and
        // the terms in 1 / s are dropped.
        const int oa = departureOffset(k - 1), ok = nodeOffset_[k], ob = arrivalOffset(k + 1);
        const Eigen::Vector3d din = x.template segment<3>(ok) - x.template segment<3>(oa);
        const Eigen::Vector3d dout = x.template segment<3>(ob) - x.template segment<3>(ok);
        const Eigen::Vector3d w = din.cross(dout);
        const double s = w.norm(), c = din.dot(dout), q = s * s + c * c;
        const bool plane = s > 1e-14 * std::sqrt(q);
        const Eigen::Vector3d n = plane ? Eigen::Vector3d(w / s) : grooveAxes_[k];
        a.alpha = std::atan2(s, c);
        const Eigen::Vector3d gin = (c * dout.cross(n) - s * dout) / q;   // dalpha/dd_in
        const Eigen::Vector3d gout = (c * n.cross(din) - s * din) / q;    // dalpha/dd_out
        // d_in = r_k - p_a, d_out = p_b - r_k: dalpha/dp_a = -gin, dalpha/dr_k = gin - gout, dalpha/dp_b = gout.
        a.count = 9;
        for (int d = 0; d < 3; ++d) {
            a.cols[d] = oa + d;
            a.grad[d] = -gin[d];
            a.cols[3 + d] = ok + d;
            a.grad[3 + d] = gin[d] - gout[d];
            a.cols[6 + d] = ob + d;
            a.grad[6 + d] = gout[d];
        }
        if (xdot) {
            const Eigen::Vector3d vin = xdot->template segment<3>(ok) - xdot->template segment<3>(oa);
            const Eigen::Vector3d vout = xdot->template segment<3>(ob) - xdot->template segment<3>(ok);
            const Eigen::Vector3d wdot = vin.cross(dout) + din.cross(vout);
            const double sdot = n.dot(wdot), cdot = vin.dot(dout) + din.dot(vout);
            const double cddot = 2.0 * vin.dot(vout);
            const double sddot =
                (plane ? (wdot.squaredNorm() - sdot * sdot) / s : 0.0) + 2.0 * n.dot(vin.cross(vout));
            a.rate = gin.dot(vin) + gout.dot(vout);
            a.bias = (c * sddot - s * cddot) / q - 2.0 * (c * sdot - s * cdot) * (s * sdot + c * cdot) / (q * q);
        }
        return a;
    }
}

template <int Dim>
double RopeModel<Dim>::wrapAngle(const RopeData<Dim>& data, int node) const {
    if (node < 1 || node >= numSpans())
        throw std::invalid_argument("RopeModel::wrapAngle: node " + std::to_string(node) + " is not an interior node");
    const Eigen::VectorXd& x = elements_->arcs.empty() ? data.ws().packedX : data.ws().stationPositionMap.x;
    if (x.size() != numExternalCoordinates())
        throw std::invalid_argument("RopeModel::wrapAngle: data holds no evaluation from node positions");
    return slipAngle(node, x, nullptr).alpha;
}

template <int Dim>
std::pair<double, double> RopeModel<Dim>::fleetAngles(const RopeData<Dim>& data, int span) const {
    if (span < 0 || span >= numSpans())
        throw std::invalid_argument("RopeModel::fleetAngles: span " + std::to_string(span) + " is outside 0.." +
                                    std::to_string(numSpans() - 1));
    if (elements_->arcs.empty()) {
        if (data.ws().packedX.size() != numExternalCoordinates())
            throw std::invalid_argument("RopeModel::fleetAngles: data holds no evaluation from node positions");
        return {0.0, 0.0};
    }
    const WrapStationMapData& m = data.ws().stationPositionMap;
    if (m.startFleetAngles.size() != numSpans())
        throw std::invalid_argument("RopeModel::fleetAngles: data holds no evaluation from node positions");
    return {m.startFleetAngles[span], m.endFleetAngles[span]};
}

template <int Dim>
double RopeModel<Dim>::surfaceCoordinate(const RopeData<Dim>& data, int node) const {
    if (node < 0 || node > numSpans() || drivenIndex_[node] < 0)
        throw std::invalid_argument("RopeModel::surfaceCoordinate: node " + std::to_string(node) +
                                    " is neither Driven nor Slipping");
    const Eigen::VectorXd& x = elements_->arcs.empty() ? data.ws().packedX : data.ws().stationPositionMap.x;
    if (x.size() != numExternalCoordinates())
        throw std::invalid_argument("RopeModel::surfaceCoordinate: data holds no evaluation from node positions");
    return x[numNodeCoordinates_ + drivenIndex_[node]];
}

template <int Dim>
double RopeModel<Dim>::surfaceRate(const RopeData<Dim>& data, int node) const {
    if (node < 0 || node > numSpans() || drivenIndex_[node] < 0)
        throw std::invalid_argument("RopeModel::surfaceRate: node " + std::to_string(node) +
                                    " is neither Driven nor Slipping");
    const Eigen::VectorXd& w = data.ws().w;  // [xdot; qdot_m] of the last computeDynamics
    if (w.size() != numExternalCoordinates() + numModal_)
        throw std::invalid_argument("RopeModel::surfaceRate: data holds no computeDynamics");
    return w[numNodeCoordinates_ + drivenIndex_[node]];
}

template <int Dim>
void RopeModel<Dim>::setStationaryNodes(const std::vector<bool>& stationary) {
    if (static_cast<int>(stationary.size()) != numNodes())
        throw std::invalid_argument("RopeModel::setStationaryNodes: " + std::to_string(stationary.size()) +
                                    " flags given for " + std::to_string(numNodes()) + " nodes");
    stationaryColumn_.assign(numExternalCoordinates(), 0);
    for (int k = 0; k < numNodes(); ++k) {
        if (!isWrapped(k)) {
            for (int d = 0; d < Dim; ++d) stationaryColumn_[nodeOffset_[k] + d] = stationary[k] ? 1 : 0;
            continue;
        }
        // A wrapped node's tangent points and arc length move with its neighbours too: only what
        // depends on stationary nodes alone is. A wrapped end (a drum) has one tangent point, T_in =
        // T_out, and no arc (l = 0).
        const int N = numSpans();
        const bool before = k > 0 ? stationary[k - 1] : stationary[k + 1];
        const bool after = k < N ? stationary[k + 1] : stationary[k - 1];
        const bool in = stationary[k] && before, out = stationary[k] && after;
        const int o = nodeOffset_[k];
        for (int i = 0; i < wrappedBlockSize(); ++i) {
            bool fixed = stationary[k];  // the centre and the axis
            if (i >= wrappedArrivalOffset() && i < wrappedArrivalOffset() + Dim) fixed = in;
            if (i >= wrappedDepartureOffset() && i < wrappedDepartureOffset() + Dim) fixed = out;
            if (i == wrappedArcLengthOffset()) fixed = in && out;
            stationaryColumn_[o + i] = fixed ? 1 : 0;
        }
    }
}

namespace {
// The law of the rope stored at Driven end node k (setStoredRope; StoredRope.h): a point drum, or
// a wrapped one whose rope leaves at its tangent point (the start of span 0, the end of span N - 1).
template <int Dim>
detail::StoredRope<Dim> storedRopeLaw(const RopeModel<Dim>& model, int k, double lengthAtZero, double slope) {
    detail::StoredRope<Dim> law(k, lengthAtZero, slope, model.properties().massPerLength, model.span(0).gravity());
    const int o = model.nodeCoordinateOffset(k);
    if (model.isWrapped(k)) {
        const int tangent = o + (k == 0 ? RopeModel<Dim>::wrappedDepartureOffset() : RopeModel<Dim>::wrappedArrivalOffset());
        law.setWrapped(model.arc(k).radius(), model.arc(k).wrapSense(), o + RopeModel<Dim>::wrappedCentreOffset(), tangent,
                       o + (Dim == 3 ? RopeModel<Dim>::wrappedAxisOffset() : 0));
        if (model.axisStation(k) >= 0) law.setTurningAxis();
    } else {
        law.setPointOffset(o);
    }
    law.setMaterialOffset(model.numNodeCoordinates() + model.drivenIndex(k));
    return law;
}
}  // namespace

// The grip's terms after the x-level dynamics (setGrip): the bias d(1/lambda)/dt v = -lambda^-3
// epsdot v of the node's row, with epsdot the span's end-strain rate at the complete velocities of
// this evaluation; and, unless the evaluation was a repeat (its results already carried to the
// stations), the wound rope's strain energy and the stored ring at the groove's own rate.
template <int Dim>
void RopeModel<Dim>::applyGripTerms(const Eigen::VectorXd& x, const Eigen::VectorXd& xdot, bool repeated,
                                    RopeData<Dim>& data) const {
    detail::RopeWorkspace<Dim>& ws = data.ws();
    if (!repeated) data.gripHeldEnergyRates.setZero(numDriven_);
    for (std::size_t g = 0; g < gripNodes_.size(); ++g) {
        const int k = gripNodes_[g], d = drivenIndex_[k], row = numNodeCoordinates_ + d;
        const auto [j, end] = gripSpan(k, numSpans());
        const SpanModel<Dim>& span = elements_->spans[j];
        EndStrain<Dim> e;
        span.endStrain(ws.spanQ[j], ws.spanQdot[j], end, e);
        const double inv = ws.gripInverseStretch[static_cast<Eigen::Index>(g)];
        const double v = ws.gripSurfaceSpeeds[static_cast<Eigen::Index>(g)];
        ws.stationMap.bias[row] -= inv * inv * inv * e.rate * v;
        if (repeated) continue;
        // The wound rope keeps the strain it had at the tangent point: U_w grows by w = EA F(eps)
        // per metre of material stored, dU_w/dt = kappa w sdot_k (kappa = +1 at a start drum,
        // -1 at an end drum), a generalized force -kappa w on s_k.
        const double kappa = k == 0 ? 1.0 : -1.0;
        const double w = span.axialLaw().EA * span.axialLaw().F(e.strain);
        data.nodeForce[row] -= kappa * w;
        data.gripHeldEnergyRates[d] = kappa * w * v * inv;
        // The creep's weight (with a stored ring, which is laid over the groove it covers, kappa
        // (s_k - c_k), and so is short of the material wound on by kappa c_k): the creep's mass
        // rhoA kappa c_k is held at the height where it was wound, U_c with rate kappa rhoA phi_T
        // cdot_k (phi_T = -g . r_T, r_T the tangent point), a generalized force
        // kappa rhoA phi_T (lambda - 1) on s_k (its power is -dU_c/dt). The rope's mass is then
        // conserved, and no force depends on the height datum.
        bool hasRing = false;
        for (const Storage& st : storage_) hasRing = hasRing || st.node == k;
        if (hasRing) {  // mutation-site: creep-weight
            const Eigen::Matrix<double, Dim, 1> rT =
                ws.spanQ[j].template segment<Dim>(end == SpanEnd::First ? span.r1Index() : span.r2Index());
            const double phiT = -span.gravity().dot(rT), rhoA = properties().massPerLength;
            data.nodeForce[row] += kappa * rhoA * phiT * (1.0 / inv - 1.0);
            data.gripHeldEnergyRates[d] += kappa * rhoA * phiT * v * (inv - 1.0);
        }
        // The stored ring turns with the groove: its law is evaluated at the groove's rate v
        // (not sdot_k = v / lambda) and carried to s_k by its rate's map, d(v) = lambda d(sdot_k)
        // + lambdadot sdot_k: mass D M D, force D (f - M e_s lambdadot sdot_k), D = diag(1.., lambda
        // at s_k).
        for (std::size_t i = 0; i < storage_.size(); ++i) {
            if (storage_[i].node != k) continue;
            detail::StoredRopeTerms<Dim>& t = ws.storedRope[i];
            for (int a = 0; a < t.count; ++a) {
                data.nodeForce[t.cols[a]] -= t.force[a];
                if (data.formNodeMass)
                    for (int b = 0; b < t.count; ++b) data.nodeMass(t.cols[a], t.cols[b]) -= t.mass(a, b);
            }
            data.kineticEnergy -= t.kineticEnergy;
            data.gravityEnergy -= t.gravityEnergy;
            const double creep = gripCreepAt(data, d);
            ws.gripXdot = xdot;
            ws.gripXdot[row] = v;
            storedRopeLaw(*this, k, storage_[i].lengthAtZero, storage_[i].slope)
                .evaluate(x, ws.gripXdot, data.materialCoordinates[k] - creep, v, t);
            int at = -1;
            for (int a = 0; a < t.count; ++a)
                if (t.cols[a] == row) at = a;
            if (at >= 0) {
                const double lambda = 1.0 / inv, lambdaDot = e.rate * inv, sdot = v * inv;
                for (int a = 0; a < t.count; ++a) t.force[a] -= t.mass(a, at) * lambdaDot * sdot;
                t.force[at] *= lambda;
                t.mass.row(at) *= lambda;
                t.mass.col(at) *= lambda;
            }
            for (int a = 0; a < t.count; ++a) {
                data.nodeForce[t.cols[a]] += t.force[a];
                if (data.formNodeMass)
                    for (int b = 0; b < t.count; ++b) data.nodeMass(t.cols[a], t.cols[b]) += t.mass(a, b);
            }
            data.kineticEnergy += t.kineticEnergy;
            data.gravityEnergy += t.gravityEnergy;
        }
    }
}

template <int Dim>
double RopeModel<Dim>::storedRopeGravityEnergy(const NodeMatrix& nodes, const RopeData<Dim>& data) const {
    double u = 0;
    for (const Storage& st : storage_) {
        const detail::StoredRope<Dim> law = storedRopeLaw(*this, st.node, st.lengthAtZero, st.slope);
        double s = data.materialCoordinates[st.node];
        if (grips(st.node)) s -= gripCreepAt(data, drivenIndex_[st.node]);  // (laid from the groove's coordinate)
        if (!law.isWrapped()) {
            u -= properties().massPerLength * law.length(s) * elements_->spans.front().gravity().dot(nodes.col(st.node));
            continue;
        }
        u += law.gravityEnergy(mappedPositions(nodes, data), s);
    }
    return u;
}


namespace {
// The coordinates q of span j of `model` (SpanModel layout) from its end positions r1, r2, its
// material coordinates s1, s2 and the rope's modal state and condensed amplitudes.
template <int Dim, class R1, class R2>
void assembleSpanCoordinates(const RopeModel<Dim>& model, int j, const R1& r1, const R2& r2, double s1, double s2,
                             const Eigen::VectorXd& qm, const RopeData<Dim>& data, Eigen::VectorXd& q);
}  // namespace

template <int Dim>
void RopeModel<Dim>::spanCoordinates(int j, const NodeMatrix& nodes, const Eigen::VectorXd& qm,
                                     const RopeData<Dim>& data, Eigen::VectorXd& q) const {
    if (!elements_->arcs.empty()) {
        spanCoordinatesFromExternal(j, mappedPositions(nodes, data), qm, data, q);
        return;
    }
    assembleSpanCoordinates(*this, j, nodes.col(j), nodes.col(j + 1), data.materialCoordinates[j],
                            data.materialCoordinates[j + 1], qm, data, q);
}

template <int Dim>
const Eigen::VectorXd& RopeModel<Dim>::mappedPositions(const NodeMatrix& nodes, const RopeData<Dim>& data) const {
    detail::RopeWorkspace<Dim>& ws = data.scratch();
    const int np = Dim * numStations();
    Eigen::VectorXd& Y = ws.queryStations;
    Y.setZero(np + numDriven_);
    for (int k = 0; k < numStations(); ++k) Y.template segment<Dim>(Dim * k) = nodes.col(k);
    for (const WrapStationMapData* m : {&ws.stationPositionMap, &ws.stationMap})
        if (m->stations.size() == Y.size() && m->x.size() > 0 && m->stations.head(np) == Y.head(np)) return m->x;
    ws.queryMap.wrapAngles = ws.stationMap.wrapAngles;  // continuity with the last evaluation
    ws.queryMap.arrivalAngles = ws.stationMap.arrivalAngles;
    WrapStationMap<Dim>(*this).evaluatePositions(Y, ws.queryMap);
    return ws.queryMap.x;
}

template <int Dim>
WrapStationMapData RopeModel<Dim>::stationMapAt(const NodeMatrix& nodes, const RopeData<Dim>& data) const {
    WrapStationMapData m;
    const int nY = Dim * numStations() + numDriven_;
    Eigen::VectorXd Y = Eigen::VectorXd::Zero(nY);
    for (int k = 0; k < numStations(); ++k) Y.template segment<Dim>(Dim * k) = nodes.col(k);
    m.wrapAngles = data.ws().stationMap.wrapAngles;  // continuity with the last evaluation
    m.arrivalAngles = data.ws().stationMap.arrivalAngles;
    WrapStationMap<Dim>(*this).evaluatePositions(Y, m);
    return m;
}

template <int Dim>
double RopeModel<Dim>::arcGravityEnergy(const NodeMatrix& nodes, const RopeData<Dim>& data) const {
    if (elements_->arcs.empty()) return 0.0;
    const Eigen::VectorXd& x = mappedPositions(nodes, data);
    double u = 0;
    typename GrooveArc<Dim>::Coordinates a;
    for (std::size_t i = 0; i < elements_->arcs.size(); ++i) {
        arcCoordinates(arcNode_[i], x, data.materialCoordinates[arcNode_[i]], a);
        u += elements_->arcs[i].gravityEnergy(a);
    }
    return u;
}

template <int Dim>
void RopeModel<Dim>::spanCoordinatesFromExternal(int j, const Eigen::VectorXd& x, const Eigen::VectorXd& qm,
                                                 const RopeData<Dim>& data, Eigen::VectorXd& q) const {
    assembleSpanCoordinates(*this, j, x.template segment<Dim>(departureOffset(j)),
                            x.template segment<Dim>(arrivalOffset(j + 1)),
                            data.materialCoordinates[j] + arcLengthAt(x, j), data.materialCoordinates[j + 1], qm, data,
                            q);
}

namespace {
template <int Dim, class R1, class R2>
void assembleSpanCoordinates(const RopeModel<Dim>& model, int j, const R1& r1, const R2& r2, double s1, double s2,
                             const Eigen::VectorXd& qm, const RopeData<Dim>& data, Eigen::VectorXd& q) {
    const auto& sp = model.span(j);
    q.resize(sp.numCoordinates());
    q.template segment<Dim>(0) = r1;
    q.template segment<Dim>(Dim) = r2;
    const int nmSpan = sp.numModalCoordinates();
    if (model.isCondensed(j)) {
        const int na = sp.numCondensedModes();
        q.segment(2 * Dim, na) = data.condensedAmplitudes.segment(model.condensedOffset(j), na);
        q.segment(2 * Dim + na, nmSpan - na) = qm.segment(model.modalOffset(j), nmSpan - na);
    } else {
        q.segment(2 * Dim, nmSpan) = qm.segment(model.modalOffset(j), nmSpan);
    }
    q[sp.s1Index()] = s1;
    q[sp.s2Index()] = s2;
}
}  // namespace

template <int Dim>
void RopeModel<Dim>::fillSpanCoordinates(const Eigen::VectorXd& x, const Eigen::VectorXd& qm,
                                         RopeData<Dim>& data) const {
    const int N = numSpans();
    data.ws().spanQ.resize(N);
    data.ws().spanQdot.resize(N);
    for (int j = 0; j < N; ++j) {
        spanCoordinatesFromExternal(j, x, qm, data, data.ws().spanQ[j]);
        if (data.ws().spanQdot[j].size() != data.ws().spanQ[j].size()) data.ws().spanQdot[j].setZero(data.ws().spanQ[j].size());
    }
}

template <int Dim>
void RopeModel<Dim>::evaluateConstraints(const Eigen::VectorXd& x, const Eigen::VectorXd& qm, RopeData<Dim>& data,
                                         bool withRates) const {
    const int N = numSpans(), nw = numExternalCoordinates() + numModal_, nd = numDependent();
    const int nqc = numCondensed_, nc = numSliding_;
    fillSpanCoordinates(x, qm, data);
    Eigen::VectorXd& C = data.ws().newtonResidual;
    data.ws().bias.setZero(nd);
    std::vector<detail::JacobianEntry>& jac = data.ws().jacobian;
    detail::RopeWorkspace<Dim>& w = data.ws();
    // The Jacobian's structure (which (row, column) entries, in which order the terms add to them)
    // depends on the model only. The first evaluation records it (putTarget: the entry of jac each
    // term lands in, rows merged by column); later ones replay it, adding the terms into the same
    // entries in the same order (bit for bit the recorded sums), checking row and column as they go.
    const bool build = !withRates || elements_->kernels.empty();
    const bool replay = build && w.patternId == structureId_ && w.patternValid;
    if (build) {
        C.setZero(nd);
        if (replay) {
            for (detail::JacobianEntry& e : jac) e.value = 0.0;
        } else {
            jac.clear();
            w.putTarget.clear();
            w.dependentOffset.clear();
            w.kktOffset.clear();
            w.kktTransposedOffset.clear();
            w.patternValid = false;
        }
    }
    std::size_t counter = 0;
    bool mismatch = false;
    // Recording: entries of one row are merged by column before they join jac (a row sums up to six
    // span quantities' gradients over the same coordinates): each (row, column) appears once, its
    // value summed in the order the terms come, as the band matrices summed them before.
    std::vector<int>& slot = w.rowSlot;
    std::vector<detail::JacobianEntry>& pending = w.rowPending;
    if (static_cast<int>(slot.size()) < nw + nd) slot.assign(nw + nd, -1);
    auto flush = [&]() {
        for (const detail::JacobianEntry& e : pending) {
            jac.push_back(e);
            slot[e.col] = -1;
        }
        pending.clear();
    };
    // Replaying, the structure is the recorded one (same model structure, structureId_): each term
    // goes to its recorded entry, the count checked.
    auto put = [&](int row, int col, double value) {
        if (replay) {
            if (counter < w.putTarget.size())
                jac[w.putTarget[counter++]].value += value;
            else
                mismatch = true;
            return;
        }
        if (!pending.empty() && pending.front().row != row) flush();
        if (slot[col] < 0) {
            slot[col] = static_cast<int>(pending.size());
            pending.push_back({row, col, value});
        } else {
            pending[slot[col]].value += value;
        }
        w.putTarget.push_back(static_cast<int>(jac.size()) + slot[col]);
    };
    // Ends the pass: true if a replay found another structure (then the caller evaluates again,
    // recording).
    auto finish = [&]() {
        flush();
        if (build && !replay) {
            w.patternId = structureId_;
            w.patternValid = true;
            // The band offsets of the entries (C_d; the KKT's C_y and C_y^T), once per structure.
            w.dependentOffset.assign(jac.size(), -1);
            w.kktOffset.assign(jac.size(), -1);
            w.kktTransposedOffset.assign(jac.size(), -1);
            for (std::size_t t = 0; t < jac.size(); ++t) {
                const detail::JacobianEntry& e = jac[t];
                if (e.col >= nw)
                    w.dependentOffset[t] = BandedLU::offset(nd, dependentKl_, dependentKu_, dependentRowPos_[e.row],
                                                            dependentColPos_[e.col - nw]);
                if (e.col >= numExternalCoordinates()) {
                    const int pr = kktRowPos_[e.row], pc = kktPos_[e.col];
                    w.kktOffset[t] = BandedLU::offset(kktSize_, kktBand_, kktBand_, pr, pc);
                    w.kktTransposedOffset[t] = BandedLU::offset(kktSize_, kktBand_, kktBand_, pc, pr);
                }
            }
        }
        if (replay && (mismatch || counter != w.putTarget.size())) {
            w.patternValid = false;
            return true;
        }
        return false;
    };
    auto scatter = [&](int row, int j, const auto& gradient, double coef) {
        const auto& map = spanToRope_[j];
        if (replay) {  // put's replay for the span's Jacobian columns
            const std::vector<int>& live = jacobianSpanCoordinates_[j];
            if (counter + live.size() > w.putTarget.size()) {
                mismatch = true;
                return;
            }
            detail::JacobianEntry* entries = jac.data();
            const int* target = w.putTarget.data() + counter;
            for (std::size_t t = 0; t < live.size(); ++t) entries[target[t]].value += coef * gradient[live[t]];
            counter += live.size();
        } else {
            for (int i = 0; i < static_cast<int>(map.size()); ++i) {
                const int zi = map[i];
                if (zi < nw + nd) put(row, zi, coef * gradient[i]);
            }
        }
        // A span starting at a wrapped node: s1 = s_j + l_j.
        if (elementExtra_[j] >= 0) put(row, elementExtra_[j], coef * gradient[elementExtraLocal_[j]]);
    };

    // Node k's tension row (k Sliding or Slipping): its law's weights, and the wrap angle when they
    // follow it (taken once per row and pass; ws.w holds xdot at the rates' pass).
    auto tensionRow = [&](int k) {
        detail::TensionRow<Dim> r;
        detail::visitDependent(laws_[k], [&](const auto& law) {
            law.tensionRow([&] { return slipAngle(k, x, withRates ? &data.ws().w : nullptr); }, r);
        });
        return r;
    };
    // kappa(alpha) (setSlipLaw): dC/dalpha dalpha/dx into the row's Jacobian (jacobian), and the
    // bias's terms in alphadot and alpha's own bias (rates), at the strains a, b of spans k - 1 and
    // k at the node and their rates aRate, bRate.
    auto addAngleTerms = [&](int row, const detail::TensionRow<Dim>& r, double a, double b, double aRate, double bRate,
                             bool jacobian, bool rates) {
        if (!r.angleLaw) return;
        if (jacobian) {
            const double dC = r.angleSlope(a, b);
            for (int i = 0; i < r.angle.count; ++i) put(row, r.angle.cols[i], dC * r.angle.grad[i]);
        }
        if (rates) data.ws().bias[row] += r.angleBias(a, b, aRate, bRate);
    };

    if (elements_->kernels.empty()) {
        // The paper's rows: eps_{k-1}(s_k) - eps_k(s_k) from the spans' analytic end strains.
        data.ws().firstEnd.resize(N);
        data.ws().secondEnd.resize(N);
        for (int j = 0; j < N; ++j) {
            elements_->spans[j].endStrain(data.ws().spanQ[j], data.ws().spanQdot[j], SpanEnd::First, data.ws().firstEnd[j]);
            elements_->spans[j].endStrain(data.ws().spanQ[j], data.ws().spanQdot[j], SpanEnd::Second, data.ws().secondEnd[j]);
        }
        for (int row = 0; row < nc; ++row) {
            const int k = slidingNode_[row];
            // 1, 1 but at Slipping nodes: eps_{k-1} = kappa eps_k, scaled (CapstanLaw)
            const detail::TensionRow<Dim> tr = tensionRow(k);
            const double wb = tr.weights.before, wa = tr.weights.after;
            const EndStrain<Dim>& a = data.ws().secondEnd[k - 1];
            const EndStrain<Dim>& b = data.ws().firstEnd[k];
            C[row] = wb * a.strain - wa * b.strain;
            scatter(row, k - 1, a.gradient, wb);
            scatter(row, k, b.gradient, -wa);
            addAngleTerms(row, tr, a.strain, b.strain, a.rate, b.rate, true, withRates);
            if (withRates)
                data.ws().bias[row] += wb * a.accelerationBias - wa * b.accelerationBias;
        }
        if (finish()) evaluateConstraints(x, qm, data, withRates);
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
            elements_->kernels[j].evaluateRates(data.ws().spanQ[j], data.ws().spanQdot[j], data.ws().condensation[j]);
        else
            elements_->kernels[j].evaluate(data.ws().spanQ[j], noRates, data.ws().condensation[j]);
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
    // coef * nu_m * f with f a span quantity: nu is a dependent coordinate too, coef = sign * node
    // m's row weight (after: w_after, else w_before). Only nodes whose law has a constraint C_m and
    // a multiplier in the stationarity (Sliding) add terms; the others' vanish (a Slipping node's
    // multiplier is held at zero, its row below: the capstan row alone fixes s_m).
    auto addProduct = [&](int row, int m, int j, int quantity, double sign, bool after) {
        if (m < 1 || m > N - 1) return;
        detail::visitDependent(laws_[m], [&](const auto& law) {
            law.multiplierProducts([&](const detail::SlipWeights& weights) {
                const double coef = sign * (after ? weights.after : weights.before);
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
                put(row, nw + nqc + nc + mi, coef * K.value[quantity]);
            });
        });
    };
    for (int j = 0; j < N; ++j) {
        if (!isCondensed(j)) continue;
        const AxialCondensation<Dim>& kj = elements_->kernels[j];
        for (int i = 0; i < kj.numCondensedModes(); ++i) {
            const int row = condensedOffset_[j] + i;
            addTerm(row, j, kj.phi(i), invEA);
            addProduct(row, j, j, kj.endStrainModeSlope(SpanEnd::First, i), -1.0, true);
            addProduct(row, j + 1, j, kj.endStrainModeSlope(SpanEnd::Second, i), 1.0, false);
        }
    }
    for (int ki = 0; ki < nc; ++ki) {
        const int k = slidingNode_[ki], row = nqc + ki;
        const detail::TensionRow<Dim> tr = tensionRow(k);
        const int qa = elements_->kernels[k - 1].endStrain(SpanEnd::Second), qb = elements_->kernels[k].endStrain(SpanEnd::First);
        addTerm(row, k - 1, qa, tr.weights.before);
        addTerm(row, k, qb, -tr.weights.after);
        // (The values are the position pass's, still in the kernels' data at the rates' pass; the
        // rates exist at the rates' pass only.)
        const auto& Ka = data.ws().condensation[k - 1];
        const auto& Kb = data.ws().condensation[k];
        addAngleTerms(row, tr, Ka.value[qa], Kb.value[qb], withRates ? Ka.rate[qa] : 0.0, withRates ? Kb.rate[qb] : 0.0,
                      !withRates, withRates);
    }
    for (int ki = 0; ki < nc; ++ki) {
        const int k = slidingNode_[ki], row = nqc + nc + ki;
        // The row of node k's multiplier, as its law says: the stationarity in s_k (Sliding), or
        // nu_k = 0 (Slipping: the capstan row eps_{k-1} = kappa eps_k fixes s_k and the friction
        // force, computeDynamics, is applied to it. So no multiplier of the ratio enters the
        // amplitudes' stationarity: the condensed amplitudes solve the same equations in stick and
        // in slip, and at a stick -> slip transition (where the ratio row holds already) the
        // dependent coordinates are continuous. With the stationarity in s_k here and nu_k in the
        // amplitudes' rows, they jumped: 16 J of the rope's potential energy in the elevator's
        // stall at mu = 10.)
        auto stationarity = [&] {
            // dU/ds_k = dU_{k-1}/dl_{k-1} - dU_k/dl_k (s_k ends span k-1 and starts span k).
            addTerm(row, k - 1, elements_->kernels[k - 1].lengthDerivative(), invEA);
            addTerm(row, k, elements_->kernels[k].lengthDerivative(), -invEA);
            // sum_m nu_m dC_m/ds_k with C_m = wb_m eps2_{m-1}(l_{m-1}) - wa_m eps1_m(l_m), l_j = s_{j+1} - s_j
            // (wb, wa: node m's row weights).
            addProduct(row, k, k - 1, elements_->kernels[k - 1].endStrainLengthSlope(SpanEnd::Second), 1.0, false);
            addProduct(row, k, k, elements_->kernels[k].endStrainLengthSlope(SpanEnd::First), 1.0, true);
            addProduct(row, k + 1, k, elements_->kernels[k].endStrainLengthSlope(SpanEnd::Second), -1.0, false);
            addProduct(row, k - 1, k - 1, elements_->kernels[k - 1].endStrainLengthSlope(SpanEnd::First), -1.0, true);
        };
        auto holdAtZero = [&] {
            if (withRates) return;
            C[row] = data.multipliers[ki];
            put(row, nw + nqc + nc + ki, 1.0);
        };
        detail::visitDependent(laws_[k], [&](const auto& law) { law.multiplierRow(stationarity, holdAtZero); });
    }
    if (finish()) evaluateConstraints(x, qm, data, withRates);
}

template <int Dim>
void RopeModel<Dim>::setKnownMaterialCoordinates(const Eigen::VectorXd& x, RopeData<Dim>& data) const {
    const int N = numSpans();
    // The material a stretch of spans between nodes a and b holds besides the arcs on its wrapped
    // nodes a..b-1 (the departing span of node k starts at s_k + l_k).
    auto arcsFrom = [&](int a, int b) {
        double sum = 0;
        for (int k = a; k < b; ++k) sum += arcLengthAt(x, k);
        return sum;
    };
    Eigen::VectorXd& s = data.materialCoordinates;
    bool warm = s.size() == N + 1 && s.allFinite();
    if (!warm) s.setZero(N + 1);
    auto known = [&](int k) { return slidingIndex_[k] < 0; };
    auto knownValue = [&](int k) {  // (Fixed: its constant; Driven: its entry of x)
        double value = 0;
        detail::visitKnown(laws_[k], [&](const auto& law) { value = law.coordinate(x); });
        return value;
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
        if (!(s[b] > s[a] + arcsFrom(a, b))) {
            std::ostringstream msg;
            msg << "RopeModel: no rope material between node " << a << " (s = " << s[a] << " m) and node " << b
                << " (s = " << s[b] << " m): the " << (b - a == 1 ? "span " + std::to_string(a) : "spans")
                << " between them would have a non-positive unstretched length";
            throw std::runtime_error(msg.str());
        }
        a = b;
    }
    for (int k = 0; warm && k < N; ++k) warm = s[k + 1] > s[k] + arcLengthAt(x, k);
    if (warm) return;
    // Chord-proportional guess for the Sliding nodes between consecutive known nodes (the arcs'
    // material set aside).
    auto chord = [&](int j) {
        return (x.template segment<Dim>(arrivalOffset(j + 1)) - x.template segment<Dim>(departureOffset(j))).norm();
    };
    for (int a = 0; a < N;) {
        int b = a + 1;
        while (!known(b)) ++b;
        double total = 0;
        for (int j = a; j < b; ++j) total += chord(j);
        const double spanMaterial = s[b] - s[a] - arcsFrom(a, b);
        double acc = 0;
        for (int j = a; j + 1 < b; ++j) {
            acc += chord(j);
            const double start = s[a] + arcsFrom(a, j + 1);
            s[j + 1] = total > 0 ? start + spanMaterial * acc / total : start + spanMaterial * (j + 1 - a) / (b - a);
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
    solveDependentCoordinatesFromExternal(stationsToExternal(nodes, nullptr, drivenS, nullptr, data), qm, data);
}

template <int Dim>
void RopeModel<Dim>::solveDependentCoordinatesFromExternal(const Eigen::VectorXd& x, const Eigen::VectorXd& qm,
                                                           RopeData<Dim>& data) const {
    const int N = numSpans(), nqc = numCondensed_, nd = numDependent();
    if (x.size() != numExternalCoordinates()) {
        std::ostringstream msg;
        msg << "RopeModel: " << x.size() << " external coordinates given for " << numExternalCoordinates();
        throw std::invalid_argument(msg.str());
    }
    Eigen::VectorXd& s = data.materialCoordinates;
    const bool warm = s.size() == N + 1 && s.allFinite();
    detail::RopeWorkspace<Dim>& ws = data.ws();
    setKnownMaterialCoordinates(x, data);
    if (data.condensedAmplitudes.size() != nqc || !data.condensedAmplitudes.allFinite())
        data.condensedAmplitudes.setZero(nqc);
    if (data.multipliers.size() != numMultipliers_ || !data.multipliers.allFinite())
        data.multipliers.setZero(numMultipliers_);
    data.multiplierRates.setZero(numMultipliers_);
    data.newtonIterations = 0;
    ws.dynamicsCurrent = false;
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
            setKnownMaterialCoordinates(x, data);
            data.condensedAmplitudes.setZero(nqc);
            data.multipliers.setZero(numMultipliers_);
        }
        evaluateConstraints(x, qm, data, false);
        if (nd == 0) return;
        // Converged at 1e-14 in strain, or stagnating at round-off below 1e-12 (eps = 1/2(|t|^2/l^2 - 1)
        // carries about 1e-16 absolute error, the stationarity sums a few times that: a long chain's
        // rows reach 1e-15, so a bound of 1e-15 spent one more iteration just to see the round-off
        // stagnate, 2.75 against 1.89 iterations per solve on the 12-fall crane). States with
        // very large strains (an impact, an integrator's far trial state) have a higher round-off
        // floor: after 4 iterations, stagnation below 1e-9 is accepted too (the equations then hold
        // to 1e-9 in strain units), rather than failing an evaluation that has converged.
        const double err = C.cwiseAbs().maxCoeff();
        const bool stagnating = err > 0.5 * previous;
        if (err <= 1e-14 || (stagnating && err <= 1e-12) || (stagnating && iter >= 4 && err <= 1e-9)) {
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
        factorDependentJacobian(data, ws.newtonLu);
        Eigen::VectorXd& step = data.ws().newtonStep;
        solveDependent(data, ws.newtonLu, C, step);
        step *= -1.0;
        // Halve the step until the material coordinates stay ordered (every span keeps l > 0).
        auto stepped = [&](int k, double a) {
            return slidingIndex_[k] >= 0 ? s[k] + a * step[nqc + slidingIndex_[k]] : s[k];
        };
        alpha = alphaCap;
        for (int halve = 0; halve < 30; ++halve, alpha *= 0.5) {
            bool ok = true;
            for (int k = 1; k <= N && ok; ++k) ok = stepped(k, alpha) > stepped(k - 1, alpha) + arcLengthAt(x, k - 1);
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
            if (condensedOffset_[j] >= 0 && row >= condensedOffset_[j] && row < condensedOffset_[j] + elements_->spans[j].numCondensedModes())
                span = j;
        where << "span " << span << " (quasi-static modal amplitudes)";
    } else if (row < nqc + numSliding_) {
        const int k = slidingNode_[row - nqc];
        where << "sheave node " << k << " (tension equality of spans " << k - 1 << " and " << k << ")";
    } else {
        where << "sheave node " << slidingNode_[row - nqc - numSliding_]
              << " (stationarity in its material coordinate)";
    }
    std::ostringstream msg;
    msg << "RopeModel: the dependent coordinates (sheave tension equality"
        << (nqc > 0 ? ", quasi-static modes" : "") << ") did not converge in " << kMaxIterations << " Newton iterations "
        << "(max residual " << C.cwiseAbs().maxCoeff() << " in strain units, at " << where.str()
        << "); the configuration may be infeasible (a span shorter than its chord allows, nodes crossing)";
    throw std::runtime_error(msg.str());
}

template <int Dim>
bool RopeModel<Dim>::positionsMatch(const Eigen::VectorXd& x, const Eigen::VectorXd& qm,
                                    const RopeData<Dim>& data) const {
    const int N = numSpans();
    if (static_cast<int>(data.ws().spanQ.size()) != N || data.materialCoordinates.size() != N + 1 ||
        data.condensedAmplitudes.size() != numCondensed_ || data.multipliers.size() != numMultipliers_ ||
        x.size() != numExternalCoordinates())
        return false;
    for (int k = 0; k <= N; ++k) {
        bool agrees = true;  // (a Driven s_k is the x it was solved at)
        detail::visitKnown(laws_[k], [&](const auto& law) { agrees = law.agrees(data.materialCoordinates[k], x); });
        if (!agrees) return false;
    }
    for (int j = 0; j < N; ++j) {
        const auto& q = data.ws().spanQ[j];
        const int nmSpan = elements_->spans[j].numModalCoordinates();
        const int na = elements_->spans[j].numCondensedModes();
        if (q.size() != elements_->spans[j].numCoordinates() || q.template segment<Dim>(0) != x.template segment<Dim>(departureOffset(j)) ||
            q.template segment<Dim>(Dim) != x.template segment<Dim>(arrivalOffset(j + 1)) ||
            q.segment(2 * Dim + na, nmSpan - na) != qm.segment(modalOffset_[j], nmSpan - na) ||
            (isWrapped(j) && q[elements_->spans[j].s1Index()] != data.materialCoordinates[j] + arcLengthAt(x, j)))
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
    if (drivenSdot.size() != numDriven_) {
        std::ostringstream msg;
        msg << "RopeModel::computeDynamics: drivenSdot has the wrong size: " << drivenSdot.size()
            << " rates given for " << numDriven_ << " Driven nodes";
        throw std::invalid_argument(msg.str());
    }
    const Eigen::VectorXd& x = stationsToExternal(nodes, &nodeVelocities, drivenS, &drivenSdot, data);
    const Eigen::VectorXd& xdot = elements_->arcs.empty() ? data.ws().packedXdot : data.ws().stationMap.xdot;
    if (!gripNodes_.empty()) applyGripRates(x, qm, data);
    computeDynamicsFromExternal(x, xdot, qm, qmdot, data);
    // (With wrapped nodes stationMode is still set only if computeDynamicsFromExternal found a
    // repeat of the last evaluation.)
    if (!gripNodes_.empty()) applyGripTerms(x, xdot, data.ws().stationMode, data);
    // A rope with wrapped nodes is coupled at its stations: S, h and the modal reduction carried
    // over (once per evaluation: a repeated one returns above with them already carried).
    if (!elements_->arcs.empty() && !data.ws().stationMode) dynamicsToStations(data);
}

template <int Dim>
void RopeModel<Dim>::computeDynamicsFromExternal(const Eigen::VectorXd& x, const Eigen::VectorXd& xdot,
                                                 const Eigen::VectorXd& qm, const Eigen::VectorXd& qmdot,
                                                 RopeData<Dim>& data) const {
    const int N = numSpans(), nn = numNodeCoordinates_, nx = nn + numDriven_, nm = numModal_, nw = nx + nm;
    const int nqc = numCondensed_, nc = numSliding_, nd = numDependent(), nz = nw + nd + numFixed_;
    // solveDependentCoordinates left the span coordinates and the constraint Jacobians (velocity
    // independent) of this configuration in data; they are reused when they belong to these
    // positions, and solved afresh otherwise.
    if (x.size() != nx || xdot.size() != nx) {
        std::ostringstream msg;
        msg << "RopeModel::computeDynamics: " << x.size() << " external coordinates and " << xdot.size()
            << " rates given for " << nx;
        throw std::invalid_argument(msg.str());
    }
    detail::RopeWorkspace<Dim>& ws = data.ws();
    auto dependentsSnapshot = [&](Eigen::VectorXd& y) {  // [s; q_condensed; nu] (sizes fixed by the model)
        y.resize(N + 1 + nqc + numMultipliers_);
        y.head(N + 1) = data.materialCoordinates;
        y.segment(N + 1, nqc) = data.condensedAmplitudes;
        y.tail(numMultipliers_) = data.multipliers;
    };
    if (!positionsMatch(x, qm, data)) {
        solveDependentCoordinatesFromExternal(x, qm, data);
    } else if (ws.dynamicsCurrent && ws.model == this && ws.nodeMassFormed == data.formNodeMass) {
        // A realization of the same positions and velocities again (Simbody invalidates
        // Stage::Velocity when u is written, even with the values it had; measured on the 12-fall
        // crane: 17 % of its velocity realizations): the results in data are this evaluation's.
        bool same = ws.dynamicsDependents.size() == N + 1 + nqc + numMultipliers_ &&
                    ws.dynamicsDependents.head(N + 1) == data.materialCoordinates &&
                    ws.dynamicsDependents.segment(N + 1, nqc) == data.condensedAmplitudes &&
                    ws.dynamicsDependents.tail(numMultipliers_) == data.multipliers && ws.w.size() == nw;
        same = same && ws.w.head(nx) == xdot && ws.w.tail(nm) == qmdot;
        // (The arcs' centres and axes are not span coordinates: compared here.)
        same = same && (elements_->arcs.empty() || ws.dynamicsX == x);
        if (same) return;
    }
    ws.dynamicsCurrent = false;
    externalBuffersBack(data);  // data's x-level buffers back from the station forms' last reduction
    ws.stationMode = false;

    // Independent velocities w = [xdot (node blocks, sdot_driven); qdot_m].
    data.ws().w.resize(nw);
    data.ws().w.head(nx) = xdot;
    data.ws().w.tail(nm) = qmdot;
    if (!elements_->arcs.empty()) ws.dynamicsX = x;

    data.ws().spans.resize(N);
    data.materialRates.setZero(N + 1);
    for (int k = 0; k <= N; ++k)  // the known rates (Fixed: 0; Driven: as given); the solved ones below
        detail::visitKnown(laws_[k], [&](const auto& law) { data.materialRates[k] = law.rate(xdot); });
    data.condensedRates.setZero(nqc);
    data.multiplierRates.setZero(numMultipliers_);
    auto fillSpanVelocities = [&] {
        for (int j = 0; j < N; ++j) {
            const auto& sp = elements_->spans[j];
            Eigen::VectorXd& qd = data.ws().spanQdot[j];
            qd.resize(sp.numCoordinates());
            qd.template segment<Dim>(0) = xdot.template segment<Dim>(departureOffset(j));
            qd.template segment<Dim>(Dim) = xdot.template segment<Dim>(arrivalOffset(j + 1));
            const int nmSpan = sp.numModalCoordinates();
            if (isCondensed(j)) {
                const int na = sp.numCondensedModes();
                qd.segment(2 * Dim, na) = data.condensedRates.segment(condensedOffset_[j], na);
                qd.segment(2 * Dim + na, nmSpan - na) = qmdot.segment(modalOffset_[j], nmSpan - na);
            } else {
                qd.segment(2 * Dim, nmSpan) = qmdot.segment(modalOffset_[j], nmSpan);
            }
            qd[sp.s1Index()] = data.materialRates[j] + (isWrapped(j) ? xdot[nodeOffset_[j] + wrappedArcLengthOffset()] : 0.0);
            qd[sp.s2Index()] = data.materialRates[j + 1];
        }
    };
    data.ws().spanQdot.resize(N);
    // Velocity transformation zdot = G w, zddot = G wdot + c: G is the identity on w, zero for the
    // Fixed material coordinates; for the dependents d, C_d ddot = -C_w w and c_d = -C_d^-1 bias,
    // solved with the band LU of C_d (chain order), never formed as a dense Gd = -C_d^-1 C_w.
    ws.model = this;
    ws.reducedValid = false;
    ws.productColumns = -1;
    if (nd > 0) {
        factorDependentJacobian(data, ws.dependentLu);
        ws.rowScratch.setZero(nd);
        for (const detail::JacobianEntry& e : ws.jacobian)
            if (e.col < nw) ws.rowScratch[e.row] -= e.value * ws.w[e.col];
        solveDependent(data, ws.dependentLu, ws.rowScratch, ws.cd);  // (scratch: ddot)
        data.condensedRates = ws.cd.head(nqc);
        for (int ki = 0; ki < nc; ++ki) data.materialRates[slidingNode_[ki]] = ws.cd[nqc + ki];
        data.multiplierRates = ws.cd.tail(numMultipliers_);
        // Biases (second time derivatives of the constraints at wdot = 0) with the complete
        // velocities, dependent rates included.
        fillSpanVelocities();
        evaluateConstraints(x, qm, data, true);
        solveDependent(data, ws.dependentLu, ws.bias, ws.cd);
        ws.cd *= -1.0;
    } else {
        fillSpanVelocities();
        ws.cd.resize(0);
    }

    // Span evaluations; their forces scattered into Q_z (the multipliers carry no mass).
    ws.Qz.setZero(nz);
    data.inertialCorrectionValid = false;
    if (nqc > 0) ws.velocityForcesZ.setZero(nz);
    data.kineticEnergy = data.strainEnergy = data.gravityEnergy = data.dampingPower = 0;
    for (int j = 0; j < N; ++j) {
        SpanData<Dim>& d = ws.spans[j];
        elements_->spans[j].evaluate(ws.spanQ[j], ws.spanQdot[j], d);
        const auto& map = spanToRope_[j];
        const int n = elements_->spans[j].numCoordinates();
        for (int a = 0; a < n; ++a) {
            ws.Qz[map[a]] += d.velocityForces[a] + d.elasticForces[a] + d.gravityForces[a] + d.dampingForces[a];
            if (nqc > 0) ws.velocityForcesZ[map[a]] += d.velocityForces[a];
        }
        if (elementExtra_[j] >= 0) {  // s1 = s_j + l_j
            const int a = elementExtraLocal_[j];
            ws.Qz[elementExtra_[j]] += d.velocityForces[a] + d.elasticForces[a] + d.gravityForces[a] + d.dampingForces[a];
            if (nqc > 0) ws.velocityForcesZ[elementExtra_[j]] += d.velocityForces[a];
        }
        data.kineticEnergy += d.kineticEnergy;
        data.strainEnergy += d.strainEnergy();
        data.gravityEnergy += d.gravityEnergy;
        data.dampingPower += d.dampingPower;
    }
    // The rope on the groove arcs of wrapped nodes (GrooveArc).
    ws.arcs.resize(elements_->arcs.size());
    for (std::size_t i = 0; i < elements_->arcs.size(); ++i) {
        const int k = arcNode_[i];
        typename GrooveArc<Dim>::Coordinates a, adot;
        arcCoordinates(k, x, data.materialCoordinates[k], a);
        arcCoordinates(k, xdot, data.materialRates[k], adot);
        GrooveArcData<Dim>& d = ws.arcs[i];
        elements_->arcs[i].evaluate(a, adot, d);
        const auto& map = elementToRope_[N + i];
        for (int l = 0; l < GrooveArc<Dim>::kNumCoordinates; ++l) {
            ws.Qz[map[l]] += d.velocityForces[l] + d.gravityForces[l];
            if (nqc > 0) ws.velocityForcesZ[map[l]] += d.velocityForces[l];
        }
        data.kineticEnergy += d.kineticEnergy;
        data.gravityEnergy += d.gravityEnergy;
    }
    // The friction at the solved nodes, as their laws say (Slipping: F_f = P_k - P_{k-1} on the
    // material s_k, its reaction on the sheave's surface coordinate; Sliding: none).
    for (int ki = 0; ki < nc; ++ki) {
        const int k = slidingNode_[ki];
        detail::visitDependent(laws_[k], [&](const auto& law) {
            law.addFriction([&] { return constraintError(data, k); }, ws.Qz, nw + nqc + ki);
        });
    }

    // The rope's equations at given external accelerations xddot, with y = [q_free, d] and
    // multipliers mu of the constraints (M zddot = Q - C_z^T mu + E^T f, f the supports' force on x):
    //     [M_yy  C_y^T] [yddot]   [Q_y - M_yx xddot]
    //     [C_y   0    ] [mu   ] = [-bias - C_x xddot],      f = M_xx xddot + M_xy yddot - Q_x + C_x^T mu,
    // a band matrix in chain order (span by span, node by node): the same equations as
    // G^T M G wddot = G^T (Q - M c) (G spans the null space of C_z), solved in O(spans). Then
    // f = S xddot - h: h = -f(0) from one solve, S column by column from one solve per external
    // coordinate; qddot_m = modalFree - modalCoupling xddot.
    const int nk = kktSize_;
    BandedLU& kkt = ws.kktLu;
    kkt.reset(nk, kktBand_, kktBand_);
    const int ne = static_cast<int>(elementToRope_.size());
    for (int e = 0; e < ne; ++e) {  // M_yy, at the offsets buildChainOrder found
        int n = 0;
        const double* M = elementMass(data, e, n);
        for (const BandTarget& t : kktMassTargets_[e]) kkt.addAt(t.offset, M[t.source]);
    }
    // C_x by column (counting sort), C_y into the band (at the offsets recorded with C_z's structure).
    ws.externalColumnStart.assign(nx + 1, 0);
    const bool offsets = ws.kktOffset.size() == ws.jacobian.size();
    for (std::size_t t = 0; t < ws.jacobian.size(); ++t) {
        const detail::JacobianEntry& e = ws.jacobian[t];
        if (e.col < nx) {
            ++ws.externalColumnStart[e.col + 1];
        } else if (offsets) {
            kkt.addAt(ws.kktOffset[t], e.value);
            kkt.addAt(ws.kktTransposedOffset[t], e.value);
        } else {
            const int pr = kktRowPos_[e.row], pc = kktPos_[e.col];
            kkt.add(pr, pc, e.value);
            kkt.add(pc, pr, e.value);
        }
    }
    for (int i = 0; i < nx; ++i) ws.externalColumnStart[i + 1] += ws.externalColumnStart[i];
    ws.externalColumnRow.resize(ws.externalColumnStart[nx]);
    ws.externalColumnValue.resize(ws.externalColumnStart[nx]);
    {
        std::vector<int>& next = ws.externalColumnStart;  // shifted while filling, restored below
        for (const detail::JacobianEntry& e : ws.jacobian)
            if (e.col < nx) {
                const int at = next[e.col]++;
                ws.externalColumnRow[at] = e.row;
                ws.externalColumnValue[at] = e.value;
            }
        for (int i = nx; i > 0; --i) next[i] = next[i - 1];
        next[0] = 0;
    }
    if (nk > 0 && !kkt.factor())
        throw std::runtime_error("RopeModel::computeDynamics: the rope's equations of motion are singular at this state");

    // All right-hand sides in one block solve (row-major, nk x nc): column 0 at xddot = 0 (-> h), then
    // one per moving external coordinate i: -[M_yx e_i; C_x e_i] (-> S e_i).
    std::vector<int>& columns = ws.solvedColumns;
    columns.clear();
    for (int i = 0; data.formNodeMass && i < nx; ++i)
        if (stationaryColumn_.empty() || !stationaryColumn_[i]) columns.push_back(i);
    ws.nodeMassFormed = data.formNodeMass;
    const int ncol = 1 + static_cast<int>(columns.size());
    Eigen::VectorXd& B = ws.chainSolution;
    B.setZero(static_cast<Eigen::Index>(nk) * ncol);
    if (data.formNodeMass)
        data.nodeMass.setZero(nx, nx);
    else
        data.nodeMass.resize(0, 0);
    for (int z = nx; z < nw + nd; ++z) B[kktPos_[z] * ncol] = ws.Qz[z];
    for (int r = 0; r < nd; ++r) B[kktRowPos_[r] * ncol] = -ws.bias[r];
    for (int c = 1; c < ncol; ++c) {
        const int i = columns[c - 1];
        const auto& spansAt = externalSpans_[i];
        for (int slot = 0; slot < 6; slot += 2) {
            const int e = spansAt[slot];
            if (e < 0) continue;
            const int a = spansAt[slot + 1];
            const int* map = elementToRope_[e].data();
            int n = 0;
            const double* M = elementMass(data, e, n) + static_cast<std::ptrdiff_t>(n) * a;
            for (int b = 0; b < n; ++b) {
                const int pb = kktPos_[map[b]];
                if (pb >= 0)
                    B[pb * ncol + c] -= M[b];
                else if (map[b] < nx)
                    data.nodeMass(map[b], i) += M[b];  // M_xx e_i
            }
            const int extraLocal = elementExtraLocal_[e];  // s1 = s_j + l_j: l_j's share
            if (extraLocal >= 0) data.nodeMass(elementExtra_[e], i) += M[extraLocal];
        }
        for (int at = ws.externalColumnStart[i]; at < ws.externalColumnStart[i + 1]; ++at)
            B[kktRowPos_[ws.externalColumnRow[at]] * ncol + c] -= ws.externalColumnValue[at];
    }
    if (nk > 0) kkt.solve(B.data(), ncol);
    // F = M_xy Y + C_x^T Mu (nx x ncol, row-major) for the solutions [Y; Mu] in B.
    Eigen::VectorXd& F = ws.supportBlock;
    F.setZero(static_cast<Eigen::Index>(nx) * ncol);
    for (int e = 0; e < ne; ++e) {  // M_xy Y (the terms multiplyByNodeMass applies, in the same order)
        const RowTerm* terms = massTimesKktIntoExternal_.data();
        int n = 0;
        applyRowTerms<false>(terms + massTermSpanStart_[3 * e + 2], terms + massTermSpanStart_[3 * e + 5],
                             elementMass(data, e, n), B.data(), F.data(), ncol, nullptr);
    }
    for (int i = 0; i < nx; ++i) {
        double* f = F.data() + static_cast<std::ptrdiff_t>(i) * ncol;
        for (int at = ws.externalColumnStart[i]; at < ws.externalColumnStart[i + 1]; ++at)
            axpyRow<false>(ws.externalColumnValue[at],
                           B.data() + static_cast<std::ptrdiff_t>(kktRowPos_[ws.externalColumnRow[at]]) * ncol, f, ncol);
    }
    // h = Q_x - M_xy y0 - C_x^T mu0;  S e_i = M_xx e_i + M_xy dy_i + C_x^T dmu_i.
    data.nodeForce = ws.Qz.head(nx);
    for (int i = 0; i < nx; ++i) {
        data.nodeForce[i] -= F[i * ncol];
        for (int c = 1; c < ncol; ++c) data.nodeMass(i, columns[c - 1]) += F[i * ncol + c];
    }
    ws.modalFree.resize(nm);
    ws.modalCoupling.setZero(nm, data.formNodeMass ? nx : 0);
    for (int m = 0; m < nm; ++m) {
        const double* y = B.data() + static_cast<std::ptrdiff_t>(kktPos_[nx + m]) * ncol;
        ws.modalFree[m] = y[0];
        for (int c = 1; c < ncol; ++c) ws.modalCoupling(m, columns[c - 1]) = -y[c];
    }

    // Rope stored on drums (setStoredRope, StoredRope): it involves only the external coordinates,
    // so it adds to S and h after the modal reduction.
    ws.storedRope.resize(storage_.size());
    for (std::size_t i = 0; i < storage_.size(); ++i) {
        const int k = storage_[i].node;
        detail::StoredRopeTerms<Dim>& t = ws.storedRope[i];
        storedRopeLaw(*this, k, storage_[i].lengthAtZero, storage_[i].slope).evaluate(x, xdot, data.materialCoordinates[k], data.materialRates[k], t);
        for (int a = 0; a < t.count; ++a) {
            data.nodeForce[t.cols[a]] += t.force[a];
            if (data.formNodeMass)
                for (int b = 0; b < t.count; ++b) data.nodeMass(t.cols[a], t.cols[b]) += t.mass(a, b);
        }
        data.kineticEnergy += t.kineticEnergy;
        data.gravityEnergy += t.gravityEnergy;
    }
    dependentsSnapshot(ws.dynamicsDependents);
    ws.dynamicsCurrent = true;
}

template <int Dim>
void RopeModel<Dim>::multiplyByNodeMass(const RopeData<Dim>& data, const Eigen::Ref<const Eigen::MatrixXd>& X, Eigen::MatrixXd& SX) const {
    const detail::RopeWorkspace<Dim>& w = data.ws();
    if (!w.stationMode) {
        multiplyByExternalMass(data, X, SX);
        return;
    }
    // At the stations: S_Y X = J^T S (J X).
    const Eigen::MatrixXd& J = w.stationMap.jacobian;
    if (X.rows() != J.cols())
        throw std::invalid_argument("RopeModel::multiplyByNodeMass: X has " + std::to_string(X.rows()) +
                                    " rows for " + std::to_string(J.cols()) + " station coordinates");
    detail::RopeWorkspace<Dim>& ws = data.scratch();
    multiplyByStationJacobian(w.stationMap, X, ws.stationProductX);
    multiplyByExternalMass(data, ws.stationProductX, ws.stationProductSX);
    multiplyByStationJacobianTransposed(w.stationMap, ws.stationProductSX, SX);
}

template <int Dim>
void RopeModel<Dim>::multiplyByExternalMass(const RopeData<Dim>& data, const Eigen::Ref<const Eigen::MatrixXd>& X,
                                            Eigen::MatrixXd& SX) const {
    const int nx = numExternalCoordinates();
    if (X.rows() != nx)
        throw std::invalid_argument("RopeModel::multiplyByNodeMass: X has " + std::to_string(X.rows()) +
                                    " rows for " + std::to_string(nx) + " external coordinates");
    detail::RopeWorkspace<Dim>& ws = data.scratch();
    const int p = static_cast<int>(X.cols()), nk = kktSize_;
    SX.setZero(nx, p);
    ws.productColumns = p;
    if (p == 0) return;
    // Row-major copies of X and S X (each row's p columns contiguous, as in B), and the rows of X
    // that are zero (nodes that do not move along these directions: Ground, or bodies outside the
    // coupling), whose terms are skipped.
    std::vector<double>& Xr = ws.productX;
    std::vector<double>& SXr = ws.productSX;
    Xr.resize(static_cast<std::size_t>(nx) * p);
    SXr.assign(static_cast<std::size_t>(nx) * p, 0.0);
    std::vector<char>& live = ws.liveProductRow;
    live.assign(nx, 0);
    for (int c = 0; c < p; ++c)
        for (int i = 0; i < nx; ++i) {
            const double v = X(i, c);
            Xr[static_cast<std::size_t>(i) * p + c] = v;
            if (v != 0.0) live[i] = 1;
        }
    auto row = [p](std::vector<double>& m, int i) { return m.data() + static_cast<std::ptrdiff_t>(i) * p; };
    // Right-hand sides -[M_yx X; C_x X] (row-major), and M_xx X into S X.
    Eigen::VectorXd& B = ws.productBlock;
    B.setZero(static_cast<Eigen::Index>(nk) * p);
    // (The span terms from the lists buildChainOrder made, in its loops' order: each row sums its
    // terms in the same order as a loop over spans, coordinates a and b would.)
    const int ne = static_cast<int>(elementToRope_.size());
    for (int e = 0; e < ne; ++e) {
        int n = 0;
        const double* M = elementMass(data, e, n);
        const RowTerm* terms = massTimesExternalIntoKkt_.data();
        applyRowTerms<true>(terms + massTermSpanStart_[3 * e], terms + massTermSpanStart_[3 * e + 3], M, Xr.data(),
                            B.data(), p, live.data());
        terms = massTimesExternalIntoExternal_.data();
        applyRowTerms<false>(terms + massTermSpanStart_[3 * e + 1], terms + massTermSpanStart_[3 * e + 4], M,
                             Xr.data(), SXr.data(), p, live.data());
    }
    for (int i = 0; i < nx; ++i) {
        if (!live[i]) continue;
        const double* x = row(Xr, i);
        for (int at = ws.externalColumnStart[i]; at < ws.externalColumnStart[i + 1]; ++at)
            axpyRow<true>(ws.externalColumnValue[at], x,
                          B.data() + static_cast<std::ptrdiff_t>(kktRowPos_[ws.externalColumnRow[at]]) * p, p);
    }
    if (nk > 0) ws.kktLu.solve(B.data(), p);
    // + M_xy Y + C_x^T Mu
    for (int e = 0; e < ne; ++e) {
        const RowTerm* terms = massTimesKktIntoExternal_.data();
        int n = 0;
        applyRowTerms<false>(terms + massTermSpanStart_[3 * e + 2], terms + massTermSpanStart_[3 * e + 5],
                             elementMass(data, e, n), B.data(), SXr.data(), p, nullptr);
    }
    for (int i = 0; i < nx; ++i) {
        double* sx = row(SXr, i);
        for (int at = ws.externalColumnStart[i]; at < ws.externalColumnStart[i + 1]; ++at)
            axpyRow<false>(ws.externalColumnValue[at],
                           B.data() + static_cast<std::ptrdiff_t>(kktRowPos_[ws.externalColumnRow[at]]) * p, sx, p);
    }
    // Stored rope: its mass block at the drum's coordinates (StoredRope).
    for (const detail::StoredRopeTerms<Dim>& t : ws.storedRope)
        for (int a = 0; a < t.count; ++a) {
            double* sx = row(SXr, t.cols[a]);
            for (int b = 0; b < t.count; ++b) {
                const double* xb = row(Xr, t.cols[b]);
                for (int c = 0; c < p; ++c) sx[c] += t.mass(a, b) * xb[c];
            }
        }
    for (int c = 0; c < p; ++c)
        for (int i = 0; i < nx; ++i) SX(i, c) = SXr[static_cast<std::size_t>(i) * p + c];
}

template <int Dim>
void RopeModel<Dim>::modalAccelerations(const RopeData<Dim>& data, const Eigen::VectorXd& nodeAccelerations,
                                        Eigen::VectorXd& qmddot) const {
    if (numModal_ == 0) {
        qmddot.resize(0);
        return;
    }
    const detail::RopeWorkspace<Dim>& w = data.ws();
    if (w.nodeMassFormed) {
        qmddot = w.modalFree;
        qmddot.noalias() -= w.modalCoupling * nodeAccelerations;
        return;
    }
    // Without the formed columns: qddot_m = modalFree + (the solution for -[M_yx xddot; C_x xddot]).
    multiplyByNodeMass(data, nodeAccelerations, data.scratch().modalProduct);  // leaves the solution in productBlock
    const int nx = numExternalCoordinates();
    qmddot.resize(numModal_);
    for (int m = 0; m < numModal_; ++m) qmddot[m] = w.modalFree[m] + w.productBlock[kktPos_[nx + m]];
}

template <int Dim>
void RopeModel<Dim>::modalAccelerationsFromLastProduct(const RopeData<Dim>& data, const Eigen::VectorXd& columnWeights,
                                                       Eigen::VectorXd& qmddot) const {
    const detail::RopeWorkspace<Dim>& w = data.ws();
    const int p = w.productColumns;
    if (p < 0 || columnWeights.size() != p)
        throw std::invalid_argument("RopeModel::modalAccelerationsFromLastProduct: " +
                                    std::to_string(columnWeights.size()) + " weights for " + std::to_string(p) +
                                    " columns of the last multiplyByNodeMass (-1: none since computeDynamics)");
    qmddot = w.modalFree;
    if (numModal_ == 0 || kktSize_ == 0) return;
    const int nx = numExternalCoordinates();
    for (int m = 0; m < numModal_; ++m) {
        const double* y = w.productBlock.data() + static_cast<std::ptrdiff_t>(kktPos_[nx + m]) * p;
        double sum = 0;
        for (int c = 0; c < p; ++c) sum += y[c] * columnWeights[c];
        qmddot[m] += sum;
    }
}

template <int Dim>
void RopeModel<Dim>::recoverInertialStrain(RopeData<Dim>& data, const Eigen::VectorXd& nodeAccelerations,
                                           const Eigen::VectorXd& qmddot) const {
    if (numCondensed_ == 0) return;
    const int nx = numExternalCoordinates(), nw = nx + numModal_, nd = numDependent();
    const int nqc = numCondensed_, nc = numSliding_;
    detail::RopeWorkspace<Dim>& ws = data.ws();
    Eigen::VectorXd& zdd = ws.zddot;
    const int nz = nw + nd + numFixed_;
    zdd.setZero(nz);
    if (ws.stationMode) {  // xddot = J Yddot + b
        multiplyByStationJacobian(ws.stationMap, nodeAccelerations, ws.stationAccelerations);
        zdd.head(nx) = ws.stationAccelerations + ws.stationMap.bias;
    }
    else
        zdd.head(nx) = nodeAccelerations;
    zdd.segment(nx, numModal_) = qmddot;
    // ddot = -C_d^-1 (C_w wddot + bias)
    ws.rowScratch = ws.bias;
    for (const detail::JacobianEntry& e : ws.jacobian)
        if (e.col < nw) ws.rowScratch[e.row] += e.value * zdd[e.col];
    solveDependent(data, ws.dependentLu, ws.rowScratch, ws.dependentAccelerations);
    zdd.segment(nw, nd) = -ws.dependentAccelerations;
    // (M zddot) at the condensed amplitudes and the Sliding material coordinates, span by span.
    Eigen::VectorXd& Mzdd = ws.massTimesAcceleration;
    Mzdd.setZero(nz);
    for (int e = 0; e < static_cast<int>(elementToRope_.size()); ++e) {
        const auto& map = elementToRope_[e];
        int n = 0;
        const double* M = elementMass(data, e, n);
        for (int a = 0; a < n; ++a) {
            if (map[a] < nw || map[a] >= nw + nqc + nc) continue;
            double sum = 0;
            for (int b = 0; b < n; ++b) sum += M[a + static_cast<std::ptrdiff_t>(n) * b] * zdd[map[b]];
            const int extraLocal = elementExtraLocal_[e];  // s1 = s_j + l_j
            if (extraLocal >= 0) sum += M[a + static_cast<std::ptrdiff_t>(n) * extraLocal] * zdd[elementExtra_[e]];
            Mzdd[map[a]] += sum;
        }
    }
    const double invEA = 1.0 / properties().axialStiffness;
    Eigen::VectorXd& load = ws.inertialLoad;
    load.setZero(nd);
    for (int r = 0; r < nqc; ++r) load[r] = invEA * (Mzdd[nw + r] - ws.velocityForcesZ[nw + r]);
    for (int k = 0; k < nc; ++k)
        load[nqc + nc + k] = invEA * (Mzdd[nw + nqc + k] - ws.velocityForcesZ[nw + nqc + k]);
    solveDependent(data, ws.dependentLu, load, data.inertialCorrection);
    data.inertialCorrection *= -1.0;
    data.inertialCorrectionValid = true;  // mutation-site: mode-accel
}

template <int Dim>
void RopeModel<Dim>::recoveredSpanCoordinates(int j, const NodeMatrix& nodes, const Eigen::VectorXd& qm,
                                              const RopeData<Dim>& data, Eigen::VectorXd& q) const {
    spanCoordinates(j, nodes, qm, data, q);
    addInertialCorrection(j, data, q);
}

template <int Dim>
void RopeModel<Dim>::recoveredSpanCoordinatesFromExternal(int j, const Eigen::VectorXd& x, const Eigen::VectorXd& qm,
                                                          const RopeData<Dim>& data, Eigen::VectorXd& q) const {
    spanCoordinatesFromExternal(j, x, qm, data, q);
    addInertialCorrection(j, data, q);
}

template <int Dim>
void RopeModel<Dim>::addInertialCorrection(int j, const RopeData<Dim>& data, Eigen::VectorXd& q) const {
    if (numCondensed_ == 0 || !data.inertialCorrectionValid) return;
    const auto& sp = elements_->spans[j];
    if (isCondensed(j))
        q.segment(2 * Dim, sp.numCondensedModes()) +=
            data.inertialCorrection.segment(condensedOffset_[j], sp.numCondensedModes());
    if (slidingIndex_[j] >= 0) q[sp.s1Index()] += data.inertialCorrection[numCondensed_ + slidingIndex_[j]];
    if (slidingIndex_[j + 1] >= 0) q[sp.s2Index()] += data.inertialCorrection[numCondensed_ + slidingIndex_[j + 1]];
}

template <int Dim>
double RopeModel<Dim>::constraintError(const RopeData<Dim>& data, int k) const {
    if (!elements_->kernels.empty())
        return properties().axialStiffness * (data.ws().condensation[k - 1].value[elements_->kernels[k - 1].endStrain(SpanEnd::Second)] -
                                              data.ws().condensation[k].value[elements_->kernels[k].endStrain(SpanEnd::First)]);
    return properties().axialStiffness * (data.ws().secondEnd[k - 1].strain - data.ws().firstEnd[k].strain);
}

template <int Dim>
RopeData<Dim>::Scratch::Scratch() : p_(std::make_unique<detail::RopeWorkspace<Dim>>()) {}
template <int Dim>
RopeData<Dim>::Scratch::~Scratch() = default;
template <int Dim>
RopeData<Dim>::Scratch::Scratch(const Scratch& o) : p_(std::make_unique<detail::RopeWorkspace<Dim>>(*o.p_)) {}
template <int Dim>
typename RopeData<Dim>::Scratch& RopeData<Dim>::Scratch::operator=(const Scratch& o) {
    if (this != &o) p_ = std::make_unique<detail::RopeWorkspace<Dim>>(*o.p_);
    return *this;
}
template <int Dim>
RopeData<Dim>::Scratch::Scratch(Scratch&&) noexcept = default;
template <int Dim>
typename RopeData<Dim>::Scratch& RopeData<Dim>::Scratch::operator=(Scratch&&) noexcept = default;
template <int Dim>
RopeData<Dim>::RopeData() = default;
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
const Eigen::MatrixXd& RopeData<Dim>::reducedMass() const {
    detail::RopeWorkspace<Dim>& w = *workspace_;  // computed on demand (the workspace is scratch)
    if (!w.reducedValid && w.model) w.model->assembleReduced(const_cast<RopeData<Dim>&>(*this));
    return w.Mbar;
}
template <int Dim>
const Eigen::VectorXd& RopeData<Dim>::reducedForce() const {
    reducedMass();
    return ws().Qbar;
}

template <int Dim>
void RopeModel<Dim>::assembleReduced(RopeData<Dim>& data) const {
    // The dense route of the reduced equations (as computeDynamics did before the chain solve):
    // Gd = -C_d^-1 C_w, Mbar = G^T Mz G = M_ww + M_wd Gd + Gd^T M_dw + Gd^T M_dd Gd,
    // Qbar = G^T (Qz - Mz c) = Q_w - M_wd c_d + Gd^T (Q_d - M_dd c_d).
    detail::RopeWorkspace<Dim>& ws = data.ws();
    const int nw = numExternalCoordinates() + numModal_, nd = numDependent();
    const int nz = nw + nd + numFixed_;
    ws.Mz.setZero(nz, nz);
    for (int e = 0; e < static_cast<int>(elementToRope_.size()); ++e) {
        const auto& map = elementToRope_[e];
        int n = 0;
        const double* M = elementMass(data, e, n);
        int ta[2], tb[2];
        auto targets = [&](int a, int* t) {
            t[0] = map[a];
            if (a != elementExtraLocal_[e]) return 1;
            t[1] = elementExtra_[e];
            return 2;
        };
        for (int a = 0; a < n; ++a)
            for (int b = 0; b < n; ++b)
                for (int ia = 0, na = targets(a, ta); ia < na; ++ia)
                    for (int ib = 0, nb = targets(b, tb); ib < nb; ++ib)
                        ws.Mz(ta[ia], tb[ib]) += M[a + static_cast<std::ptrdiff_t>(n) * b];
    }
    ws.Mbar = ws.Mz.topLeftCorner(nw, nw);
    ws.Qbar = ws.Qz.head(nw);
    if (nd > 0) {
        ws.Cw.setZero(nd, nw);
        ws.Cd.setZero(nd, nd);
        for (const detail::JacobianEntry& e : ws.jacobian)
            (e.col < nw ? ws.Cw(e.row, e.col) : ws.Cd(e.row, e.col - nw)) += e.value;
        ws.constraintLu.compute(ws.Cd);
        ws.Gd = ws.constraintLu.solve(ws.Cw);
        ws.Gd *= -1.0;
        const auto Mwd = ws.Mz.block(0, nw, nw, nd);
        const auto Mdd = ws.Mz.block(nw, nw, nd, nd);
        ws.MwdGd.noalias() = Mwd * ws.Gd;
        ws.Mbar += ws.MwdGd;
        ws.Mbar += ws.MwdGd.transpose();
        ws.MddGd.noalias() = Mdd * ws.Gd;
        ws.Mbar.noalias() += ws.Gd.transpose() * ws.MddGd;
        ws.Qbar.noalias() -= Mwd * ws.cd;
        ws.Qd = ws.Qz.segment(nw, nd);
        ws.Qd.noalias() -= Mdd * ws.cd;
        ws.Qbar.noalias() += ws.Gd.transpose() * ws.Qd;
    }
    if (ws.stationMode) {
        // w = [x, qm] = G [Y, qm] + [b, 0] with G = diag(J, I): Mbar_Y = G^T Mbar G,
        // Qbar_Y = G^T (Qbar - Mbar [b; 0]); J's products over its row bands.
        const WrapStationMapData& map = ws.stationMap;
        const int nx = numExternalCoordinates(), nY = static_cast<int>(map.jacobian.cols()), nm = numModal_;
        ws.Qbar.noalias() -= ws.Mbar.leftCols(nx) * map.bias;
        multiplyByStationJacobianTransposed(map, ws.Qbar.head(nx), ws.stationForce);
        ws.stationReducedQ.resize(nY + nm);
        ws.stationReducedQ << ws.stationForce, ws.Qbar.tail(nm);
        ws.Qbar = ws.stationReducedQ;
        // Mbar G = [Mbar_:x J, Mbar_:m], then G^T (Mbar G) = [J^T (Mbar G)_x; (Mbar G)_m].
        multiplyStationJacobianFromLeft(ws.Mbar.leftCols(nx), map, ws.stationScratch);
        ws.stationReducedMG.resize(nx + nm, nY + nm);
        ws.stationReducedMG.leftCols(nY) = ws.stationScratch;
        ws.stationReducedMG.rightCols(nm) = ws.Mbar.rightCols(nm);
        multiplyByStationJacobianTransposed(map, ws.stationReducedMG.topRows(nx), ws.stationProductSX);
        ws.Mbar.resize(nY + nm, nY + nm);
        ws.Mbar.topRows(nY) = ws.stationProductSX;
        ws.Mbar.bottomRows(nm) = ws.stationReducedMG.bottomRows(nm);
    }
    ws.reducedValid = true;
}
template <int Dim>
const Eigen::VectorXd& RopeData<Dim>::spanCoordinates(int span) const { return ws().spanQ[span]; }

template <int Dim>
const Eigen::VectorXd& RopeData<Dim>::spanRates(int span) const { return ws().spanQdot[span]; }

template struct RopeData<2>;
template struct RopeData<3>;
template class RopeModel<2>;
template class RopeModel<3>;

}  // namespace SimbodyReeving
