// RopeNodeKind::DeviationSheave: a frictionless idler; s from the tension equality (paper eq 32).

#include "NodeKinds.h"

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

NodeWrap DeviationSheaveNode::wrap(const NodeSite& site, const SimTK::UnitVec3&) {
    const RopeNode& n = site.spec;
    if (n.sense != 1 && n.sense != -1)
        invalid("rope '" + site.rope.spec.name + "': sheave " + std::to_string(site.node) +
                " wrap sense = " + std::to_string(n.sense) + " must be +1 or -1");
    NodeWrap w;
    w.radius = n.radius;
    w.wrapSense = n.sense;
    return w;
}

}  // namespace detail
}  // namespace SimbodyReeving
