// ReevingSubsystem: construction, addRope (validation), rope accessors and the modal state.

#include "ReevingSubsystemGuts.h"
#include "nodes/NodeKinds.h"

#include <algorithm>
#include <cmath>
#include <memory>
#include <sstream>
#include <stdexcept>
#include <typeinfo>
#include <string>
#include <utility>
#include <vector>

using SimTK::ForceSubsystem;
using SimTK::MultibodySystem;
using SimTK::State;
using SimTK::Vec3;
using SimTK::Vector;

namespace SimbodyReeving {

using namespace detail;

// ---- rope specs --------------------------------------------------------------------------------

RopeNode RopeSpec::node(int k) const {
    if (k < 0 || k >= numNodes())
        throw std::out_of_range("RopeSpec::node: node index = " + std::to_string(k) + " is outside 0.." +
                                std::to_string(numNodes() - 1));
    const auto widen = [](const auto& kind) { return RopeNode(kind); };
    if (k == 0) return std::visit(widen, start);
    if (k == numNodes() - 1) return std::visit(widen, end);
    return std::visit(widen, sheaves[static_cast<std::size_t>(k - 1)]);
}

namespace detail {
NodeSpec toNodeSpec(const RopeNode& node) {
    NodeSpec n;
    struct Fill {
        NodeSpec& n;
        void operator()(const RopeAnchor& a) const {
            n.kind = NodeKind::Anchor;
            n.body = a.body;
            n.point = a.station;
        }
        void operator()(const DeviationSheave& d) const {
            n.kind = NodeKind::DeviationSheave;
            n.body = d.body;
            n.point = d.centre;
            n.radius = d.radius;
            n.sense = d.wrapSense;
            n.axis = d.axis;
        }
        void operator()(const WinchDrum& w) const {
            n.kind = NodeKind::WinchDrum;
            n.body = w.body;
            n.point = w.centre;
            n.radius = w.radius;
            n.sense = w.payoutSense;
            n.ropeOnDrum = w.ropeOnDrum;
        }
        void operator()(const TurningSheave& t) const {
            n.kind = NodeKind::TurningSheave;
            n.body = t.body;
            n.point = t.centre;
            n.radius = t.radius;
            n.sense = t.sense;
            n.materialCoordinateAtZeroAngle = t.materialCoordinateAtZeroAngle;
        }
        void operator()(const TractionSheave& t) const {
            n.kind = NodeKind::TractionSheave;
            n.body = t.body;
            n.point = t.centre;
            n.radius = t.radius;
            n.sense = t.sense;
            n.materialCoordinateAtZeroAngle = t.materialCoordinateAtZeroAngle;
            n.frictionCoefficient = t.frictionCoefficient;
            n.wrapAngle = t.wrapAngle;
            n.slipModel = t.slipModel;
        }
    };
    std::visit(Fill{n}, node);
    return n;
}
}  // namespace detail


// ---- ReevingSubsystem ------------------------------------------------------------------------

bool ReevingSubsystem::isInstanceOf(const ForceSubsystem& s) {
    return dynamic_cast<const Guts*>(&s.getSubsystemGuts()) != nullptr;
}
const ReevingSubsystem& ReevingSubsystem::downcast(const ForceSubsystem& s) {
    return static_cast<const ReevingSubsystem&>(s);
}
ReevingSubsystem& ReevingSubsystem::updDowncast(ForceSubsystem& s) { return static_cast<ReevingSubsystem&>(s); }
ReevingSubsystem::Guts& ReevingSubsystem::updGuts() { return dynamic_cast<Guts&>(updSubsystemGuts()); }
const ReevingSubsystem::Guts& ReevingSubsystem::getGuts() const { return dynamic_cast<const Guts&>(getSubsystemGuts()); }

ReevingSubsystem::ReevingSubsystem(MultibodySystem& system, const Vec3& gravity) {
    if (!finite(gravity)) invalid("gravity [m/s^2] = " + str(gravity) + " must be finite");
    adoptSubsystemGuts(new Guts(gravity, false));
    system.addForceSubsystem(*this);
}

ReevingSubsystem::ReevingSubsystem(MultibodySystem& system) {
    adoptSubsystemGuts(new Guts(Vec3(0), true));
    system.addForceSubsystem(*this);
}

Vec3 ReevingSubsystem::getGravity() const { return getGuts().gravity(); }

void ReevingSubsystem::Guts::findGravityForces() {
    gravityForces_.clear();
    const SimTK::System& sys = getSystem();
    for (SimTK::SubsystemIndex i(0); i < sys.getNumSubsystems(); ++i) {
        const SimTK::Subsystem& sub = sys.getSubsystem(i);
        // Simbody 3.7's GeneralForceSubsystem::isInstanceOf answers true for other force
        // subsystems (this one included), and its accessors then throw std::bad_cast: identify
        // it by its name, and let a bad_cast say it is not one after all.
        if (sub.getName() != "GeneralForceSubsystem" || !ForceSubsystem::isInstanceOf(sub)) continue;
        const auto& forces = static_cast<const SimTK::GeneralForceSubsystem&>(ForceSubsystem::downcast(sub));
        int numForces = 0;
        try {
            numForces = forces.getNumForces();
        } catch (const std::bad_cast&) {
            continue;
        }
        for (SimTK::ForceIndex f(0); f < numForces; ++f) {
            const SimTK::Force& force = forces.getForce(f);
            if (SimTK::Force::Gravity::isInstanceOf(force))
                gravityForces_.push_back({&force, &SimTK::Force::Gravity::downcast(force), nullptr});
            else if (SimTK::Force::UniformGravity::isInstanceOf(force))
                gravityForces_.push_back({&force, nullptr, &SimTK::Force::UniformGravity::downcast(force)});
        }
    }
}

int ReevingSubsystem::Guts::systemGravity(const State* state, Vec3& sum) const {
    sum = Vec3(0);
    int count = 0;
    for (const GravityForce& g : gravityForces_) {
        if (state ? g.force->isDisabled(*state) : g.force->isDisabledByDefault()) continue;
        if (g.gravity)
            sum += state ? g.gravity->getGravityVector(*state) : g.gravity->getDefaultGravityVector();
        else
            sum += g.uniform->getGravity();
        ++count;
    }
    return count;
}

void ReevingSubsystem::Guts::checkStateGravity(const State& s) const {
    if (gravityForces_.empty()) return;
    Vec3 stateG;
    systemGravity(&s, stateG);
    if ((stateG - gravity_).norm() > 1e-12 * std::max(stateG.norm(), gravity_.norm()))
        throw std::logic_error("ReevingSubsystem: the gravity the bodies feel in this state, " + str(stateG) +
                               " m/s^2 (the system's enabled Force::Gravity / Force::UniformGravity), differs "
                               "from the ropes' gravity " + str(gravity_) +
                               " m/s^2 fixed at realizeTopology; change gravity through the forces' defaults "
                               "and realize the topology again");
}

RopeHandle ReevingSubsystem::addRope(const RopeSpec& specIn) {
    Guts& g = updGuts();
    RopeRecord r;
    r.spec = specIn;
    for (int k = 0; k < r.spec.numNodes(); ++k) r.nodeSpecs.push_back(toNodeSpec(r.spec.node(k)));
    const RopeSpec& spec = r.spec;
    const std::string who = "rope '" + spec.name + "': ";
    const SimTK::SimbodyMatterSubsystem* matter =
        SimTK::MultibodySystem::isInstanceOf(getSystem()) &&
                SimTK::MultibodySystem::downcast(getSystem()).hasMatterSubsystem()
            ? &SimTK::MultibodySystem::downcast(getSystem()).getMatterSubsystem()
            : nullptr;
    auto number = [](const std::string& what, double v, const char* must) { return mustBe(what, v, must); };
    for (int k = 0; k < r.numNodes(); ++k) {
        const NodeSpec& n = r.nodeSpec(k);
        const std::string name = who + (k == 0                  ? std::string("start node")
                                        : k == r.numNodes() - 1 ? std::string("end node")
                                                                : "sheave " + std::to_string(k - 1)) +
                                 " (" + nodeKindName(n.kind) + ", node " + std::to_string(k) + ")";
        visitNodeKind(n.kind, [&](auto unit) {
            using Unit = decltype(unit);
            if (n.body.isEmptyHandle()) invalid(name + " has no body");
            if (matter && &n.body.getMatterSubsystem() != matter)
                invalid(name + " is on a body of another system's matter subsystem");
            if (!finite(n.point)) invalid(name + " point [m] = " + str(n.point) + " must be finite");
            Unit::validate(NodeSite{r, k, n, name});
        });
    }
    if (!std::isfinite(spec.minimumSpanLength) || !(spec.minimumSpanLength > 0))
        invalid(number(who + "minimumSpanLength [m]", spec.minimumSpanLength, "finite and > 0"));
    // Consecutive path points on the same body must not coincide.
    for (int k = 0; k + 1 < r.numNodes(); ++k) {
        const auto a = r.node(k), b = r.node(k + 1);
        if (a.first->getMobilizedBodyIndex() == b.first->getMobilizedBodyIndex() && (a.second - b.second).norm() == 0)
            invalid(who + "path points " + std::to_string(k) + " and " + std::to_string(k + 1) +
                    " coincide (same body, station " + str(a.second) + ")");
    }
    if (!std::isfinite(spec.unstretchedLength) || !(spec.unstretchedLength > 0)) {
        std::ostringstream o;
        o << who << "unstretchedLength [m] = " << spec.unstretchedLength << " must be finite and > 0";
        invalid(o.str());
    }
    try {
        validate(spec.properties);
    } catch (const std::invalid_argument& e) {
        invalid(who + e.what());
    }
    r.spanOptions.assign(r.numSpans(), spec.spanDefaults);
    for (const auto& [index, options] : spec.spanOverrides) {
        if (index < 0 || index >= r.numSpans())
            invalid(who + "span override index = " + std::to_string(index) + " is outside 0.." +
                    std::to_string(r.numSpans() - 1));
        r.spanOptions[index] = options;
    }
    // Material coordinates: Fixed at anchors, Sliding at deviation sheaves, Driven (s = sRef +
    // g(theta), nodes/DrivenLaw.h) at drums and turning sheaves.
    r.materialKinds.resize(r.numNodes());
    for (int k = 0; k < r.numNodes(); ++k) {
        const NodeSpec& n = r.nodeSpec(k);
        const std::string name = nodeKindName(n.kind);
        NodeSite site{r, k, n, name};
        visitNodeKind(n.kind, [&](auto unit) { decltype(unit)::addMaterialRelation(site); });
    }
    if (!finite(spec.planeNormal)) invalid(who + "planeNormal = " + str(spec.planeNormal) + " must be finite");
    r.planar = spec.planeNormal.norm() > 0;
    // Wrapped deviation sheaves: the groove's radius and the rope's wrap sense about the plane normal.
    r.wraps.assign(r.numNodes(), NodeWrap{});
    if (spec.sheaveModel == SheaveModel::Wrapped) {
        const Vec3 normal = r.planar ? Vec3(SimTK::UnitVec3(spec.planeNormal)) : Vec3(0);
        for (int k = 0; k < r.numNodes(); ++k) {
            const NodeSpec& n = r.nodeSpec(k);
            const std::string name = nodeKindName(n.kind);
            const NodeSite site{r, k, n, name};
            r.wraps[k] = visitNodeKind(n.kind, [&](auto unit) { return decltype(unit)::wrap(site, normal); });
        }
    }
    const Eigen::Vector3d gravity = toEigen(g.gravity());
    try {
        if (r.planar) {
            const Eigen::Matrix3d frame = makeReferenceFrame(toEigen(spec.planeNormal));
            r.normal = frame.col(0);
            r.e1 = frame.col(1);
            r.e2 = frame.col(2);
            r.planeBasis << r.e1, r.e2;
            if (!g.gravityFromSystem() && std::abs(r.normal.dot(gravity)) > 1e-12 * gravity.norm())
                invalid(who + "gravity " + str(g.gravity()) + " is not in the rope plane (normal " +
                        str(spec.planeNormal) + ")");
            // The model itself is built at realizeTopology, when gravity is known.
            for (int j = 0; j < r.numSpans(); ++j) {
                const SpanModel<2> probe(spec.properties, r.spanOptions[j], Eigen::Vector2d::Zero());
                r.numModal += probe.numModalCoordinates();
                r.numModal -= probe.numCondensedModes();  // condensed: not states
            }
            // Validates the rope as a chain (material kinds, lengths) now rather than at topology.
            std::vector<SpanModel<2>> spans;
            for (int j = 0; j < r.numSpans(); ++j)
                spans.emplace_back(spec.properties, r.spanOptions[j], Eigen::Vector2d::Zero());
            const RopeModel<2> probeRope(std::move(spans), spec.unstretchedLength, r.materialKinds, r.wraps);
            if (probeRope.numModalCoordinates() != r.numModal)
                throw std::logic_error("ReevingSubsystem: modal coordinate count mismatch (internal)");
        } else {
            std::vector<SpanModel<3>> spans;
            for (int j = 0; j < r.numSpans(); ++j) {
                spans.emplace_back(spec.properties, r.spanOptions[j], gravity);  // validates options
                r.numModal += spans.back().numModalCoordinates();
                r.numModal -= spans.back().numCondensedModes();  // condensed: not states
            }
            // Validates the rope as a chain (material kinds, wraps) now rather than at its first realization.
            const RopeModel<3> probeRope(std::move(spans), spec.unstretchedLength, r.materialKinds, r.wraps);
        }
    } catch (const std::invalid_argument& e) {
        const std::string msg = e.what();
        if (msg.rfind("ReevingSubsystem", 0) == 0) throw;
        invalid(who + msg);
    }
    if (g.ropes.empty()) installLimitHandler(updSystem(), getMySubsystemIndex());
    if (!r.planar) installFrameChangeHandler(updSystem(), getMySubsystemIndex(), static_cast<int>(g.ropes.size()));
    for (size_t d = 0; d < r.driven.size(); ++d)  // a TractionSheave's stick/slip events
        r.driven[d].role.installEvents(updSystem(), getMySubsystemIndex(), static_cast<int>(g.ropes.size()),
                                       static_cast<int>(d));
    g.ropes.push_back(std::move(r));
    invalidateSubsystemTopologyCache();
    return RopeHandle(g, static_cast<int>(g.ropes.size()) - 1);
}

RopeHandle ReevingSubsystem::getRope(int rope) const {
    ropeAt(getGuts(), rope);
    return RopeHandle(getGuts(), rope);
}

// ---- handles ---------------------------------------------------------------------------------

const ReevingSubsystem& RopeNodeHandle::getReevingSubsystem() const {
    return ReevingSubsystem::downcast(SimTK::ForceSubsystem::downcast(guts_->getOwnerSubsystemHandle()));
}

int RopeHandle::getNumNodes() const { return ropeAt(*guts_, index_).numNodes(); }

namespace {
/// Node `node` of rope r, checked to be of kind `kind` (its handle's).
void checkNodeKind(const RopeRecord& r, int node, NodeKind kind) {
    if (node < 0 || node >= r.numNodes())
        invalid("rope '" + r.spec.name + "': node index = " + std::to_string(node) + " is outside 0.." +
                std::to_string(r.numNodes() - 1));
    if (r.nodeSpec(node).kind != kind)
        invalid("rope '" + r.spec.name + "': node " + std::to_string(node) + " (" +
                nodeKindName(r.nodeSpec(node).kind) + ") is not a " + nodeKindName(kind));
}
}  // namespace

WinchDrumHandle RopeHandle::getWinchDrum(int node) const {
    checkNodeKind(ropeAt(*guts_, index_), node, NodeKind::WinchDrum);
    return WinchDrumHandle(*guts_, index_, node);
}
TurningSheaveHandle RopeHandle::getTurningSheave(int node) const {
    checkNodeKind(ropeAt(*guts_, index_), node, NodeKind::TurningSheave);
    return TurningSheaveHandle(*guts_, index_, node);
}
TractionSheaveHandle RopeHandle::getTractionSheave(int node) const {
    checkNodeKind(ropeAt(*guts_, index_), node, NodeKind::TractionSheave);
    return TractionSheaveHandle(*guts_, index_, node);
}

int ReevingSubsystem::getNumRopes() const { return static_cast<int>(getGuts().ropes.size()); }

const RopeSpec& ReevingSubsystem::getRopeSpec(int rope) const { return ropeAt(getGuts(), rope).spec; }
int ReevingSubsystem::getNumSpans(int rope) const { return ropeAt(getGuts(), rope).numSpans(); }
bool ReevingSubsystem::isPlanar(int rope) const { return ropeAt(getGuts(), rope).planar; }
int ReevingSubsystem::getNumModalCoordinates(int rope) const { return ropeAt(getGuts(), rope).numModal; }

Vector ReevingSubsystem::getModalCoordinates(const State& s, int rope) const {
    const RopeRecord& r = ropeAt(getGuts(), rope);
    return getGuts().getZ(s)(r.zOffset, r.numModal);
}
Vector ReevingSubsystem::getModalRates(const State& s, int rope) const {
    const RopeRecord& r = ropeAt(getGuts(), rope);
    return getGuts().getZ(s)(r.zOffset + r.numModal, r.numModal);
}
void ReevingSubsystem::setModalCoordinates(State& s, int rope, const Vector& q) const {
    const RopeRecord& r = ropeAt(getGuts(), rope);
    if (q.size() != r.numModal)
        invalid("setModalCoordinates: size " + std::to_string(q.size()) + " differs from " + std::to_string(r.numModal));
    getGuts().updZ(s)(r.zOffset, r.numModal) = q;
}
void ReevingSubsystem::setModalRates(State& s, int rope, const Vector& qdot) const {
    const RopeRecord& r = ropeAt(getGuts(), rope);
    if (qdot.size() != r.numModal)
        invalid("setModalRates: size " + std::to_string(qdot.size()) + " differs from " + std::to_string(r.numModal));
    getGuts().updZ(s)(r.zOffset + r.numModal, r.numModal) = qdot;
}

void ReevingSubsystem::setFrameChangeAlignment(double alignment) {
    if (!std::isfinite(alignment) || alignment < 0.01 || alignment > 1.99) {
        std::ostringstream o;
        o << "frame change alignment 1 + i0 . i_e = " << alignment << " must be in [0.01, 1.99]";
        invalid(o.str());
    }
    updGuts().frameChangeAlignment = alignment;
}
double ReevingSubsystem::getFrameChangeAlignment() const { return getGuts().frameChangeAlignment; }

int ReevingSubsystem::getNumFrameChanges(const State& s, int rope) const {
    ropeAt(getGuts(), rope);
    return getGuts().spatialFrames(s).changes[rope];
}

SimTK::Mat33 ReevingSubsystem::getSpanReferenceFrame(const State& s, int rope, int span) const {
    const Guts& g = getGuts();
    const RopeRecord& r = ropeAt(g, rope);
    if (r.planar) invalid("rope '" + r.spec.name + "' is planar: its spans have no reference frame");
    if (span < 0 || span >= r.numSpans())
        invalid("span index = " + std::to_string(span) + " is outside 0.." + std::to_string(r.numSpans() - 1));
    g.positionCache(s);  // Stage::Position: the frames exist
    const Eigen::Matrix3d& A0 = g.spatialModel(s, r).span(span).referenceFrame();
    SimTK::Mat33 out;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) out(i, j) = A0(i, j);
    return out;
}

void ReevingSubsystem::resetSpanFrames(State& s) const {
    const Guts& g = getGuts();
    for (int i = 0; i < getNumRopes(); ++i) g.changeSpanFrames(s, i, false);
}

void ReevingSubsystem::setDecorationResolution(int pointsPerSpan) {
    if (pointsPerSpan < 2) invalid("decoration resolution = " + std::to_string(pointsPerSpan) + " must be >= 2");
    updGuts().decorationPoints = pointsPerSpan;
}

}  // namespace SimbodyReeving
