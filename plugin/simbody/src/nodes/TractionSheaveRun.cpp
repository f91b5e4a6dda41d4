// NodeKind::TractionSheave at run time (TractionRole, nodes/DrivenRole.h). Stick is a Driven node
// whose offset is state; slip makes the node MaterialNode::Slipping with the capstan ratio of the
// slip's direction (TractionSlip::CapstanConstraint), or drives it by the state Y with the rope's
// momentum over the groove (TractionSlip::RopeMomentum); the transitions are events; the friction
// work is a Z entry. Written once for planar (RopeModel<2>) and spatial (RopeModel<3>) ropes:
// Guts::withRope.

#include "../ReevingSubsystemGuts.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

using SimTK::Real;
using SimTK::Stage;
using SimTK::State;
using SimTK::SubsystemIndex;
using SimTK::System;

namespace SimbodyReeving {

using namespace detail;

namespace {
using Guts = ReevingSubsystem::Guts;

const TractionNodeState& phaseOf(const DrivenRun& run, const State& s, int index) {
    return run.guts.tractionStates(s).ropes[run.rope.index][index];
}
}  // namespace

double TractionRole::wrapAngle(const DrivenRun& run, const State& s) const {
    if (!geometricWrap) return givenWrapAngle;
    // l / R wrapped (in a spatial rope the groove-plane angle between the 3D tangent points), the
    // chords' turning angle at a point sheave: the angle the slip law uses.
    return Guts::withRope(run.rope, run.guts.positionCache(s).ropes[run.rope.index],
                          [&](const auto& model, const auto& data) { return model.wrapAngle(data, run.node.node); });
}

double TractionRole::limit(const DrivenRun& run, const State& s) const {
    return std::exp(frictionCoefficient * wrapAngle(run, s));  // mutation-site: capstan-exponent
}

double TractionRole::phaseKeyEntry(const TractionNodeState& t) const {
    if (t.mode == TractionMode::Stick || momentum()) return 0.0;
    if (geometricWrap) return t.mode == TractionMode::SlipTowardStart ? 1.0 : -1.0;
    const double limit = std::exp(frictionCoefficient * givenWrapAngle);  // mutation-site: capstan-exponent
    return t.mode == TractionMode::SlipTowardStart ? limit : 1.0 / limit;
}

namespace {
template <int Dim>
void setSlipLawOf(const TractionRole& t, double frictionCoefficient, const std::vector<double>& key,
                  RopeModel<Dim>& model, int node) {
    if (key[t.index] == 0) return;
    if (t.geometricWrap)
        // mutation-site: capstan-exponent
        model.setSlipLaw(node, 1.0, key[t.index] * frictionCoefficient);
    else
        model.setSlipRatio(node, key[t.index]);
}
}  // namespace

void TractionRole::setPhaseLaw(const std::vector<double>& key, RopeModel<2>& model, int node) const {
    setSlipLawOf(*this, frictionCoefficient, key, model, node);
}
void TractionRole::setPhaseLaw(const std::vector<double>& key, RopeModel<3>& model, int node) const {
    setSlipLawOf(*this, frictionCoefficient, key, model, node);
}

bool TractionRole::inMomentumSlip(const DrivenRun& run, const State& s) const {
    return momentum() && phaseOf(run, s, index).mode != TractionMode::Stick;
}

void TractionRole::materialCoordinate(const DrivenRun& run, const State& s, double theta, double thetaDot, bool rates,
                                      double& sk, double& skDot) const {
    // The stick offset is state (in slip the entry is the groove's coordinate, which no span
    // reads); with TractionSlip::RopeMomentum in slip it is the state Y.
    const TractionNodeState& t = phaseOf(run, s, index);
    if (momentum() && t.mode != TractionMode::Stick) {
        const int zi = slipStateZ();
        sk = run.guts.getZ(s)[zi];
        if (rates) skDot = run.guts.getZ(s)[zi + 1];
        return;
    }
    sk = run.node.law.materialCoordinate(t.sStick, theta);
    if (rates) skDot = run.node.law.materialRate(theta, thetaDot);
}

double TractionRole::slipRate(const DrivenRun& run, const State& s) const {
    const RopeRecord& r = run.rope;
    const DrivenNode& d = run.node;
    const RopeCache& c = run.guts.positionCache(s).ropes[r.index];
    if (phaseOf(run, s, index).mode == TractionMode::Stick) return 0;
    if (momentum()) {  // v - g'(theta) thetadot: the rope over the groove's top
        const DrivenAngleSite site = run.guts.angleSite(s, r, d);
        return c.drivenZRates[run.driven] - d.law.materialRate(d.angle.angle(site), d.angle.rate(site));
    }
    // The groove's surface where the rope arrives: g'(theta) thetadot, plus sigma R phi_in-dot on a
    // wrapped sheave (RopeModel::surfaceRate).
    return Guts::withRope(r, c, [&](const auto& model, const auto& data) {
        return data.materialRates[d.node] - model.surfaceRate(data, d.node);
    });
}

void TractionRole::startMomentumSlip(const DrivenRun& run, State& s, const TractionNodeState& stick) const {
    // Y and Ydot from the stick phase's s = sStick + g(theta): s_k and its rate continuous.
    const DrivenNode& d = run.node;
    const DrivenAngleSite site = run.guts.angleSite(s, run.rope, d);
    const double theta = d.angle.angle(site), thetaDot = d.angle.rate(site);
    SimTK::Vector& z = run.guts.updZ(s);
    z[slipStateZ()] = d.law.materialCoordinate(stick.sStick, theta);
    z[slipStateZ() + 1] = d.law.materialRate(theta, thetaDot);
}

double TractionRole::maxFriction(const DrivenRun& run, double tight, const State& s) const {
    // In stick the rope moves with the groove: v = g'(theta) thetadot.
    const DrivenNode& d = run.node;
    const DrivenAngleSite site = run.guts.angleSite(s, run.rope, d);
    const double v = d.law.materialRate(d.angle.angle(site), d.angle.rate(site));
    // mutation-site: rhoa-v2
    const double pressing = std::max(tight - run.rope.spec.properties.massPerLength * v * v, 0.0);
    // mutation-site: capstan-exponent
    return pressing * (1.0 - std::exp(-frictionCoefficient * wrapAngle(run, s)));
}

namespace {
// (J^T M b) at the rope's external coordinate `external`: the inertia of the station map's bias in
// the rope's h (RopeData::nodeMassBias; 0 when the rope's nodes are not stations). The momentum
// balance over the groove keeps it: its accelerations are the stations' plus that bias (a
// gripping drum's material acceleration d(v / lambda)/dt, a rolling tangent point's).
double stationBiasInertia(const RopeRecord& r, const RopeCache& c, int external) {
    return Guts::withRope(r, c, [&](const auto&, const auto& data) {
        // mutation-site: bias-inertia
        return data.nodeMassBias.size() > external ? data.nodeMassBias[external] : 0.0;
    });
}
}  // namespace

double TractionRole::stickFriction(const DrivenRun& run, const State& s) const {
    const RopeRecord& r = run.rope;
    const RopeCache& c = run.guts.positionCache(s).ropes[r.index];
    const auto [pa, pb] = run.guts.nodeTotalForces(s, r, run.node.node);
    const int external = r.drivenExternal(r.drivenIndex(run.node.node));
    // ropeReaction = h - S xddot, so (S xddot)_Y = h_Y - reaction_Y.
    const double h = Guts::withRope(r, c, [&](const auto&, const auto& data) { return data.nodeForce[external]; });
    const double sxdd = h - run.guts.ropeReaction(s, r, c)[external];
    return pa - pb - sxdd - stationBiasInertia(r, c, external);
}

TractionRole::MomentumSlip TractionRole::momentumSlip(const DrivenRun& run, const State& s) const {
    const RopeRecord& r = run.rope;
    const DrivenNode& d = run.node;
    const RopeCache& c = run.guts.positionCache(s).ropes[r.index];
    const TractionNodeState& t = phaseOf(run, s, index);
    MomentumSlip m;
    const auto [pa, pb] = run.guts.nodeTotalForces(s, r, d.node);
    m.speed = c.drivenZRates[run.driven];
    const double sigma = t.mode == TractionMode::SlipTowardStart ? 1.0 : -1.0;
    // mutation-site: tight-side
    const double tight = sigma > 0 ? pa : pb, rhoA = r.spec.properties.massPerLength;
    // The groove's normal load per unit angle is P - rhoA v^2: none where the rope lifts off.
    // mutation-site: rhoa-v2
    const double pressing = std::max(tight - rhoA * m.speed * m.speed, 0.0);
    // mutation-site: capstan-exponent
    m.friction = sigma * pressing * (1.0 - std::exp(-frictionCoefficient * wrapAngle(run, s)));
    m.external = r.drivenExternal(r.drivenIndex(d.node));
    // S_YY Yddot + S_Yx xddot + (J^T M b)_Y = P_a - P_b - F: the balance keeps the bias's inertia.
    const double biasInertia = stationBiasInertia(r, c, m.external);
    m.drive = pa - pb - m.friction - biasInertia;
    m.correction = pa - pb - biasInertia -
                   Guts::withRope(r, c, [&](const auto&, const auto& data) { return data.nodeForce[m.external]; });
    const DrivenAngleSite site = run.guts.angleSite(s, r, d);
    m.slipRate = m.speed - d.law.materialRate(d.angle.angle(site), d.angle.rate(site));
    m.workRate = m.friction * m.slipRate - m.correction * m.speed;
    return m;
}

void TractionRole::condense(const DrivenRun& run, const State& s, CouplingWorkspace& ws, SimTK::Vector& mobilityForces,
                            SimTK::Vector_<SimTK::SpatialVec>& bodyForces) const {
    if (!inMomentumSlip(run, s)) return;
    const DrivenNode& d = run.node;
    const MomentumSlip ms = momentumSlip(run, s);
    ws.freeSlips.push_back({run.rope.index, run.driven, ms.external, ms.drive, ms.workRate});
    // The friction's reaction on the groove, sigma F g'(theta), on the angle's row.
    const DrivenAngleSite site = run.guts.angleSite(s, run.rope, d);
    DrivenAngleRow row;
    d.angle.row(site, row);
    row.addGeneralizedForce(ms.friction * d.law.slope(d.angle.angle(site)), mobilityForces, bodyForces);
}

void TractionRole::zDerivatives(const DrivenRun& run, const State& s, const RopeCache& c, const CouplingWorkspace& ws,
                                const SimTK::Vector& z, SimTK::Vector& zdot) const {
    // Friction work: (P_a - P_b) v_slip, zero in stick; the slip states of TractionSlip::RopeMomentum
    // sheaves (zero rates in stick).
    const RopeRecord& r = run.rope;
    const int zy = slipStateZ();
    zdot[zy] = zdot[zy + 1] = 0;
    if (inMomentumSlip(run, s)) {
        const int external = r.drivenExternal(run.driven);
        zdot[zy] = z[zy + 1];
        zdot[zy + 1] = c.externalAccelerations[external];
        for (const CouplingWorkspace::FreeSlip& f : ws.freeSlips)
            if (f.rope == r.index && f.external == external) zdot[frictionWorkZ()] = f.workRate;
        return;
    }
    const double v = slipRate(run, s);
    double power = 0;
    if (v != 0) {
        const auto [pa, pb] = run.guts.nodeAxialForces(s, r, run.node.node);
        power = (pa - pb) * v;
    }
    zdot[frictionWorkZ()] = power;
}

double TractionRole::witness(const DrivenRun& run, const State& s) const {
    const RopeRecord& r = run.rope;
    const TractionNodeState& t = phaseOf(run, s, index);
    if (t.mode == TractionMode::Stick && momentum()) {
        // The groove holds the rope with Phi = P_a - P_b - (S xddot)_Y (Stage::Dynamics: the coupled
        // solve's accelerations); it slips when |Phi| reaches F_max of the side it would slide to.
        const auto [pa, pb] = run.guts.nodeTotalForces(s, r, run.node.node);
        const double phi = stickFriction(run, s);
        const double fa = maxFriction(run, pa, s), fb = maxFriction(run, pb, s);
        return std::min(fa - phi, fb + phi) + kTractionHysteresis * (std::abs(pa) + std::abs(pb));
    }
    if (t.mode == TractionMode::Stick) {
        const auto [pa, pb] = run.guts.nodeAxialForces(s, r, run.node.node);
        const double scale = std::abs(pa) + std::abs(pb);
        if (!(std::max(pa, pb) > 0)) return scale + 1.0;  // both sides slack: no traction to lose
        // min(limit P_b - P_a, limit P_a - P_b) / limit: divided by the limit (>= 1), so that a large
        // e^(mu alpha) (4.4e13 at mu = 10) does not multiply the slack side's round-off (1e-9 N)
        // past the hysteresis; the sign, and so the event, is the same.
        const double lim = limit(run, s);
        return std::min(pb - pa / lim, pa - pb / lim) + kTractionHysteresis * scale;
    }
    const double v = slipRate(run, s);
    return (t.mode == TractionMode::SlipTowardStart ? v : -v) + kSlipRateHysteresis;
}

void TractionRole::changeMode(const DrivenRun& run, State& s) const {
    const Guts& g = run.guts;
    const RopeRecord& r = run.rope;
    const DrivenNode& d = run.node;
    g.getSystem().realize(s, Stage::Velocity);
    TractionNodeState next = phaseOf(run, s, index);
    if (next.mode == TractionMode::Stick && momentum()) {
        g.getSystem().realize(s, Stage::Dynamics);
        next.mode = stickFriction(run, s) > 0 ? TractionMode::SlipTowardStart : TractionMode::SlipTowardEnd;
        startMomentumSlip(run, s, next);
    } else if (next.mode == TractionMode::Stick) {
        const auto [pa, pb] = g.nodeAxialForces(s, r, d.node);
        const double lim = limit(run, s);
        next.mode = lim * pb - pa < lim * pa - pb ? TractionMode::SlipTowardStart : TractionMode::SlipTowardEnd;
    } else if (momentum()) {
        // s_k continuous: the stick offset takes over from Y (Y - g(theta)).
        next.sStick = d.law.offsetOf(g.getZ(s)[slipStateZ()], d.angle.angle(g.angleSite(s, r, d)));
        next.mode = TractionMode::Stick;
    } else {
        // s_k continuous: the surface coordinate where the rope arrives (sStick + g(theta),
        // plus sigma R phi_in on a wrapped sheave) moves onto s_k.
        next.sStick += Guts::withRope(r, g.positionCache(s).ropes[r.index], [&](const auto& model, const auto& data) {
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
    const double before = Guts::withRope(r, g.positionCache(s).ropes[r.index], kinetic);
    g.updTractionStates(s).ropes[r.index][index] = next;
    g.getSystem().realize(s, Stage::Velocity);
    const double after = Guts::withRope(r, g.positionCache(s).ropes[r.index], kinetic);
    g.updZ(s)[frictionWorkZ()] += before - after;
}

bool TractionRole::wrapAngle(const DrivenRun& run, const State& s, double& alpha) const {
    run.guts.positionCache(s);  // Stage::Position: the wrap angle is resolved
    alpha = wrapAngle(run, s);
    return true;
}

bool TractionRole::startSlipOverLimit(const DrivenRun& run, State& s) const {
    const Guts& g = run.guts;
    const RopeRecord& r = run.rope;
    TractionNodeState t = phaseOf(run, s, index);
    if (t.mode != TractionMode::Stick) return false;
    const auto [pa, pb] = g.nodeAxialForces(s, r, run.node.node);
    if (!(std::max(pa, pb) > 0)) return false;
    const double lim = limit(run, s);
    if (pa > lim * pb) {
        t.mode = TractionMode::SlipTowardStart;
    } else if (pb > lim * pa) {
        t.mode = TractionMode::SlipTowardEnd;
    } else {
        return false;
    }
    ++t.transitions;
    if (momentum()) startMomentumSlip(run, s, t);
    g.updTractionStates(s).ropes[r.index][index] = t;
    return true;
}

void TractionRole::addFrictionWork(const SimTK::Vector& z, double& w) const {
    w += z[frictionWorkZ()];
}

namespace {

/// Witness: TractionRole::witness of one traction sheave; when it falls through zero, the sheave
/// changes between stick and slip.
class TractionEvent : public SimTK::TriggeredEventHandler {
public:
    TractionEvent(const System& system, SubsystemIndex reeving, int rope, int driven, Stage stage)
        : SimTK::TriggeredEventHandler(stage), system_(system), reeving_(reeving), rope_(rope),
          driven_(driven) {
        getTriggerInfo().setTriggerOnRisingSignTransition(false);
        getTriggerInfo().setTriggerOnFallingSignTransition(true);
        getTriggerInfo().setRequiredLocalizationTimeWindow(1e-8);
    }
    Real getValue(const State& s) const override {
        const Guts& g = guts();
        const DrivenRun run = g.ropes[rope_].drivenRun(g, driven_);
        return std::get<TractionRole>(run.node.role.unit).witness(run, s);
    }
    void handleEvent(State& s, Real, bool& shouldTerminate) const override {
        shouldTerminate = false;
        const Guts& g = guts();
        const DrivenRun run = g.ropes[rope_].drivenRun(g, driven_);
        std::get<TractionRole>(run.node.role.unit).changeMode(run, s);
    }

private:
    const Guts& guts() const {
        return dynamic_cast<const Guts&>(system_.getSubsystem(reeving_).getSubsystemGuts());
    }
    const System& system_;
    SubsystemIndex reeving_;
    int rope_, driven_;
};

/// Node `node` of rope r as a TractionSheave: its driven index and role.
std::pair<int, const TractionRole*> tractionAt(const RopeRecord& r, int node) {
    if (node < 0 || node >= r.numNodes())
        invalid("node index = " + std::to_string(node) + " is outside 0.." + std::to_string(r.numNodes() - 1));
    const int d = r.drivenIndex(node);
    const TractionRole* t = d < 0 ? nullptr : std::get_if<TractionRole>(&r.driven[d].role.unit);
    if (!t) invalid("rope '" + r.spec.name + "' node " + std::to_string(node) + " is not a TractionSheave");
    return {d, t};
}

}  // namespace

void TractionRole::installEvents(System& system, SubsystemIndex reeving, int rope, int driven) const {
    // A TractionSlip::RopeMomentum sheave's stick witness reads the coupled solve's accelerations.
    const Stage stage = momentum() ? Stage::Dynamics : Stage::Velocity;
    system.addEventHandler(new TractionEvent(system, reeving, rope, driven, stage));  // the system owns it
}

// ---- public queries ---------------------------------------------------------------------------

TractionMode TractionSheaveHandle::getTractionMode(const State& s) const {
    const int rope = getRopeIndex(), node = getNodeIndex();
    const RopeRecord& r = ropeAt(guts(), rope);
    return guts().tractionStates(s).ropes[rope][tractionAt(r, node).second->index].mode;
}

double TractionSheaveHandle::getSlipRate(const State& s) const {
    const int rope = getRopeIndex(), node = getNodeIndex();
    const RopeRecord& r = ropeAt(guts(), rope);
    const auto [d, t] = tractionAt(r, node);
    if (s.getSystemStage() < Stage::Velocity)
        throw std::logic_error("TractionSheaveHandle::getSlipRate: realize the state to Stage::Velocity first");
    return t->slipRate(r.drivenRun(guts(), d), s);
}

double TractionSheaveHandle::getSlipDistance(const State& s) const {
    const int rope = getRopeIndex(), node = getNodeIndex();
    const RopeRecord& r = ropeAt(guts(), rope);
    const auto [driven, t] = tractionAt(r, node);
    const DrivenRun run = r.drivenRun(guts(), driven);
    const DrivenNode& d = run.node;
    // The slip of the current phase (s_k off the surface where it arrives; 0 in stick) plus the
    // offset the stick phases so far have accumulated.
    const RopeCache& c = guts().positionCache(s).ropes[rope];
    if (t->inMomentumSlip(run, s))  // Y over the groove's top, less the pin's turn
        return d.law.offsetOf(c.drivenZStates[driven], d.angle.angle(guts().angleSite(s, r, d))) - d.sRef;
    const double sStick = guts().tractionStates(s).ropes[rope][t->index].sStick;
    return Guts::withRope(r, c, [&](const auto& model, const auto& data) {
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
    const auto [d, t] = tractionAt(r, node);
    guts().positionCache(s);  // Stage::Position: the wrap angle is resolved
    return t->limit(r.drivenRun(guts(), d), s);
}

double TractionSheaveHandle::getFrictionPower(const State& s) const {
    const int rope = getRopeIndex(), node = getNodeIndex();
    const double v = getSlipRate(s);
    const RopeRecord& r = ropeAt(guts(), rope);
    const auto [d, t] = tractionAt(r, node);
    const DrivenRun run = r.drivenRun(guts(), d);
    if (t->inMomentumSlip(run, s)) return t->momentumSlip(run, s).workRate;
    if (v == 0) return 0;
    const auto [pa, pb] = guts().nodeAxialForces(s, r, node);
    return (pa - pb) * v;
}

double TractionSheaveHandle::getFrictionWork(const State& s) const {
    const int rope = getRopeIndex(), node = getNodeIndex();
    const RopeRecord& r = ropeAt(guts(), rope);
    return guts().getZ(s)[tractionAt(r, node).second->frictionWorkZ()];
}

int TractionSheaveHandle::getNumTractionTransitions(const State& s) const {
    const int rope = getRopeIndex(), node = getNodeIndex();
    const RopeRecord& r = ropeAt(guts(), rope);
    return guts().tractionStates(s).ropes[rope][tractionAt(r, node).second->index].transitions;
}

}  // namespace SimbodyReeving
