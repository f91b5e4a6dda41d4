// What the node kinds' bend queries share (NodeBend.h): span ranges, chords, pin axes.

#include "NodeBend.h"

namespace SimbodyReeving {
namespace detail {

std::pair<double, double> NodeBend::spanRange(int span) const {
    const RopeCache& c = guts.positionCache(state).ropes[rope.index];
    const Eigen::VectorXd& sv = rope.planar ? c.planar.materialCoordinates : c.spatial.materialCoordinates;
    return {guts.spanStartMaterial(state, rope, span), sv[span + 1]};
}

double NodeBend::materialCoordinate() const {
    const RopeCache& c = guts.positionCache(state).ropes[rope.index];
    return (rope.planar ? c.planar.materialCoordinates : c.spatial.materialCoordinates)[node];
}

std::pair<double, double> sheaveInterval(const NodeBend& bend) {
    return {bend.spanRange(bend.node - 1).second, bend.spanRange(bend.node).first};
}

SimTK::Vec3 unitPlaneNormal(const RopeRecord& rope) { return rope.spec.planeNormal / rope.spec.planeNormal.norm(); }

SimTK::Vec3 chordTurn(const NodeBend& bend) {
    auto chord = [&](int span) {
        const std::vector<SimTK::Vec3> ends = bend.guts.sample(bend.state, bend.rope.index, span, 2);
        return ends[1] - ends[0];
    };
    return SimTK::cross(chord(bend.node - 1), chord(bend.node));
}

SimTK::Vec3 pinAxisInGround(const NodeBend& bend) {
    const SimTK::MobilizedBody& pin = bend.spec().body;
    return SimTK::Vec3((pin.getBodyRotation(bend.state) * pin.getOutboardFrame(bend.state).R()).z());
}

SimTK::Vec3 pinnedSheaveBendAxis(const NodeBend& bend) {
    if (bend.rope.spec.sheaveModel != SheaveModel::Wrapped) return chordTurn(bend);
    return -double(bend.spec().sense) * pinAxisInGround(bend);
}

}  // namespace detail
}  // namespace SimbodyReeving
