// ReevingSubsystem::Guts: traction sheaves (NodeKind::TractionSheave). Stick is a Driven node
// whose offset is state; slip makes the node MaterialNode::Slipping with the capstan ratio of the
// slip's direction; the transitions are events; the friction work is a Z entry. Written once for
// planar (RopeModel<2>) and spatial (RopeModel<3>) ropes: Guts::withRope and tractionPhaseModel.

#include "ReevingSubsystemGuts.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <string>
#include <type_traits>
#include <vector>

using SimTK::MobilizedBody;
using SimTK::Real;
using SimTK::Stage;
using SimTK::State;
using SimTK::SubsystemIndex;
using SimTK::System;
using SimTK::Value;

namespace SimbodyReeving {

using namespace detail;

const TractionStates& ReevingSubsystem::Guts::tractionStates(const State& s) const {
    return Value<TractionStates>::downcast(getDiscreteVariable(s, tractionVariable_)).get();
}

TractionStates& ReevingSubsystem::Guts::updTractionStates(State& s) const {
    return Value<TractionStates>::updDowncast(updDiscreteVariable(s, tractionVariable_)).upd();
}

double ReevingSubsystem::Guts::tractionWrapAngle(const State& s, const RopeRecord& r,
                                                 const RopeRecord::DrivenNode& d) const {
    if (!d.geometricWrap) return d.wrapAngle;
    // l / R wrapped (in a spatial rope the groove-plane angle between the 3D tangent points), the
    // chords' turning angle at a point sheave: the angle the slip law uses.
    return withRope(r, positionCache(s).ropes[r.index],
                    [&](const auto& model, const auto& data) { return model.wrapAngle(data, d.node); });
}

double ReevingSubsystem::Guts::tractionLimit(const State& s, const RopeRecord& r, const RopeRecord::DrivenNode& d) const {
    return std::exp(d.frictionCoefficient * tractionWrapAngle(s, r, d));  // mutation-site: capstan-exponent
}

namespace {

// Traction sheave d's entry of its rope's phase key (RopeRecord::TractionPhaseModel): 0 in stick
// and for TractionSlip::RopeMomentum (Driven by Y), +-1 (the slip's direction) with the geometry's
// wrap angle, else kappa = P_{k-1} / P_k: the tight side is the one the rope slides towards.
double phaseKeyEntry(const RopeRecord::DrivenNode& d, const TractionNodeState& t) {
    if (t.mode == TractionMode::Stick || d.momentumSlip) return 0.0;
    if (d.geometricWrap) return t.mode == TractionMode::SlipTowardStart ? 1.0 : -1.0;
    const double limit = std::exp(d.frictionCoefficient * d.wrapAngle);  // mutation-site: capstan-exponent
    return t.mode == TractionMode::SlipTowardStart ? limit : 1.0 / limit;
}

}  // namespace

template <int Dim>
const RopeModel<Dim>& ReevingSubsystem::Guts::tractionPhaseModel(
    const State& s, const RopeRecord& r, const std::shared_ptr<const RopeModel<Dim>>& base,
    std::vector<RopeRecord::TractionPhaseModel<Dim>>& models) const {
    if (r.numTraction == 0) return *base;
    const std::vector<TractionNodeState>& ts = tractionStates(s).ropes[r.index];
    bool anySlip = false;
    for (const RopeRecord::DrivenNode& d : r.driven)
        if (d.traction && phaseKeyEntry(d, ts[d.tractionIndex]) != 0) anySlip = true;
    if (!anySlip) return *base;
    // Compared entry by entry (no key formed: no allocation per evaluation).
    for (const RopeRecord::TractionPhaseModel<Dim>& m : models) {
        if (m.base != base) continue;
        bool same = true;
        for (const RopeRecord::DrivenNode& d : r.driven)
            if (d.traction && m.key[d.tractionIndex] != phaseKeyEntry(d, ts[d.tractionIndex])) same = false;
        if (same) return *m.model;
    }
    std::vector<double> key(r.numTraction, 0.0);
    for (const RopeRecord::DrivenNode& d : r.driven)
        if (d.traction) key[d.tractionIndex] = phaseKeyEntry(d, ts[d.tractionIndex]);
    std::vector<MaterialNode> kinds = r.materialKinds;
    for (const RopeRecord::DrivenNode& d : r.driven)
        if (d.traction && key[d.tractionIndex] != 0) kinds[d.node] = MaterialNode::Slipping;
    std::vector<SpanModel<Dim>> spans;
    for (int j = 0; j < r.numSpans(); ++j) spans.push_back(base->span(j));  // their reference frames too
    auto model = std::make_shared<RopeModel<Dim>>(std::move(spans), r.spec.unstretchedLength, kinds, r.wraps);
    for (const RopeRecord::DrivenNode& d : r.driven) {
        if (!d.traction || key[d.tractionIndex] == 0) continue;
        if (d.geometricWrap)
            // mutation-site: capstan-exponent
            model->setSlipLaw(d.node, 1.0, key[d.tractionIndex] * d.frictionCoefficient);
        else
            model->setSlipRatio(d.node, key[d.tractionIndex]);
    }
    r.addStoredRope(*model);
    model->setStationaryNodes(r.stationaryNodes());
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

double ReevingSubsystem::Guts::slipRate(const State& s, const RopeRecord& r, const RopeRecord::DrivenNode& d) const {
    const RopeCache& c = positionCache(s).ropes[r.index];
    if (tractionStates(s).ropes[r.index][d.tractionIndex].mode == TractionMode::Stick) return 0;
    if (d.momentumSlip) {  // v - g'(theta) thetadot: the rope over the groove's top
        const DrivenAngleSite site = angleSite(s, r, d);
        return c.slipRates[d.tractionIndex] - d.law.materialRate(d.angle.angle(site), d.angle.rate(site));
    }
    // The groove's surface where the rope arrives: g'(theta) thetadot, plus sigma R phi_in-dot on a
    // wrapped sheave (RopeModel::surfaceRate).
    return withRope(r, c, [&](const auto& model, const auto& data) {
        return data.materialRates[d.node] - model.surfaceRate(data, d.node);
    });
}

void ReevingSubsystem::Guts::startMomentumSlip(State& s, const RopeRecord& r, const RopeRecord::DrivenNode& d,
                                               const TractionNodeState& stick) const {
    // Y and Ydot from the stick phase's s = sStick + g(theta): s_k and its rate continuous.
    const DrivenAngleSite site = angleSite(s, r, d);
    const double theta = d.angle.angle(site), thetaDot = d.angle.rate(site);
    SimTK::Vector& z = updZ(s);
    z[r.slipZOffset + 2 * d.tractionIndex] = d.law.materialCoordinate(stick.sStick, theta);
    z[r.slipZOffset + 2 * d.tractionIndex + 1] = d.law.materialRate(theta, thetaDot);
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

double ReevingSubsystem::Guts::maxFriction(const RopeRecord& r, const RopeRecord::DrivenNode& d, double tight,
                                           const State& s) const {
    // In stick the rope moves with the groove: v = g'(theta) thetadot.
    const DrivenAngleSite site = angleSite(s, r, d);
    const double v = d.law.materialRate(d.angle.angle(site), d.angle.rate(site));
    // mutation-site: rhoa-v2
    const double pressing = std::max(tight - r.spec.properties.massPerLength * v * v, 0.0);
    // mutation-site: capstan-exponent
    return pressing * (1.0 - std::exp(-d.frictionCoefficient * tractionWrapAngle(s, r, d)));
}

double ReevingSubsystem::Guts::stickFriction(const State& s, const RopeRecord& r, const RopeRecord::DrivenNode& d) const {
    const RopeCache& c = positionCache(s).ropes[r.index];
    const auto [pa, pb] = nodeTotalForces(s, r, d.node);
    const int external = r.drivenExternal(r.drivenIndex(d.node));
    // ropeReaction = h - S xddot, so (S xddot)_Y = h_Y - reaction_Y.
    const double h = withRope(r, c, [&](const auto&, const auto& data) { return data.nodeForce[external]; });
    const double sxdd = h - ropeReaction(s, r, c)[external];
    return pa - pb - sxdd;
}

ReevingSubsystem::Guts::MomentumSlip ReevingSubsystem::Guts::momentumSlip(const State& s, const RopeRecord& r,
                                                                          const RopeRecord::DrivenNode& d) const {
    const RopeCache& c = positionCache(s).ropes[r.index];
    const TractionNodeState& t = tractionStates(s).ropes[r.index][d.tractionIndex];
    MomentumSlip m;
    const auto [pa, pb] = nodeTotalForces(s, r, d.node);
    m.speed = c.slipRates[d.tractionIndex];
    const double sigma = t.mode == TractionMode::SlipTowardStart ? 1.0 : -1.0;
    // mutation-site: tight-side
    const double tight = sigma > 0 ? pa : pb, rhoA = r.spec.properties.massPerLength;
    // The groove's normal load per unit angle is P - rhoA v^2: none where the rope lifts off.
    // mutation-site: rhoa-v2
    const double pressing = std::max(tight - rhoA * m.speed * m.speed, 0.0);
    // mutation-site: capstan-exponent
    m.friction = sigma * pressing * (1.0 - std::exp(-d.frictionCoefficient * tractionWrapAngle(s, r, d)));
    m.drive = pa - pb - m.friction;
    m.external = r.drivenExternal(r.drivenIndex(d.node));
    m.correction = pa - pb - withRope(r, c, [&](const auto&, const auto& data) { return data.nodeForce[m.external]; });
    const DrivenAngleSite site = angleSite(s, r, d);
    m.slipRate = m.speed - d.law.materialRate(d.angle.angle(site), d.angle.rate(site));
    m.workRate = m.friction * m.slipRate - m.correction * m.speed;
    return m;
}

// Y is a coordinate of the rope alone (no body): with F the Y indices of a rope and g_F their
// momentum balances' right sides, S' = S - S_xF S_FF^-1 S_Fx and h' = h - S_xF S_FF^-1 g_F on the
// other coordinates (rows and columns F zero), so the coupled solve sees the rope with Y moving as
// its balance says.
void ReevingSubsystem::Guts::condenseMomentumSlips(const State& s, PositionCache& pc, SimTK::Vector& mobilityForces,
                                                   SimTK::Vector_<SimTK::SpatialVec>& bodyForces) const {
    CouplingWorkspace& ws = pc.coupling;
    ws.freeSlips.clear();
    for (const RopeRecord& r : ropes) {
        pc.ropes[r.index].condensed = false;
        for (const RopeRecord::DrivenNode& d : r.driven) {
            if (!d.traction || !inMomentumSlip(s, r, d)) continue;
            const MomentumSlip ms = momentumSlip(s, r, d);
            ws.freeSlips.push_back({r.index, static_cast<int>(&d - r.driven.data()), ms.external, ms.drive, ms.workRate});
            // The friction's reaction on the groove, sigma F g'(theta), on the angle's row.
            const DrivenAngleSite site = angleSite(s, r, d);
            DrivenAngleRow row;
            d.angle.row(site, row);
            row.addGeneralizedForce(ms.friction * d.law.slope(d.angle.angle(site)), mobilityForces, bodyForces);
        }
    }
    for (const RopeRecord& r : ropes) {
        ws.freeIndex.clear();
        for (const CouplingWorkspace::FreeSlip& f : ws.freeSlips)
            if (f.rope == r.index) ws.freeIndex.push_back(f.external);
        if (ws.freeIndex.empty()) continue;
        RopeCache& c = pc.ropes[r.index];
        const int nx = r.numExternal(), nf = static_cast<int>(ws.freeIndex.size());
        const Eigen::MatrixXd& S = withRope(r, c, [&](const auto& model, auto& data) -> const Eigen::MatrixXd& {
            if (data.nodeMass.size() == 0)
                model.multiplyByNodeMass(data, Eigen::MatrixXd::Identity(nx, nx), data.nodeMass);
            return data.nodeMass;
        });
        ws.freeSxF.resize(nx, nf);
        ws.freeSFF.resize(nf, nf);
        ws.freeDrive.resize(nf);
        int a = 0;
        for (const CouplingWorkspace::FreeSlip& f : ws.freeSlips)
            if (f.rope == r.index) ws.freeDrive[a++] = f.drive;
        for (a = 0; a < nf; ++a) {
            ws.freeSxF.col(a) = S.col(ws.freeIndex[a]);
            for (int b = 0; b < nf; ++b) ws.freeSFF(a, b) = S(ws.freeIndex[a], ws.freeIndex[b]);
        }
        for (a = 0; a < nf; ++a) ws.freeSxF.row(ws.freeIndex[a]).setZero();  // the others' rows only
        ws.freeLdlt.compute(ws.freeSFF);
        ws.freeSolve = ws.freeLdlt.solve(ws.freeSxF.transpose());
        c.condensedMass = S;
        c.condensedMass.noalias() -= ws.freeSxF * ws.freeSolve;
        ws.freeAcceleration = ws.freeLdlt.solve(ws.freeDrive);
        c.condensedForce = withRope(r, c, [](const auto&, const auto& data) -> const Eigen::VectorXd& { return data.nodeForce; });
        c.condensedForce.noalias() -= ws.freeSxF * ws.freeAcceleration;
        for (a = 0; a < nf; ++a) {
            c.condensedMass.row(ws.freeIndex[a]).setZero();
            c.condensedMass.col(ws.freeIndex[a]).setZero();
            c.condensedForce[ws.freeIndex[a]] = 0;
        }
        c.condensed = true;
    }
}

void ReevingSubsystem::Guts::recoverMomentumSlips(PositionCache& pc, int rope) const {
    CouplingWorkspace& ws = pc.coupling;
    RopeCache& c = pc.ropes[rope];
    ws.freeIndex.clear();
    for (const CouplingWorkspace::FreeSlip& f : ws.freeSlips)
        if (f.rope == rope) ws.freeIndex.push_back(f.external);
    const int nf = static_cast<int>(ws.freeIndex.size());
    const Eigen::MatrixXd& S =
        withRope(ropes[rope], c, [](const auto&, const auto& data) -> const Eigen::MatrixXd& { return data.nodeMass; });
    ws.freeDrive.resize(nf);
    ws.freeSFF.resize(nf, nf);
    int a = 0;
    for (const CouplingWorkspace::FreeSlip& f : ws.freeSlips)
        if (f.rope == rope) ws.freeDrive[a++] = f.drive;
    for (a = 0; a < nf; ++a) c.externalAccelerations[ws.freeIndex[a]] = 0;
    for (a = 0; a < nf; ++a) {
        ws.freeDrive[a] -= S.row(ws.freeIndex[a]).dot(c.externalAccelerations);
        for (int b = 0; b < nf; ++b) ws.freeSFF(a, b) = S(ws.freeIndex[a], ws.freeIndex[b]);
    }
    ws.freeLdlt.compute(ws.freeSFF);
    ws.freeAcceleration = ws.freeLdlt.solve(ws.freeDrive);
    for (a = 0; a < nf; ++a) c.externalAccelerations[ws.freeIndex[a]] = ws.freeAcceleration[a];
}

double ReevingSubsystem::Guts::tractionWitness(const State& s, int rope, int driven) const {
    const RopeRecord& r = ropes[rope];
    const RopeRecord::DrivenNode& d = r.driven[driven];
    const TractionNodeState& t = tractionStates(s).ropes[rope][d.tractionIndex];
    if (t.mode == TractionMode::Stick && d.momentumSlip) {
        // The groove holds the rope with Phi = P_a - P_b - (S xddot)_Y (Stage::Dynamics: the coupled
        // solve's accelerations); it slips when |Phi| reaches F_max of the side it would slide to.
        const auto [pa, pb] = nodeTotalForces(s, r, d.node);
        const double phi = stickFriction(s, r, d);
        const double fa = maxFriction(r, d, pa, s), fb = maxFriction(r, d, pb, s);
        return std::min(fa - phi, fb + phi) + kTractionHysteresis * (std::abs(pa) + std::abs(pb));
    }
    if (t.mode == TractionMode::Stick) {
        const auto [pa, pb] = nodeAxialForces(s, r, d.node);
        const double scale = std::abs(pa) + std::abs(pb);
        if (!(std::max(pa, pb) > 0)) return scale + 1.0;  // both sides slack: no traction to lose
        // min(limit P_b - P_a, limit P_a - P_b) / limit: divided by the limit (>= 1), so that a large
        // e^(mu alpha) (4.4e13 at mu = 10) does not multiply the slack side's round-off (1e-9 N)
        // past the hysteresis; the sign, and so the event, is the same.
        const double limit = tractionLimit(s, r, d);
        return std::min(pb - pa / limit, pa - pb / limit) + kTractionHysteresis * scale;
    }
    const double v = slipRate(s, r, d);
    return (t.mode == TractionMode::SlipTowardStart ? v : -v) + kSlipRateHysteresis;
}

void ReevingSubsystem::Guts::changeTractionMode(State& s, int rope, int driven) const {
    getSystem().realize(s, Stage::Velocity);
    const RopeRecord& r = ropes[rope];
    const RopeRecord::DrivenNode& d = r.driven[driven];
    TractionNodeState next = tractionStates(s).ropes[rope][d.tractionIndex];
    if (next.mode == TractionMode::Stick && d.momentumSlip) {
        getSystem().realize(s, Stage::Dynamics);
        next.mode = stickFriction(s, r, d) > 0 ? TractionMode::SlipTowardStart : TractionMode::SlipTowardEnd;
        startMomentumSlip(s, r, d, next);
    } else if (next.mode == TractionMode::Stick) {
        const auto [pa, pb] = nodeAxialForces(s, r, d.node);
        const double limit = tractionLimit(s, r, d);
        next.mode = limit * pb - pa < limit * pa - pb ? TractionMode::SlipTowardStart : TractionMode::SlipTowardEnd;
    } else if (d.momentumSlip) {
        // s_k continuous: the stick offset takes over from Y (Y - g(theta)).
        next.sStick = d.law.offsetOf(getZ(s)[r.slipZOffset + 2 * d.tractionIndex], d.angle.angle(angleSite(s, r, d)));
        next.mode = TractionMode::Stick;
    } else {
        // s_k continuous: the surface coordinate where the rope arrives (sStick + g(theta),
        // plus sigma R phi_in on a wrapped sheave) moves onto s_k.
        next.sStick += withRope(r, positionCache(s).ropes[rope], [&](const auto& model, const auto& data) {
            return data.materialCoordinates[d.node] - model.surfaceCoordinate(data, d.node);
        });
        next.mode = TractionMode::Stick;
    }
    ++next.transitions;
    // Stick -> slip changes the rope's material rate at the node at once (the massless contact
    // point: the slip rate jumps to the one that keeps the capstan ratio), so the rope's kinetic
    // energy jumps; slip -> stick is continuous (the slip rate is zero there). Positions and the
    // potential energy are continuous. The jump is booked as friction work, so that
    // E(t) - E(0) + W_friction = W_drives holds through the transition.
    auto kinetic = [](const auto&, const auto& data) { return data.kineticEnergy; };
    const double before = withRope(r, positionCache(s).ropes[rope], kinetic);
    updTractionStates(s).ropes[rope][d.tractionIndex] = next;
    getSystem().realize(s, Stage::Velocity);
    const double after = withRope(r, positionCache(s).ropes[rope], kinetic);
    updZ(s)[r.tractionZOffset + d.tractionIndex] += before - after;
}

namespace {

/// Witness: ReevingSubsystem::Guts::tractionWitness of one traction sheave; when it falls through
/// zero, the sheave changes between stick and slip.
class TractionEvent : public SimTK::TriggeredEventHandler {
public:
    TractionEvent(const System& system, SubsystemIndex reeving, int rope, int driven, Stage stage)
        : SimTK::TriggeredEventHandler(stage), system_(system), reeving_(reeving), rope_(rope),
          driven_(driven) {
        getTriggerInfo().setTriggerOnRisingSignTransition(false);
        getTriggerInfo().setTriggerOnFallingSignTransition(true);
        getTriggerInfo().setRequiredLocalizationTimeWindow(1e-8);
    }
    Real getValue(const State& s) const override { return guts().tractionWitness(s, rope_, driven_); }
    void handleEvent(State& s, Real, bool& shouldTerminate) const override {
        shouldTerminate = false;
        guts().changeTractionMode(s, rope_, driven_);
    }

private:
    const ReevingSubsystem::Guts& guts() const {
        return dynamic_cast<const ReevingSubsystem::Guts&>(system_.getSubsystem(reeving_).getSubsystemGuts());
    }
    const System& system_;
    SubsystemIndex reeving_;
    int rope_, driven_;
};

const RopeRecord::DrivenNode& tractionAt(const RopeRecord& r, int node) {
    if (node < 0 || node >= r.numNodes())
        invalid("node index = " + std::to_string(node) + " is outside 0.." + std::to_string(r.numNodes() - 1));
    const int d = r.drivenIndex(node);
    if (d < 0 || !r.driven[d].traction)
        invalid("rope '" + r.spec.name + "' node " + std::to_string(node) + " is not a TractionSheave");
    return r.driven[d];
}

}  // namespace

void detail::installTractionHandler(System& system, SubsystemIndex reeving, int rope, int driven, bool momentum) {
    // A TractionSlip::RopeMomentum sheave's stick witness reads the coupled solve's accelerations.
    const Stage stage = momentum ? Stage::Dynamics : Stage::Velocity;
    system.addEventHandler(new TractionEvent(system, reeving, rope, driven, stage));  // the system owns it
}

// ---- public queries ---------------------------------------------------------------------------

TractionMode TractionSheaveHandle::getTractionMode(const State& s) const {
    const int rope = getRopeIndex(), node = getNodeIndex();
    const RopeRecord& r = ropeAt(guts(), rope);
    return guts().tractionStates(s).ropes[rope][tractionAt(r, node).tractionIndex].mode;
}

double TractionSheaveHandle::getSlipRate(const State& s) const {
    const int rope = getRopeIndex(), node = getNodeIndex();
    const RopeRecord& r = ropeAt(guts(), rope);
    const RopeRecord::DrivenNode& d = tractionAt(r, node);
    if (s.getSystemStage() < Stage::Velocity)
        throw std::logic_error("TractionSheaveHandle::getSlipRate: realize the state to Stage::Velocity first");
    return guts().slipRate(s, r, d);
}

double TractionSheaveHandle::getSlipDistance(const State& s) const {
    const int rope = getRopeIndex(), node = getNodeIndex();
    const RopeRecord& r = ropeAt(guts(), rope);
    const RopeRecord::DrivenNode& d = tractionAt(r, node);
    // The slip of the current phase (s_k off the surface where it arrives; 0 in stick) plus the
    // offset the stick phases so far have accumulated.
    const RopeCache& c = guts().positionCache(s).ropes[rope];
    if (guts().inMomentumSlip(s, r, d))  // Y over the groove's top, less the pin's turn
        return d.law.offsetOf(c.slipStates[d.tractionIndex], d.angle.angle(guts().angleSite(s, r, d))) - d.sRef;
    const double sStick = guts().tractionStates(s).ropes[rope][d.tractionIndex].sStick;
    return ReevingSubsystem::Guts::withRope(r, c, [&](const auto& model, const auto& data) {
               return data.materialCoordinates[node] - model.surfaceCoordinate(data, node);
           }) + sStick - d.sRef;
}

double TractionSheaveHandle::getTractionRatio(const State& s) const {
    const int rope = getRopeIndex(), node = getNodeIndex();
    const RopeRecord& r = ropeAt(guts(), rope);
    tractionAt(r, node);
    const auto [pa, pb] = guts().nodeAxialForces(s, r, node);
    return pb > 0 ? pa / pb : std::numeric_limits<double>::quiet_NaN();
}

double TractionSheaveHandle::getTractionLimit(const State& s) const {
    const int rope = getRopeIndex(), node = getNodeIndex();
    const RopeRecord& r = ropeAt(guts(), rope);
    const RopeRecord::DrivenNode& d = tractionAt(r, node);
    guts().positionCache(s);  // Stage::Position: the wrap angle is resolved
    return guts().tractionLimit(s, r, d);
}

double ReevingSubsystem::getWrapAngle(const State& s, int rope, int node) const {
    const RopeRecord& r = ropeAt(getGuts(), rope);
    if (node < 0 || node >= r.numNodes())
        invalid("node index = " + std::to_string(node) + " is outside 0.." + std::to_string(r.numNodes() - 1));
    const int driven = r.drivenIndex(node);
    if (driven >= 0 && r.driven[driven].traction) {  // the angle its capstan law uses
        getGuts().positionCache(s);
        return getGuts().tractionWrapAngle(s, r, r.driven[driven]);
    }
    if (node > 0 && node + 1 < r.numNodes() && r.wraps[node].radius > 0)
        return getArcLength(s, rope, node) / r.wraps[node].radius;
    if (r.planar && node > 0 && node + 1 < r.numNodes()) {
        const RopeCache& c = getGuts().positionCache(s).ropes[rope];  // a point sheave: its chords' angle
        return c.planarModel->wrapAngle(c.planar, node);
    }
    invalid("rope '" + r.spec.name + "' node " + std::to_string(node) +
            " is neither a TractionSheave, a wrapped sheave nor a sheave of a planar rope: it has no wrap angle");
}

double TractionSheaveHandle::getFrictionPower(const State& s) const {
    const int rope = getRopeIndex(), node = getNodeIndex();
    const double v = getSlipRate(s);
    const RopeRecord& r = ropeAt(guts(), rope);
    if (guts().inMomentumSlip(s, r, r.driven[r.drivenIndex(node)])) return guts().momentumSlip(s, r, r.driven[r.drivenIndex(node)]).workRate;
    if (v == 0) return 0;
    const auto [pa, pb] = guts().nodeAxialForces(s, ropeAt(guts(), rope), node);
    return (pa - pb) * v;
}

double TractionSheaveHandle::getFrictionWork(const State& s) const {
    const int rope = getRopeIndex(), node = getNodeIndex();
    const RopeRecord& r = ropeAt(guts(), rope);
    return guts().getZ(s)[r.tractionZOffset + tractionAt(r, node).tractionIndex];
}

double ReevingSubsystem::getTotalFrictionWork(const State& s) const {
    double w = 0;
    for (const RopeRecord& r : getGuts().ropes)
        for (int t = 0; t < r.numTraction; ++t) w += getGuts().getZ(s)[r.tractionZOffset + t];
    return w;
}

int TractionSheaveHandle::getNumTractionTransitions(const State& s) const {
    const int rope = getRopeIndex(), node = getNodeIndex();
    const RopeRecord& r = ropeAt(guts(), rope);
    return guts().tractionStates(s).ropes[rope][tractionAt(r, node).tractionIndex].transitions;
}

int ReevingSubsystem::updateTractionModes(State& s) const {
    const Guts& g = getGuts();
    g.getSystem().realize(s, Stage::Position);
    int changed = 0;
    for (const RopeRecord& r : g.ropes)
        for (const RopeRecord::DrivenNode& d : r.driven) {
            if (!d.traction) continue;
            TractionNodeState t = g.tractionStates(s).ropes[r.index][d.tractionIndex];
            if (t.mode != TractionMode::Stick) continue;
            const auto [pa, pb] = g.nodeAxialForces(s, r, d.node);
            if (!(std::max(pa, pb) > 0)) continue;
            const double limit = g.tractionLimit(s, r, d);
            if (pa > limit * pb) {
                t.mode = TractionMode::SlipTowardStart;
            } else if (pb > limit * pa) {
                t.mode = TractionMode::SlipTowardEnd;
            } else {
                continue;
            }
            ++t.transitions;
            if (d.momentumSlip) g.startMomentumSlip(s, r, d, t);
            g.updTractionStates(s).ropes[r.index][d.tractionIndex] = t;
            g.getSystem().realize(s, Stage::Position);
            ++changed;
        }
    return changed;
}

}  // namespace SimbodyReeving
