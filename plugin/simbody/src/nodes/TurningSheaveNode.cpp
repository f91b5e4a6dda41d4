// NodeKind::TurningSheave: a sheave on a pin that grips the rope, s = s_ref + sense R theta.

#include "NodeBend.h"
#include "PinnedNode.h"

#include <cmath>

namespace SimbodyReeving {
namespace detail {

void TurningSheaveNode::validate(const NodeSite& site) {
    validatePinnedNode(site);
    const double sRef = site.spec.materialCoordinateAtZeroAngle;
    if (!std::isfinite(sRef)) invalid(mustBe(site.name + " materialCoordinateAtZeroAngle [m]", sRef, "finite"));
}

void TurningSheaveNode::addMaterialRelation(NodeSite& site) {
    RopeRecord::DrivenNode d = drivenNodeOf(site);
    d.sRef = site.spec.materialCoordinateAtZeroAngle;
    const double dsdTheta = site.spec.sense * site.spec.radius;  // mutation-site: sheave-sense
    d.law.unit = LinearDrivenLaw{dsdTheta};
    d.role.unit = GripRole{};  // the rope moves with the groove at all times
    site.rope.driven.push_back(d);
}

NodeWrap TurningSheaveNode::wrap(const NodeSite& site, const SimTK::Vec3& planeNormal) {
    return grippingSheaveWrap(site, kName, planeNormal, true);
}

std::pair<double, double> TurningSheaveNode::heldInterval(const NodeBend& bend) { return sheaveInterval(bend); }

SimTK::Vec3 TurningSheaveNode::bendAxis(const NodeBend& bend) { return pinnedSheaveBendAxis(bend); }

}  // namespace detail
}  // namespace SimbodyReeving
