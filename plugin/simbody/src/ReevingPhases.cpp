// ReevingSubsystem::Guts: the ropes' phases (the discrete state TractionStates and the rope model
// of each phase its driven nodes ask for: DrivenRole's phase hooks), the forces at a node's span
// ends, and the queries over every driven node's phase (wrap angle, friction work, traction modes).
// Written once for planar (RopeModel<2>) and spatial (RopeModel<3>) ropes: Guts::withRope and
// tractionPhaseModel. No node kind here: each driven node's part is its DrivenRole's.

#include "ReevingSubsystemGuts.h"

#include <memory>
#include <string>
#include <type_traits>
#include <vector>

using SimTK::Stage;
using SimTK::State;
using SimTK::Value;

namespace SimbodyReeving {

using namespace detail;

const TractionStates& ReevingSubsystem::Guts::tractionStates(const State& s) const {
    return Value<TractionStates>::downcast(getDiscreteVariable(s, tractionVariable_)).get();
}

TractionStates& ReevingSubsystem::Guts::updTractionStates(State& s) const {
    return Value<TractionStates>::updDowncast(updDiscreteVariable(s, tractionVariable_)).upd();
}

template <int Dim>
const RopeModel<Dim>& ReevingSubsystem::Guts::tractionPhaseModel(
    const State& s, const RopeRecord& r, const std::shared_ptr<const RopeModel<Dim>>& base,
    std::vector<RopeRecord::TractionPhaseModel<Dim>>& models) const {
    if (r.numPhaseNodes == 0) return *base;
    const std::vector<TractionNodeState>& ts = tractionStates(s).ropes[r.index];
    bool anySlip = false;
    for (const RopeRecord::DrivenNode& d : r.driven)
        if (d.role.slipsInPhase(ts)) anySlip = true;
    if (!anySlip) return *base;
    // Compared entry by entry (no key formed: no allocation per evaluation).
    for (const RopeRecord::TractionPhaseModel<Dim>& m : models) {
        if (m.base != base) continue;
        bool same = true;
        for (const RopeRecord::DrivenNode& d : r.driven)
            if (!d.role.phaseKeyMatches(m.key, ts)) same = false;
        if (same) return *m.model;
    }
    std::vector<double> key(r.numPhaseNodes, 0.0);
    for (const RopeRecord::DrivenNode& d : r.driven) d.role.writePhaseKey(ts, key);
    // The phase's model is the stick model with each slipping node's law swapped
    // (RopeModel::withNodeLaw): the spans (their reference frames too), their kernels and the
    // groove arcs are shared with `base`, its stored rope and stationary nodes kept.
    RopeModel<Dim> phase = *base;
    for (const RopeRecord::DrivenNode& d : r.driven) {
        MaterialNode kind = r.materialKinds[d.node];
        d.role.phaseMaterialKind(key, kind);
        if (kind != phase.nodeKind(d.node)) phase = phase.withNodeLaw(d.node, kind);
        d.role.setPhaseLaw(key, phase, d.node);
    }
    auto model = std::make_shared<const RopeModel<Dim>>(std::move(phase));
    // Models derived from span frames that no state holds any more (a spatial rope's frames
    // changed): base held only by such entries.
    std::vector<bool> dead(models.size());
    for (std::size_t i = 0; i < models.size(); ++i) {
        long holders = 0;
        for (const RopeRecord::TractionPhaseModel<Dim>& o : models) holders += o.base == models[i].base ? 1 : 0;
        dead[i] = models[i].base.use_count() <= holders;
    }
    std::size_t kept = 0;
    for (std::size_t i = 0; i < models.size(); ++i) {
        if (dead[i]) continue;
        if (kept != i) models[kept] = std::move(models[i]);  // (a self-move would empty the key)
        ++kept;
    }
    models.resize(kept);
    models.push_back({base, std::move(key), std::move(model)});
    return *models.back().model;
}

template const RopeModel<2>& ReevingSubsystem::Guts::tractionPhaseModel<2>(
    const State&, const RopeRecord&, const std::shared_ptr<const RopeModel<2>>&,
    std::vector<RopeRecord::TractionPhaseModel<2>>&) const;
template const RopeModel<3>& ReevingSubsystem::Guts::tractionPhaseModel<3>(
    const State&, const RopeRecord&, const std::shared_ptr<const RopeModel<3>>&,
    std::vector<RopeRecord::TractionPhaseModel<3>>&) const;

const RopeModel<2>& ReevingSubsystem::Guts::planarModel(const State& s, const RopeRecord& r) const {
    return tractionPhaseModel<2>(s, r, r.planarModel, r.tractionModels);
}

std::pair<double, double> ReevingSubsystem::Guts::nodeAxialForces(const State& s, const RopeRecord& r, int k) const {
    return withRope(r, positionCache(s).ropes[r.index], [&](const auto& model, const auto& data) {
        constexpr int Dim = std::decay_t<decltype(model)>::Vec::RowsAtCompileTime;
        EndStrain<Dim> e;
        const Eigen::VectorXd& qa = data.spanCoordinates(k - 1);
        model.span(k - 1).endStrain(qa, Eigen::VectorXd::Zero(qa.size()), SpanEnd::Second, e);
        const double pa = r.spec.properties.axialStiffness * e.strain;
        const Eigen::VectorXd& qb = data.spanCoordinates(k);
        model.span(k).endStrain(qb, Eigen::VectorXd::Zero(qb.size()), SpanEnd::First, e);
        return std::pair<double, double>{pa, r.spec.properties.axialStiffness * e.strain};
    });
}

std::pair<double, double> ReevingSubsystem::Guts::nodeTotalForces(const State& s, const RopeRecord& r, int k) const {
    // EA (eps + c deps/dt) at the node's two span ends (Stage::Velocity): the rope's Kelvin-Voigt
    // damping (RopeProperties::axialRetardationTime c) included.
    const double EA = r.spec.properties.axialStiffness, tau = r.spec.properties.axialRetardationTime;
    return withRope(r, positionCache(s).ropes[r.index], [&](const auto& model, const auto& data) {
        constexpr int Dim = std::decay_t<decltype(model)>::Vec::RowsAtCompileTime;
        EndStrain<Dim> e;
        model.span(k - 1).endStrain(data.spanCoordinates(k - 1), data.spanRates(k - 1), SpanEnd::Second, e);
        const double pa = EA * (e.strain + tau * e.rate);
        model.span(k).endStrain(data.spanCoordinates(k), data.spanRates(k), SpanEnd::First, e);
        return std::pair<double, double>{pa, EA * (e.strain + tau * e.rate)};
    });
}

// ---- public queries ---------------------------------------------------------------------------

double ReevingSubsystem::getWrapAngle(const State& s, int rope, int node) const {
    const RopeRecord& r = ropeAt(getGuts(), rope);
    if (node < 0 || node >= r.numNodes())
        invalid("node index = " + std::to_string(node) + " is outside 0.." + std::to_string(r.numNodes() - 1));
    const int driven = r.drivenIndex(node);
    double alpha = 0;  // the angle its own law uses (a TractionSheave's capstan law)
    if (driven >= 0 && r.driven[driven].role.wrapAngle(r.drivenRun(getGuts(), driven), s, alpha)) return alpha;
    if (node > 0 && node + 1 < r.numNodes() && r.wraps[node].radius > 0)
        return getArcLength(s, rope, node) / r.wraps[node].radius;
    if (node > 0 && node + 1 < r.numNodes()) {  // a point sheave: its chords' angle
        const RopeCache& c = getGuts().positionCache(s).ropes[rope];
        return r.planar ? c.planarModel->wrapAngle(c.planar, node) : c.spatialModel->wrapAngle(c.spatial, node);
    }
    invalid("rope '" + r.spec.name + "' node " + std::to_string(node) + " is an end node: it has no wrap angle");
}

double ReevingSubsystem::getTotalFrictionWork(const State& s) const {
    double w = 0;
    for (const RopeRecord& r : getGuts().ropes)
        for (const RopeRecord::DrivenNode& d : r.driven) d.role.addFrictionWork(getGuts().getZ(s), w);
    return w;
}

int ReevingSubsystem::updateTractionModes(State& s) const {
    const Guts& g = getGuts();
    g.getSystem().realize(s, Stage::Position);
    int changed = 0;
    for (const RopeRecord& r : g.ropes)
        for (int d = 0; d < static_cast<int>(r.driven.size()); ++d) {
            if (!r.driven[d].role.startSlipOverLimit(r.drivenRun(g, d), s)) continue;
            g.getSystem().realize(s, Stage::Position);
            ++changed;
        }
    return changed;
}

}  // namespace SimbodyReeving
