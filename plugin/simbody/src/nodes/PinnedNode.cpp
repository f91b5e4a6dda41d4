// What the node kinds on a Pin share: checks, the Driven material relation, the wrapped grip.

#include "PinnedNode.h"

#include <cmath>

namespace SimbodyReeving {
namespace detail {

bool keepsGroundOrientation(const SimTK::MobilizedBody& b) {
    if (b.isGround()) return true;
    using SimTK::MobilizedBody;
    if (!MobilizedBody::Slider::isInstanceOf(b) && !MobilizedBody::Translation::isInstanceOf(b) &&
        !MobilizedBody::Weld::isInstanceOf(b))
        return false;
    const SimTK::Rotation& inboard = b.getDefaultInboardFrame().R();
    const SimTK::Rotation& outboard = b.getDefaultOutboardFrame().R();
    if (std::abs(std::abs((~inboard * outboard).convertRotationToAngleAxis()[0])) > 1e-14) return false;
    return keepsGroundOrientation(b.getParentMobilizedBody());
}

SimTK::Rotation referenceOrientation(const SimTK::MobilizedBody& b) {
    if (b.isGround()) return SimTK::Rotation();
    return referenceOrientation(b.getParentMobilizedBody()) * b.getDefaultInboardFrame().R() *
           ~b.getDefaultOutboardFrame().R();
}

bool keepsDirection(const SimTK::MobilizedBody& b, const SimTK::Vec3& direction) {
    if (b.isGround()) return true;
    using SimTK::MobilizedBody;
    const MobilizedBody& parent = b.getParentMobilizedBody();
    if (MobilizedBody::Slider::isInstanceOf(b) || MobilizedBody::Translation::isInstanceOf(b) ||
        MobilizedBody::Weld::isInstanceOf(b))
        return keepsDirection(parent, direction);
    if (MobilizedBody::Pin::isInstanceOf(b) || MobilizedBody::Planar::isInstanceOf(b)) {
        // Both turn about their inboard frame's z (fixed in the parent, which keeps `direction`).
        const SimTK::Vec3 turn = referenceOrientation(parent) * b.getDefaultInboardFrame().R().z();
        if (SimTK::cross(turn, direction).norm() > 1e-12 * direction.norm()) return false;
        return keepsDirection(parent, direction);
    }
    return false;
}

std::string mustBe(const std::string& what, double value, const char* must) {
    std::ostringstream o;
    o << what << " = " << value << " must be " << must;
    return o.str();
}

void validatePinnedNode(const NodeSite& site) {
    const NodeSpec& n = site.spec;
    if (!std::isfinite(n.radius) || !(n.radius > 0)) invalid(mustBe(site.name + " radius [m]", n.radius, "finite and > 0"));
    if (!SimTK::MobilizedBody::Pin::isInstanceOf(n.body))
        invalid(site.name + ": its body must be a MobilizedBody::Pin (the rope turns it about the pin axis)");
    const SimTK::Transform& X_BM = n.body.getDefaultOutboardFrame();
    const SimTK::Vec3 axis = X_BM.R().z(), offset = n.point - X_BM.p();
    if ((offset - axis * SimTK::dot(offset, axis)).norm() > 1e-12 * std::max(1.0, offset.norm()))
        invalid(site.name + " point " + str(n.point) + " is off the pin axis (it would orbit as the pin turns)");
    if (n.sense != 1 && n.sense != -1) invalid(site.name + " sense = " + std::to_string(n.sense) + " must be +1 or -1");
}

RopeRecord::DrivenNode drivenNodeOf(NodeSite& site) {
    site.rope.materialKinds[site.node] = MaterialNode::Driven;
    RopeRecord::DrivenNode d;
    d.node = site.node;
    return d;
}

NodeWrap grippingSheaveWrap(const NodeSite& site, const char* kindName, const SimTK::Vec3& planeNormal,
                            bool turningParent) {
    const NodeSpec& n = site.spec;
    const std::string name =
        "rope '" + site.rope.spec.name + "': " + kindName + " at node " + std::to_string(site.node);
    const SimTK::MobilizedBody& parent = n.body.getParentMobilizedBody();
    if (!turningParent && !keepsGroundOrientation(parent))
        invalid(name + ": with SheaveModel::Wrapped its pin's parent must be Ground or translate without turning "
                       "(Slider, Translation or Weld with aligned frames, on such a body): a TractionSheave's grip on "
                       "the groove is measured from Ground's angles");
    // The pin axis in Ground with the parent's chain at its reference. It turns with the parent
    // unless the parent turns about it alone (if at all): then a spatial rope's model takes it
    // from an axis station (NodeWrap::turningAxis), and a planar rope's grooves cannot.
    const SimTK::UnitVec3 axis(referenceOrientation(parent) * n.body.getDefaultInboardFrame().R().z());
    const bool planar = planeNormal.norm() > 0;
    const bool axisTurns = turningParent && !keepsDirection(parent, axis);
    if (axisTurns && planar)
        invalid(name + ": with SheaveModel::Wrapped on a planar rope its pin's parent may turn only about the pin "
                       "axis " +
                str(SimTK::Vec3(axis)) +
                " (its chain of Pin or Planar mobilizers about that axis, Sliders, Translations and Welds): the "
                "groove's axis must stay the plane normal");
    // The sense a positive angle moves the rope: the sign of ds/dtheta at theta = 0.
    const double dsdTheta = site.rope.driven[site.rope.drivenIndex(site.node)].law.slope(0.0);
    NodeWrap w;
    w.radius = n.radius;
    SimTK::Vec3 grooveAxis = axis;
    if (!(planeNormal.norm() > 0)) {
        // A spatial rope: the groove turns about the pin axis, and the rope wraps it against the
        // sense a positive pin angle moves it.
        w.axis = Eigen::Vector3d(axis[0], axis[1], axis[2]);
        w.wrapSense = dsdTheta > 0 ? -1 : 1;
    } else {
        const SimTK::UnitVec3 normal(planeNormal);
        const double alignment = SimTK::dot(axis, normal);
        if (std::abs(std::abs(alignment) - 1) > 1e-12)
            invalid(name + ": with SheaveModel::Wrapped its pin axis " + str(SimTK::Vec3(axis)) +
                    " must be along the rope's plane normal " + str(SimTK::Vec3(normal)));
        w.wrapSense = (alignment > 0) == (dsdTheta > 0) ? -1 : 1;
        grooveAxis = (alignment > 0 ? 1.0 : -1.0) * SimTK::Vec3(normal);
    }
    if (turningParent) {  // the sheave's own angle about its axis: its pin's plus its parent's turn
        RopeRecord::DrivenNode& d = site.rope.driven[site.rope.drivenIndex(site.node)];
        if (axisTurns) {  // the axis station: on the pin axis, 1 m from the centre
            w.turningAxis = true;
            TurningAxisAngle angle;
            angle.bodyAxis = SimTK::Vec3(n.body.getDefaultOutboardFrame().R().z());
            angle.parentAxis = SimTK::Vec3(n.body.getDefaultInboardFrame().R().z());
            angle.parentPerp = SimTK::Vec3(n.body.getDefaultInboardFrame().R().x());
            d.angle.unit = angle;
            site.rope.axisStations.push_back({site.node, n.point + angle.bodyAxis});
        } else {
            d.angle.unit = ParentTurnAngle{grooveAxis};
        }
    }
    return w;
}

}  // namespace detail
}  // namespace SimbodyReeving
