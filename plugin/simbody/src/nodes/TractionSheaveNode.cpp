// NodeKind::TractionSheave: a sheave on a pin that grips the rope by friction. Built as a
// TurningSheave in stick with a TractionRole (DrivenRole.h); its run time (slip phases, Z
// entries, events, queries) is in TractionSheaveRun.cpp.

#include "NodeBend.h"
#include "PinnedNode.h"

#include <cmath>

namespace SimbodyReeving {
namespace detail {

void TractionSheaveNode::validate(const NodeSite& site) {
    TurningSheaveNode::validate(site);
    const NodeSpec& n = site.spec;
    if (!std::isfinite(n.frictionCoefficient) || n.frictionCoefficient < 0)
        invalid(mustBe(site.name + " frictionCoefficient [-]", n.frictionCoefficient, "finite and >= 0"));
    if (!std::isfinite(n.wrapAngle) || n.wrapAngle < 0 || n.wrapAngle > 20 * SimTK::Pi)
        invalid(mustBe(site.name + " wrapAngle [rad]", n.wrapAngle, "in [0, 20 pi] (0: from the geometry)"));
    if (n.slipModel != TractionSlip::CapstanConstraint && n.slipModel != TractionSlip::RopeMomentum)
        invalid(site.name + " slipModel = " + std::to_string(static_cast<int>(n.slipModel)) +
                " is not a TractionSlip");
}

void TractionSheaveNode::addMaterialRelation(NodeSite& site) {
    TurningSheaveNode::addMaterialRelation(site);  // it starts in stick
    TractionRole traction;
    traction.index = site.rope.numPhaseNodes++;
    traction.frictionCoefficient = site.spec.frictionCoefficient;
    traction.givenWrapAngle = site.spec.wrapAngle;
    traction.geometricWrap = site.spec.wrapAngle == 0;  // the current geometry's (RopeModel::wrapAngle)
    traction.slipModel = site.spec.slipModel;
    site.rope.driven.back().role.unit = traction;
}

NodeWrap TractionSheaveNode::wrap(const NodeSite& site, const SimTK::Vec3& planeNormal) {
    return grippingSheaveWrap(site, kName, planeNormal, false);
}

std::pair<double, double> TractionSheaveNode::heldInterval(const NodeBend& bend) { return sheaveInterval(bend); }

SimTK::Vec3 TractionSheaveNode::bendAxis(const NodeBend& bend) { return pinnedSheaveBendAxis(bend); }

}  // namespace detail
}  // namespace SimbodyReeving
