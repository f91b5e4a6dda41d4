// NodeKind::DeviationSheave: a frictionless idler; s from the tension equality (paper eq 32).

#include "NodeBend.h"

#include <cmath>

namespace SimbodyReeving {
namespace detail {

void DeviationSheaveNode::validate(const NodeSite& site) {
    const double R = site.spec.radius;
    if (!std::isfinite(R) || !(R > 0)) invalid(mustBe(site.name + " radius [m]", R, "finite and > 0"));
}

void DeviationSheaveNode::addMaterialRelation(NodeSite& site) {
    site.rope.materialKinds[site.node] = MaterialNode::Sliding;
}

NodeWrap DeviationSheaveNode::wrap(const NodeSite& site, const SimTK::Vec3& planeNormal) {
    const NodeSpec& n = site.spec;
    const std::string name = "rope '" + site.rope.spec.name + "': sheave " + std::to_string(site.node);
    if (n.sense != 1 && n.sense != -1)
        invalid(name + " wrap sense = " + std::to_string(n.sense) + " must be +1 or -1");
    NodeWrap w;
    w.radius = n.radius;
    w.wrapSense = n.sense;
    if (planeNormal.norm() > 0) return w;  // planar: the groove turns about the plane normal
    // Spatial: the groove's axis, a body direction. Where the body turns about it alone (if at
    // all) it is fixed in Ground; otherwise it turns with the body (a sheave on a slewing or
    // luffing boom): the rope's model then takes it from an axis station, the body point one
    // metre from the groove's centre along it.
    const SimTK::Vec3& a = n.axis;
    if (!(std::isfinite(a[0]) && std::isfinite(a[1]) && std::isfinite(a[2])) || std::abs(a.norm() - 1) > 1e-12)
        invalid(name + " axis = " + str(a) + " (|axis| = " + std::to_string(a.norm()) +
                ") must be a unit vector: a spatial rope's wrapped sheave turns the rope about it");
    const SimTK::Vec3 inGround = referenceOrientation(n.body) * a;
    if (!keepsDirection(n.body, inGround)) {
        w.turningAxis = true;
        site.rope.axisStations.push_back({site.node, n.point + a / a.norm()});
    }
    w.axis = toEigen(inGround);
    return w;
}

std::pair<double, double> DeviationSheaveNode::heldInterval(const NodeBend& bend) { return sheaveInterval(bend); }

SimTK::Vec3 DeviationSheaveNode::bendAxis(const NodeBend& bend) {
    if (bend.rope.spec.sheaveModel != SheaveModel::Wrapped) return chordTurn(bend);
    const NodeSpec& n = bend.spec();
    // The wrap sense about the groove's axis (half a turn: the chords are parallel).
    const SimTK::Vec3 grooveAxis =
        bend.rope.planar ? unitPlaneNormal(bend.rope) : SimTK::Vec3(n.body.getBodyRotation(bend.state) * n.axis);
    return double(n.sense) * grooveAxis;
}

}  // namespace detail
}  // namespace SimbodyReeving
