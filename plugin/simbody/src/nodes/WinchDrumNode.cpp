// RopeNodeKind::WinchDrum: a drum at a rope end; s turns with its pin, the rest is stored rope.

#include "PinnedNode.h"

#include <cmath>

namespace SimbodyReeving {
namespace detail {

void WinchDrumNode::validate(const NodeSite& site) {
    validatePinnedNode(site);
    const double stored = site.spec.ropeOnDrum;
    if (!std::isfinite(stored) || stored < 0) invalid(mustBe(site.name + " ropeOnDrum [m]", stored, "finite and >= 0"));
}

void WinchDrumNode::addMaterialRelation(NodeSite& site) {
    RopeRecord::DrivenNode d = drivenNodeOf(site);
    d.drum = true;
    d.ropeOnDrum = site.spec.ropeOnDrum;
    // Paying out (sense R theta > 0) moves material out of the drum: s_0 = -sense R theta at the
    // start, s_N = L + sense R theta at the end.
    const double R = site.spec.sense * site.spec.radius;
    if (site.node == 0) {
        d.sRef = 0;
        d.dsdTheta = -R;
    } else {
        d.sRef = site.rope.spec.unstretchedLength;
        d.dsdTheta = R;
    }
    site.rope.driven.push_back(d);
}

NodeWrap WinchDrumNode::wrap(const NodeSite& site, const SimTK::Vec3& planeNormal) {
    // The rope leaves the drum at its tangent point (s_0 or s_N there: the drum's s plus sigma R
    // phi); the stored rope is the rest.
    return grippingSheaveWrap(site, kName, planeNormal, true);
}

}  // namespace detail
}  // namespace SimbodyReeving
