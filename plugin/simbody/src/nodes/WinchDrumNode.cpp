// NodeKind::WinchDrum: a drum at a rope end; s turns with its pin, the rest is stored rope.

#include "PinnedNode.h"

#include <cmath>

namespace SimbodyReeving {
namespace detail {

void WinchDrumNode::validate(const NodeSite& site) {
    validatePinnedNode(site);
    const double stored = site.spec.ropeOnDrum;
    if (!std::isfinite(stored) || stored < 0) invalid(mustBe(site.name + " ropeOnDrum [m]", stored, "finite and >= 0"));
    const double pitch = site.spec.pitch;
    if (!std::isfinite(pitch) || !(std::abs(pitch) < 2 * SimTK::Pi * site.spec.radius))
        invalid(mustBe(site.name + " pitch [m]", pitch, "finite and |pitch| < 2 pi radius"));
    if (pitch != 0 && (site.rope.spec.sheaveModel != SheaveModel::Wrapped || site.rope.spec.planeNormal.norm() > 0))
        invalid(site.name + " pitch = " + std::to_string(pitch) +
                " m: a drum that spools across its width needs a spatial rope (no RopeSpec::planeNormal) with "
                "SheaveModel::Wrapped (its exit point walks along the drum's axis, out of any plane)");
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
    if (site.spec.pitch != 0) {
        // x = p (Y - s_ref) / (2 pi R) along the pin axis, Y = s_ref + g(theta): stored rope
        // grows with Y at the start and as Y falls at the end.
        const RopeRecord::DrivenNode& d = site.rope.driven[site.rope.drivenIndex(site.node)];
        const double toward = site.node == 0 ? 1.0 : -1.0;
        const SimTK::Vec3 pinAxis = referenceOrientation(site.spec.body.getParentMobilizedBody()) *
                                    site.spec.body.getDefaultInboardFrame().R().z();
        // (NodeWrap::axis is the pin axis in Ground at the reference, or its opposite.)
        const double along = SimTK::dot(pinAxis, SimTK::Vec3(w.axis[0], w.axis[1], w.axis[2])) > 0 ? 1.0 : -1.0;
        w.layRate = along * toward * site.spec.pitch / (2 * SimTK::Pi * site.spec.radius);
        w.layOffset = -w.layRate * d.sRef;
    }
    return w;
}

}  // namespace detail
}  // namespace SimbodyReeving
