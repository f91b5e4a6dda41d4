// ReevingSubsystem: construction, addRope (validation), rope accessors and the modal state.

#include "ReevingSubsystemGuts.h"

#include <cmath>
#include <memory>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

using SimTK::ForceSubsystem;
using SimTK::MultibodySystem;
using SimTK::State;
using SimTK::Vec3;
using SimTK::Vector;

namespace SimbodyReeving {

using namespace detail;

// ---- ReevingSubsystem ------------------------------------------------------------------------

bool ReevingSubsystem::isInstanceOf(const ForceSubsystem& s) {
    return dynamic_cast<const Guts*>(&s.getSubsystemGuts()) != nullptr;
}
const ReevingSubsystem& ReevingSubsystem::downcast(const ForceSubsystem& s) {
    return static_cast<const ReevingSubsystem&>(s);
}
ReevingSubsystem& ReevingSubsystem::updDowncast(ForceSubsystem& s) { return static_cast<ReevingSubsystem&>(s); }
ReevingSubsystem::Guts& ReevingSubsystem::updGuts() { return dynamic_cast<Guts&>(updSubsystemGuts()); }
const ReevingSubsystem::Guts& ReevingSubsystem::getGuts() const { return dynamic_cast<const Guts&>(getSubsystemGuts()); }

ReevingSubsystem::ReevingSubsystem(MultibodySystem& system, const Vec3& gravity) {
    if (!finite(gravity)) invalid("gravity [m/s^2] = " + str(gravity) + " must be finite");
    adoptSubsystemGuts(new Guts(gravity));
    system.addForceSubsystem(*this);
}

int ReevingSubsystem::addRope(const RopeSpec& specIn) {
    Guts& g = updGuts();
    RopeRecord r;
    r.spec = specIn;
    const RopeSpec& spec = r.spec;
    const std::string who = "rope '" + spec.name + "': ";
    auto checkAnchor = [&](const RopeAnchor& a, const char* which) {
        if (a.body.isEmptyHandle()) invalid(who + which + " anchor has no body");
        if (!finite(a.station)) invalid(who + which + " anchor station [m] = " + str(a.station) + " must be finite");
    };
    checkAnchor(spec.start, "start");
    checkAnchor(spec.end, "end");
    for (size_t k = 0; k < spec.sheaves.size(); ++k) {
        const DeviationSheave& sh = spec.sheaves[k];
        const std::string name = who + "sheave " + std::to_string(k);
        if (sh.body.isEmptyHandle()) invalid(name + " has no body");
        if (!finite(sh.centre)) invalid(name + " centre [m] = " + str(sh.centre) + " must be finite");
        if (!std::isfinite(sh.radius) || !(sh.radius > 0)) {
            std::ostringstream o;
            o << name << " radius [m] = " << sh.radius << " must be finite and > 0";
            invalid(o.str());
        }
    }
    // Consecutive path points on the same body must not coincide.
    for (int k = 0; k + 1 < r.numNodes(); ++k) {
        const auto a = r.node(k), b = r.node(k + 1);
        if (a.first->getMobilizedBodyIndex() == b.first->getMobilizedBodyIndex() && (a.second - b.second).norm() == 0)
            invalid(who + "path points " + std::to_string(k) + " and " + std::to_string(k + 1) +
                    " coincide (same body, station " + str(a.second) + ")");
    }
    if (!std::isfinite(spec.unstretchedLength) || !(spec.unstretchedLength > 0)) {
        std::ostringstream o;
        o << who << "unstretchedLength [m] = " << spec.unstretchedLength << " must be finite and > 0";
        invalid(o.str());
    }
    try {
        validate(spec.properties);
    } catch (const std::invalid_argument& e) {
        invalid(who + e.what());
    }
    r.spanOptions.assign(r.numSpans(), spec.spanDefaults);
    for (const auto& [index, options] : spec.spanOverrides) {
        if (index < 0 || index >= r.numSpans())
            invalid(who + "span override index = " + std::to_string(index) + " is outside 0.." +
                    std::to_string(r.numSpans() - 1));
        r.spanOptions[index] = options;
    }
    if (!finite(spec.planeNormal)) invalid(who + "planeNormal = " + str(spec.planeNormal) + " must be finite");
    r.planar = spec.planeNormal.norm() > 0;
    const Eigen::Vector3d gravity = toEigen(g.gravity());
    try {
        if (r.planar) {
            const Eigen::Matrix3d frame = makeReferenceFrame(toEigen(spec.planeNormal));
            r.normal = frame.col(0);
            r.e1 = frame.col(1);
            r.e2 = frame.col(2);
            r.planeBasis << r.e1, r.e2;
            if (std::abs(r.normal.dot(gravity)) > 1e-12 * gravity.norm())
                invalid(who + "gravity " + str(g.gravity()) + " is not in the rope plane (normal " +
                        str(spec.planeNormal) + ")");
            std::vector<SpanModel<2>> spans;
            const Eigen::Vector2d g2(r.e1.dot(gravity), r.e2.dot(gravity));
            for (int j = 0; j < r.numSpans(); ++j) spans.emplace_back(spec.properties, r.spanOptions[j], g2);
            r.planarModel = std::make_shared<const RopeModel<2>>(std::move(spans), spec.unstretchedLength);
            r.numModal = r.planarModel->numModalCoordinates();
        } else {
            for (int j = 0; j < r.numSpans(); ++j) {
                const SpanModel<3> probe(spec.properties, r.spanOptions[j], gravity);  // validates options
                r.numModal += probe.numModalCoordinates();
                if (r.spanOptions[j].axialDynamics == AxialDynamics::QuasiStatic)
                    r.numModal -= probe.axialModes();  // condensed: not states
            }
        }
    } catch (const std::invalid_argument& e) {
        const std::string msg = e.what();
        if (msg.rfind("ReevingSubsystem", 0) == 0) throw;
        invalid(who + msg);
    }
    g.ropes.push_back(std::move(r));
    invalidateSubsystemTopologyCache();
    return static_cast<int>(g.ropes.size()) - 1;
}

int ReevingSubsystem::getNumRopes() const { return static_cast<int>(getGuts().ropes.size()); }

const RopeSpec& ReevingSubsystem::getRopeSpec(int rope) const { return ropeAt(getGuts(), rope).spec; }
int ReevingSubsystem::getNumSpans(int rope) const { return ropeAt(getGuts(), rope).numSpans(); }
bool ReevingSubsystem::isPlanar(int rope) const { return ropeAt(getGuts(), rope).planar; }
int ReevingSubsystem::getNumModalCoordinates(int rope) const { return ropeAt(getGuts(), rope).numModal; }

Vector ReevingSubsystem::getModalCoordinates(const State& s, int rope) const {
    const RopeRecord& r = ropeAt(getGuts(), rope);
    return getGuts().getZ(s)(r.zOffset, r.numModal);
}
Vector ReevingSubsystem::getModalRates(const State& s, int rope) const {
    const RopeRecord& r = ropeAt(getGuts(), rope);
    return getGuts().getZ(s)(r.zOffset + r.numModal, r.numModal);
}
void ReevingSubsystem::setModalCoordinates(State& s, int rope, const Vector& q) const {
    const RopeRecord& r = ropeAt(getGuts(), rope);
    if (q.size() != r.numModal)
        invalid("setModalCoordinates: size " + std::to_string(q.size()) + " differs from " + std::to_string(r.numModal));
    getGuts().updZ(s)(r.zOffset, r.numModal) = q;
}
void ReevingSubsystem::setModalRates(State& s, int rope, const Vector& qdot) const {
    const RopeRecord& r = ropeAt(getGuts(), rope);
    if (qdot.size() != r.numModal)
        invalid("setModalRates: size " + std::to_string(qdot.size()) + " differs from " + std::to_string(r.numModal));
    getGuts().updZ(s)(r.zOffset + r.numModal, r.numModal) = qdot;
}

void ReevingSubsystem::setDecorationResolution(int pointsPerSpan) {
    if (pointsPerSpan < 2) invalid("decoration resolution = " + std::to_string(pointsPerSpan) + " must be >= 2");
    updGuts().decorationPoints = pointsPerSpan;
}

}  // namespace SimbodyReeving
