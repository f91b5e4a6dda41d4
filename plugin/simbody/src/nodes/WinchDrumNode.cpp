// NodeKind::WinchDrum: a drum at a rope end; s turns with its pin, the rest is stored rope
// (StoredRopeRole, DrivenRole.h: its declaration to the rope model, its limit and its query).

#include "NodeBend.h"
#include "PinnedNode.h"
#include "SimbodyReeving/element/WalkingGroove.h"

#include <cmath>
#include <limits>
#include <string>
#include <variant>

namespace SimbodyReeving {
namespace detail {

void WinchDrumNode::validate(const NodeSite& site) {
    validatePinnedNode(site);
    const double stored = site.spec.ropeOnDrum;
    if (!std::isfinite(stored) || stored < 0) invalid(mustBe(site.name + " ropeOnDrum [m]", stored, "finite and >= 0"));
    const double pitch = std::get<WinchDrum>(site.rope.spec.node(site.node)).pitch;
    if (!std::isfinite(pitch) || !(std::abs(pitch) < 2 * SimTK::Pi * site.spec.radius))
        invalid(mustBe(site.name + " pitch [m]", pitch, "finite and |pitch| < 2 pi radius"));
    if (pitch != 0 && (site.rope.spec.sheaveModel != SheaveModel::Wrapped || site.rope.spec.planeNormal.norm() > 0))
        invalid(site.name + " pitch = " + std::to_string(pitch) +
                " m: a drum that spools across its width needs a spatial rope (no RopeSpec::planeNormal) with "
                "SheaveModel::Wrapped (its exit point walks along the drum's axis, out of any plane)");
}

void WinchDrumNode::addMaterialRelation(NodeSite& site) {
    RopeRecord::DrivenNode d = drivenNodeOf(site);
    StoredRopeRole stored;
    stored.ropeOnDrum = site.spec.ropeOnDrum;
    stored.grips = site.rope.spec.sheaveModel == SheaveModel::Wrapped;
    d.role.unit = stored;
    // Paying out (sense R theta > 0) moves material out of the drum: s_0 = -sense R theta at the
    // start, s_N = L + sense R theta at the end.
    const double R = site.spec.sense * site.spec.radius;
    if (site.node == 0) {
        d.sRef = 0;
        d.law.unit = LinearDrivenLaw{-R};
    } else {
        d.sRef = site.rope.spec.unstretchedLength;
        d.law.unit = LinearDrivenLaw{R};
    }
    site.rope.driven.push_back(d);
}

NodeWrap WinchDrumNode::wrap(const NodeSite& site, const SimTK::Vec3& planeNormal) {
    // The rope leaves the drum at its tangent point (s_0 or s_N there: the drum's s plus sigma R
    // phi); the stored rope is the rest.
    NodeWrap w = grippingSheaveWrap(site, kName, planeNormal, true);
    const double pitch = std::get<WinchDrum>(site.rope.spec.node(site.node)).pitch;
    if (pitch != 0) {
        // A drum that spools across its width, a WalkingGroove: x = p (Y - s_ref) / (2 pi R)
        // along the pin axis, Y = s_ref + g(theta): stored rope grows with Y at the start and as
        // Y falls at the end.
        const RopeRecord::DrivenNode& d = site.rope.driven[site.rope.drivenIndex(site.node)];
        const double toward = site.node == 0 ? 1.0 : -1.0;
        const SimTK::Vec3 pinAxis = referenceOrientation(site.spec.body.getParentMobilizedBody()) *
                                    site.spec.body.getDefaultInboardFrame().R().z();
        // (NodeWrap::axis is the pin axis in Ground at the reference, or its opposite.)
        const double along = SimTK::dot(pinAxis, SimTK::Vec3(w.axis[0], w.axis[1], w.axis[2])) > 0 ? 1.0 : -1.0;
        WalkingGroove walking;
        walking.dxdY = along * toward * pitch / (2 * SimTK::Pi * site.spec.radius);
        walking.x0 = -walking.dxdY * d.sRef;
        w.groove.unit = walking;
    }
    return w;
}

// The rope on the drum from the material coordinate where the rope leaves it (the drum's centre,
// or its tangent point when wrapped).
void StoredRopeRole::limitMargin(const DrivenRun& run, const RopeCache& c, double& margin, std::string* which) const {
    const RopeRecord& r = run.rope;
    const int node = run.node.node;
    const double s = r.planar ? c.planar.materialCoordinates[node] : c.spatial.materialCoordinates[node];
    const double stored = onDrum(node, s, r.spec.unstretchedLength);
    if (stored < margin) {
        margin = stored;
        if (which) *which = "rope '" + r.spec.name + "' winch drum at node " + std::to_string(node) + " ran out of rope";
    }
}

std::pair<double, double> WinchDrumNode::heldInterval(const NodeBend& bend) {
    constexpr double inf = std::numeric_limits<double>::infinity();
    if (bend.node == 0) return {-inf, bend.spanRange(0).first};  // below the tangent point: on the drum
    return {bend.spanRange(bend.rope.numSpans() - 1).second, inf};
}

SimTK::Vec3 WinchDrumNode::bendAxis(const NodeBend& bend) {
    const double sense = bend.spec().sense;  // payoutSense
    if (bend.node == 0) return sense * pinAxisInGround(bend);
    return -sense * pinAxisInGround(bend);
}

void StoredRopeRole::materialCoordinate(const DrivenRun& run, const SimTK::State& state, double theta, double thetaDot,
                                        bool rates, double& s, double& sdot) const {
    DrivenRoleDefaults::materialCoordinate(run, state, theta, thetaDot, rates, s, sdot);
    if (creepZ >= 0) s += run.guts.getZ(state)[creepZ];
}

void StoredRopeRole::zDerivatives(const DrivenRun& run, const SimTK::State&, const RopeCache& c,
                                  const CouplingWorkspace&, const SimTK::Vector&, SimTK::Vector& zdot) const {
    if (creepZ < 0) return;
    const Eigen::VectorXd& rates = run.rope.planar ? c.planar.gripCreepRates : c.spatial.gripCreepRates;
    zdot[creepZ] = rates.size() > run.driven ? rates[run.driven] : 0.0;
    const Eigen::VectorXd& power = run.rope.planar ? c.planar.gripHeldEnergyRates : c.spatial.gripHeldEnergyRates;
    zdot[heldEnergyZ] = power.size() > run.driven ? power[run.driven] : 0.0;
}

double StoredRopeRole::storedRope(const DrivenRun& run, const RopeCache& c) const {
    const RopeRecord& r = run.rope;
    const int node = run.node.node;
    const double s = r.planar ? c.planar.materialCoordinates[node] : c.spatial.materialCoordinates[node];
    return onDrum(node, s, r.spec.unstretchedLength);
}

}  // namespace detail

double WinchDrumHandle::getRopeOnDrum(const SimTK::State& s) const {
    using namespace detail;
    const int rope = getRopeIndex(), node = getNodeIndex();
    const RopeRecord& r = ropeAt(guts(), rope);
    if (node < 0 || node >= r.numNodes())
        invalid("node index = " + std::to_string(node) + " is outside 0.." + std::to_string(r.numNodes() - 1));
    const int d = r.drivenIndex(node);
    const StoredRopeRole* stored = d < 0 ? nullptr : std::get_if<StoredRopeRole>(&r.driven[d].role.unit);
    if (!stored) invalid("rope '" + r.spec.name + "' node " + std::to_string(node) + " is not a WinchDrum");
    const RopeCache& c = guts().positionCache(s).ropes[rope];
    const double sk = r.planar ? c.planar.materialCoordinates[node] : c.spatial.materialCoordinates[node];
    return stored->onDrum(node, sk, r.spec.unstretchedLength);
}

}  // namespace SimbodyReeving
