// ReevingSubsystem: the public queries (forces, strains, material coordinates, constraint errors,
// sampling, energies, evaluation failures).

#include "ReevingSubsystemGuts.h"
#include "nodes/NodeBend.h"
#include "nodes/NodeKinds.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

using SimTK::MultibodySystem;
using SimTK::Stage;
using SimTK::State;
using SimTK::Vec3;

namespace SimbodyReeving {

using namespace detail;

std::vector<Vec3> ReevingSubsystem::Guts::sample(const State& s, int rope, int span, int numPoints) const {
    const RopeRecord& r = ropes.at(rope);
    const RopeCache& c = positionCache(s).ropes.at(rope);
    std::vector<Vec3> out;
    Eigen::VectorXd q;
    const Eigen::VectorXd qm = modal(getZ(s), r, false);
    if (r.planar) {
        const Eigen::Matrix2Xd n2 = planarNodes(r, c.nodes3);
        c.planarModel->spanCoordinates(span, n2, qm, c.planar, q);
        const auto& sp = c.planarModel->span(span);
        const double offset = r.normal.dot(c.nodes3.col(0));
        for (int k = 0; k < numPoints; ++k) {
            const double sk = q[sp.s1Index()] + (q[sp.s2Index()] - q[sp.s1Index()]) * k / (numPoints - 1);
            const Eigen::Vector2d p = sp.position(q, std::min(sk, q[sp.s2Index()]));
            out.push_back(toSimTK(r.e1 * p[0] + r.e2 * p[1] + r.normal * offset));
        }
    } else {
        const RopeModel<3>& model = spatialModel(s, r);
        model.spanCoordinates(span, c.nodes3, qm, c.spatial, q);
        const auto& sp = model.span(span);
        for (int k = 0; k < numPoints; ++k) {
            const double sk = q[sp.s1Index()] + (q[sp.s2Index()] - q[sp.s1Index()]) * k / (numPoints - 1);
            out.push_back(toSimTK(Eigen::Vector3d(sp.position(q, std::min(sk, q[sp.s2Index()])))));
        }
    }
    return out;
}

double ReevingSubsystem::Guts::spanStartMaterial(const State& s, const RopeRecord& r, int span) const {
    const RopeCache& c = positionCache(s).ropes[r.index];
    if (!(r.wraps[span].radius > 0))
        return (r.planar ? c.planar.materialCoordinates : c.spatial.materialCoordinates)[span];
    // A span leaving a wrapped sheave starts past its arc.
    if (r.planar) return c.planar.spanCoordinates(span)[r.planarModel->span(span).s1Index()];
    return c.spatial.spanCoordinates(span)[spatialModel(s, r).span(span).s1Index()];
}

std::pair<double, double> ReevingSubsystem::getSpanMaterialRange(const State& s, int rope, int span) const {
    const Guts& g = getGuts();
    const RopeRecord& r = ropeAt(g, rope);
    if (span < 0 || span >= r.numSpans())
        invalid("span index = " + std::to_string(span) + " is outside 0.." + std::to_string(r.numSpans() - 1));
    const RopeCache& c = g.positionCache(s).ropes[rope];
    const Eigen::VectorXd& sv = r.planar ? c.planar.materialCoordinates : c.spatial.materialCoordinates;
    return {g.spanStartMaterial(s, r, span), sv[span + 1]};
}

double ReevingSubsystem::getArcLength(const State& s, int rope, int node) const {
    const Guts& g = getGuts();
    const RopeRecord& r = ropeAt(g, rope);
    if (node < 0 || node >= r.numNodes())
        invalid("node index = " + std::to_string(node) + " is outside 0.." + std::to_string(r.numNodes() - 1));
    // (A wrapped drum, an end node, has no arc: the rope beyond its tangent point is stored rope.)
    if (!(r.wraps[node].radius > 0) || node == 0 || node + 1 == r.numNodes()) return 0.0;
    const RopeCache& c = g.positionCache(s).ropes[rope];
    return g.spanStartMaterial(s, r, node) - (r.planar ? c.planar.materialCoordinates : c.spatial.materialCoordinates)[node];
}

std::pair<double, double> ReevingSubsystem::getFleetAngles(const State& s, int rope, int span) const {
    const Guts& g = getGuts();
    const RopeRecord& r = ropeAt(g, rope);
    if (span < 0 || span >= r.numSpans())
        invalid("span index = " + std::to_string(span) + " is outside 0.." + std::to_string(r.numSpans() - 1));
    const RopeCache& c = g.positionCache(s).ropes[rope];
    if (r.planar) return {0.0, 0.0};
    return g.spatialModel(s, r).fleetAngles(c.spatial, span);
}

namespace {
// The span's axial law (the tension-only law of quasi-static spans is rounded near eps = 0).
const AxialLaw& lawOf(const ReevingSubsystem::Guts& g, const State& s, const detail::RopeRecord& r, int span) {
    return r.planar ? r.planarModel->span(span).axialLaw() : g.spatialModel(s, r).span(span).axialLaw();
}
}  // namespace

double ReevingSubsystem::getAxialForce(const State& s, int rope, int span, double sMaterial) const {
    const RopeRecord& r = ropeAt(getGuts(), rope);
    const double eps = strainAt(s, rope, span, sMaterial);
    return lawOf(getGuts(), s, r, span).force(eps);
}

double ReevingSubsystem::getTension(const State& s, int rope, int span, double sMaterial) const {
    const RopeRecord& r = ropeAt(getGuts(), rope);
    const double eps = strainAt(s, rope, span, sMaterial);
    return lawOf(getGuts(), s, r, span).force(eps) * std::sqrt(std::max(1.0 + 2.0 * eps, 0.0));
}

int ReevingSubsystem::getNumEvaluationFailures() const { return getGuts().numEvaluationFailures(); }
const std::string& ReevingSubsystem::getLastEvaluationFailure() const { return getGuts().lastEvaluationFailure(); }

double ReevingSubsystem::getSpanMaxStrain(const State& s, int rope, int span) const {
    const Guts& g = getGuts();
    const RopeRecord& r = ropeAt(g, rope);
    getSpanMaterialRange(s, rope, span);  // validates span
    const RopeCache& c = g.positionCache(s).ropes[rope];
    return r.planar ? r.planarModel->span(span).maxStrain(c.planar.spanCoordinates(span))
                    : g.spatialModel(s, r).span(span).maxStrain(c.spatial.spanCoordinates(span));
}

bool ReevingSubsystem::isSpanSlack(const State& s, int rope, int span) const {
    return getRopeSpec(rope).properties.tensionOnly && getSpanMaxStrain(s, rope, span) <= 0.0;
}

double ReevingSubsystem::strainAt(const State& s, int rope, int span, double sMaterial) const {
    const Guts& g = getGuts();
    const RopeRecord& r = ropeAt(g, rope);
    getSpanMaterialRange(s, rope, span);  // validates span
    const RopeCache& c = g.positionCache(s).ropes[rope];
    Eigen::VectorXd q;
    const Eigen::VectorXd qm = g.modal(g.getZ(s), r, false);
    // QuasiStatic spans: once the accelerations are known (Stage::Dynamics), the strain includes the
    // mode-acceleration correction (RopeModel::recoverInertialStrain), which also moves the material
    // coordinates at the sheaves slightly; the point is taken at the same relative position
    // xi = (s - s1) / (s2 - s1) of the corrected span, so span ends stay span ends.
    const bool recovered = s.getSystemStage() >= Stage::Dynamics;
    auto strainOf = [&](const auto& model, const auto& nodes, const auto& data) {
        model.spanCoordinates(span, nodes, qm, data, q);
        if (!recovered) return model.span(span).strain(q, sMaterial);
        const auto& sp = model.span(span);
        const double s1 = q[sp.s1Index()], s2 = q[sp.s2Index()];
        const double xi = std::clamp((sMaterial - s1) / (s2 - s1), 0.0, 1.0);
        model.span(span).strain(q, sMaterial);  // validates sMaterial against the span's range
        model.recoveredSpanCoordinates(span, nodes, qm, data, q);
        const double r1 = q[sp.s1Index()], r2 = q[sp.s2Index()];
        return sp.strain(q, xi >= 1.0 ? r2 : r1 + xi * (r2 - r1));
    };
    if (r.planar) return strainOf(*c.planarModel, g.planarNodes(r, c.nodes3), c.planar);
    return strainOf(g.spatialModel(s, r), c.nodes3, c.spatial);
}

Vec3 ReevingSubsystem::getNodeForce(const State& s, int rope, int node) const {
    const Guts& g = getGuts();
    const RopeRecord& r = ropeAt(g, rope);
    if (node < 0 || node >= r.numNodes())
        invalid("node index = " + std::to_string(node) + " is outside 0.." + std::to_string(r.numNodes() - 1));
    if (s.getSystemStage() < Stage::Dynamics)
        throw std::logic_error("ReevingSubsystem::getNodeForce: realize the state to Stage::Dynamics first");
    const RopeCache& c = g.positionCache(s).ropes[rope];
    // The rope's equation at its external coordinates is S xdd - h = f (f: force on the rope); the
    // body receives -f = h - S xdd.
    const Eigen::VectorXd reaction = g.ropeReaction(s, r, c);
    if (r.planar) return toSimTK(r.planeBasis * reaction.segment<2>(2 * node));
    return toSimTK(Eigen::Vector3d(reaction.segment<3>(3 * node)));
}

double ReevingSubsystem::getMaterialCoordinate(const State& s, int rope, int node) const {
    const RopeRecord& r = ropeAt(getGuts(), rope);
    if (node < 0 || node >= r.numNodes())
        invalid("node index = " + std::to_string(node) + " is outside 0.." + std::to_string(r.numNodes() - 1));
    const RopeCache& c = getGuts().positionCache(s).ropes[rope];
    return (r.planar ? c.planar.materialCoordinates : c.spatial.materialCoordinates)[node];
}

double ReevingSubsystem::getConstraintError(const State& s, int rope, int sheave) const {
    const RopeRecord& r = ropeAt(getGuts(), rope);
    if (sheave < 1 || sheave >= r.numNodes() - 1)
        invalid("sheave node index = " + std::to_string(sheave) + " is outside 1.." + std::to_string(r.numNodes() - 2));
    const RopeCache& c = getGuts().positionCache(s).ropes[rope];
    return r.planar ? c.planarModel->constraintError(c.planar, sheave)
                    : getGuts().spatialModel(s, r).constraintError(c.spatial, sheave);
}

double ReevingSubsystem::getMaxConstraintError(const State& s) const {
    double worst = 0;
    for (int i = 0; i < getNumRopes(); ++i)
        for (int k = 1; k + 1 < getGuts().ropes[i].numNodes(); ++k)
            if (visitNodeKind(getGuts().ropes[i].nodeSpec(k).kind,
                              [](auto unit) { return decltype(unit)::kTensionEquality; }))
                worst = std::max(worst, std::abs(getConstraintError(s, i, k)));
    return worst;
}

namespace {
// Node `node` of rope r, or std::invalid_argument.
void checkNode(const RopeRecord& r, int node) {
    if (node < 0 || node >= r.numNodes())
        invalid("node index = " + std::to_string(node) + " is outside 0.." + std::to_string(r.numNodes() - 1));
}
// std::logic_error unless s is realized to Stage::Position.
void checkPosition(const State& s, const char* query) {
    if (s.getSystemStage() < Stage::Position)
        throw std::logic_error(std::string("ReevingSubsystem::") + query + ": realize the state to Stage::Position first");
}
}  // namespace

double ReevingSubsystem::getNodeRadius(int rope, int node) const {
    const RopeRecord& r = ropeAt(getGuts(), rope);
    checkNode(r, node);
    const NodeSpec& spec = r.nodeSpec(node);
    return visitNodeKind(spec.kind, [&](auto unit) { return decltype(unit)::bendRadius(spec); });
}

std::pair<double, double> ReevingSubsystem::getNodeMaterialInterval(const State& s, int rope, int node) const {
    const Guts& g = getGuts();
    const RopeRecord& r = ropeAt(g, rope);
    checkNode(r, node);
    checkPosition(s, "getNodeMaterialInterval");
    const NodeBend bend{g, r, node, s};
    return visitNodeKind(r.nodeSpec(node).kind, [&](auto unit) { return decltype(unit)::heldInterval(bend); });
}

Vec3 ReevingSubsystem::getNodeBendAxis(const State& s, int rope, int node) const {
    const Guts& g = getGuts();
    const RopeRecord& r = ropeAt(g, rope);
    checkNode(r, node);
    checkPosition(s, "getNodeBendAxis");
    const NodeBend bend{g, r, node, s};
    const Vec3 axis = visitNodeKind(r.nodeSpec(node).kind, [&](auto unit) { return decltype(unit)::bendAxis(bend); });
    if (r.planar) {  // the plane normal's side
        const Vec3 normal = unitPlaneNormal(r);
        const double along = SimTK::dot(axis, normal);
        return along > 0 ? normal : along < 0 ? Vec3(-normal) : Vec3(0);
    }
    const double len = axis.norm();
    return len > 0 ? Vec3(axis / len) : Vec3(0);
}

double ReevingSubsystem::getStoredRope(const State& s, int rope, int node) const {
    const Guts& g = getGuts();
    const RopeRecord& r = ropeAt(g, rope);
    checkNode(r, node);
    checkPosition(s, "getStoredRope");
    const int d = r.drivenIndex(node);
    if (d < 0) return 0.0;  // a Fixed or Sliding node: nothing turns rope onto it
    return r.driven[static_cast<std::size_t>(d)].role.storedRope(r.drivenRun(g, d), g.positionCache(s).ropes[rope]);
}

std::vector<Vec3> ReevingSubsystem::sampleSpan(const State& s, int rope, int span, int numPoints) const {
    getSpanMaterialRange(s, rope, span);  // validates
    if (numPoints < 2) invalid("sampleSpan: numPoints = " + std::to_string(numPoints) + " must be >= 2");
    return getGuts().sample(s, rope, span, numPoints);
}

std::vector<Vec3> ReevingSubsystem::sampleArc(const State& s, int rope, int node, int numPoints) const {
    const Guts& g = getGuts();
    const RopeRecord& r = ropeAt(g, rope);
    if (node < 0 || node >= r.numNodes())
        invalid("node index = " + std::to_string(node) + " is outside 0.." + std::to_string(r.numNodes() - 1));
    if (!(r.wraps[node].radius > 0) || node == 0 || node + 1 == r.numNodes())
        invalid("sampleArc: rope '" + r.spec.name + "' node " + std::to_string(node) +
                " is not a wrapped sheave (SheaveModel::Wrapped): it has no arc");
    if (numPoints < 2) invalid("sampleArc: numPoints = " + std::to_string(numPoints) + " must be >= 2");
    const RopeCache& c = g.positionCache(s).ropes.at(rope);
    // The centre: in the rope plane for a planar rope (the plane sample() draws the spans in:
    // through the start node); the station itself for a spatial one. The groove's axis n: the
    // plane normal, or the sheave's own.
    const Eigen::Vector3d station = c.nodes3.col(node);
    const Eigen::Vector3d centre =
        r.planar ? Eigen::Vector3d(station - r.normal * (r.normal.dot(station) - r.normal.dot(c.nodes3.col(0)))) : station;
    const Eigen::Vector3d n = r.planar ? r.normal : r.grooveAxis(node, c.nodes3);
    // The arc starts where span k - 1 ends and turns about sigma n (GrooveArc's kinematics):
    // r(theta) = c + cos(theta) d + sin(theta) (sigma n x d), theta in [0, alpha].
    const Eigen::Vector3d d = toEigen(g.sample(s, rope, node - 1, 2).back()) - centre;
    const Eigen::Vector3d w = (static_cast<double>(r.wraps[node].wrapSense) * n).cross(d);
    const double alpha = getArcLength(s, rope, node) / r.wraps[node].radius;
    std::vector<Vec3> out;
    out.reserve(numPoints);
    for (int k = 0; k < numPoints; ++k) {
        const double theta = alpha * k / (numPoints - 1);
        out.push_back(toSimTK(Eigen::Vector3d(centre + std::cos(theta) * d + std::sin(theta) * w)));
    }
    return out;
}

double ReevingSubsystem::calcRopeKineticEnergy(const State& s) const {
    const Guts& g = getGuts();
    // The velocity-level rope data live beside the position-level data and are refreshed by every
    // realize(Velocity): reading them below that stage would return stale numbers.
    if (s.getSystemStage() < Stage::Velocity)
        throw std::logic_error("ReevingSubsystem::calcRopeKineticEnergy: realize the state to Stage::Velocity first");
    double t = 0;
    for (size_t i = 0; i < g.ropes.size(); ++i) {
        const RopeCache& c = g.positionCache(s).ropes[i];
        t += g.ropes[i].planar ? c.planar.kineticEnergy : c.spatial.kineticEnergy;
    }
    return t;
}

double ReevingSubsystem::calcRopePotentialEnergy(const State& s) const { return getGuts().calcPotentialEnergy(s); }

double ReevingSubsystem::getDampingPower(const State& s) const {
    const Guts& g = getGuts();
    if (s.getSystemStage() < Stage::Velocity)
        throw std::logic_error("ReevingSubsystem::getDampingPower: realize the state to Stage::Velocity first");
    double p = 0;
    for (size_t i = 0; i < g.ropes.size(); ++i) {
        const RopeCache& c = g.positionCache(s).ropes[i];
        p += g.ropes[i].planar ? c.planar.dampingPower : c.spatial.dampingPower;
    }
    return p;
}

double ReevingSubsystem::getDampingWork(const State& s) const {
    double w = 0;
    for (const RopeRecord& r : getGuts().ropes)
        if (r.dampingZOffset >= 0) w += getGuts().getZ(s)[r.dampingZOffset];
    return w;
}

double ReevingSubsystem::calcMechanicalEnergy(const State& s) const {
    const MultibodySystem& mbs = getGuts().mbs();
    return mbs.calcKineticEnergy(s) + mbs.calcPotentialEnergy(s) + calcRopeKineticEnergy(s);
}

}  // namespace SimbodyReeving
