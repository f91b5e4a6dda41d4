// ReevingSubsystem: rope limits that end a run cleanly (a span at RopeSpec::minimumSpanLength:
// two-blocking or a drum hauling the last span in; a wrapped sheave's wrap angle at zero: the rope
// leaving the groove; a driven node's own, DrivenRole::limitMargin: a drum out of rope), and the
// driven-node queries (torque, power).

#include "ReevingSubsystemGuts.h"

#include <cmath>
#include <iomanip>
#include <limits>
#include <sstream>

using SimTK::MobilizedBody;
using SimTK::Stage;
using SimTK::State;

namespace SimbodyReeving {

using namespace detail;

double ReevingSubsystem::Guts::limitMargin(const State& s, std::string* which) const {
    const PositionCache& pc = positionCache(s);
    double margin = std::numeric_limits<double>::infinity();
    for (size_t i = 0; i < ropes.size(); ++i) {
        const RopeRecord& r = ropes[i];
        const Eigen::VectorXd& sv =
            r.planar ? pc.ropes[i].planar.materialCoordinates : pc.ropes[i].spatial.materialCoordinates;
        for (int j = 0; j < r.numSpans(); ++j) {
            // The span's material: s_{j+1} - s_j less the arc on a wrapped node j (its start is
            // s_j + l_j).
            const double length = sv[j + 1] - spanStartMaterial(s, r, j);
            const double m = length - r.spec.minimumSpanLength;
            if (m < margin) {
                margin = m;
                if (which) {
                    std::ostringstream o;
                    o << "rope '" << r.spec.name << "' span " << j << " (nodes " << j << "-" << j + 1
                      << "): its unstretched length reached minimumSpanLength = " << r.spec.minimumSpanLength
                      << " m (two-blocking, or a drum hauled the span in)";
                    *which = o.str();
                }
            }
        }
        // A wrapped sheave whose wrap angle falls to zero: the rope leaves its groove (the tangent
        // points meet; past them the rope would wrap the groove backwards).
        for (int k = 1; k + 1 < r.numNodes(); ++k) {
            if (!(r.wraps[k].radius > 0)) continue;
            const double arc = spanStartMaterial(s, r, k) - sv[k];
            if (arc < margin) {
                margin = arc;
                if (which)
                    *which = "rope '" + r.spec.name + "' sheave " + std::to_string(k) +
                             ": its wrap angle fell to 0 (the rope leaves the groove)";
            }
        }
        // The driven nodes' own limits (a winch drum out of rope).
        for (int d = 0; d < static_cast<int>(r.driven.size()); ++d)
            r.driven[d].role.limitMargin(r.drivenRun(*this, d), pc.ropes[i], margin, which);
        // A span of a spatial rope whose fleet angle at a wrapped node reaches kMaxFleetAngle: near
        // 90 degrees the span runs along the groove's axis, where it has no tangent point (as an
        // arc of the groove [m]: R (cos gamma - cos gamma_max)).
        if (!r.planar)
            for (int j = 0; j < r.numSpans(); ++j) {
                const auto [atStart, atEnd] = spatialModel(s, r).fleetAngles(pc.ropes[i].spatial, j);
                for (const auto& [gamma, k] : {std::pair<double, int>{atStart, j}, {atEnd, j + 1}}) {
                    if (!(r.wraps[k].radius > 0)) continue;
                    const double m = r.wraps[k].radius * (std::cos(gamma) - std::cos(kMaxFleetAngle));
                    if (m < margin) {
                        margin = m;
                        if (which) {
                            std::ostringstream o;
                            o << "rope '" << r.spec.name << "' span " << j << ": its fleet angle at node " << k
                              << " reached " << kMaxFleetAngle * 180 / SimTK::Pi
                              << " degrees (the span turns towards the groove's axis, where it has no tangent point)";
                            *which = o.str();
                        }
                    }
                }
            }
        // A wrapped gripping groove on a turning parent: the parent's turn about the groove's axis
        // is measured in (-pi, pi]; the run ends before it passes half a turn (as an arc of the
        // groove [m]: R (pi - |turn|)).
        for (const RopeRecord::DrivenNode& d : r.driven) {
            if (!d.angle.includesParentTurn(r.nodeSpec(d.node).body)) continue;
            const double turn = r.wraps[d.node].radius * (SimTK::Pi - std::abs(d.angle.parentTurn(angleSite(s, r, d))));
            if (turn < margin) {
                margin = turn;
                if (which)
                    *which = "rope '" + r.spec.name + "': the parent of the wrapped sheave or drum at node " +
                             std::to_string(d.node) + " turned half a turn about its axis (its turn is measured within "
                             "half a turn of Ground's orientation)";
            }
        }
    }
    return margin;
}

namespace {

/// Witness: the smallest margin to a rope limit [m]; when it falls through zero the run ends.
class RopeLimitEvent : public SimTK::TriggeredEventHandler {
public:
    RopeLimitEvent(const SimTK::System& system, SimTK::SubsystemIndex reeving)
        : SimTK::TriggeredEventHandler(Stage::Position), system_(system), reeving_(reeving) {
        getTriggerInfo().setTriggerOnRisingSignTransition(false);
        getTriggerInfo().setTriggerOnFallingSignTransition(true);
        getTriggerInfo().setRequiredLocalizationTimeWindow(1e-6);
    }
    SimTK::Real getValue(const State& s) const override { return guts(s).limitMargin(s, nullptr); }
    void handleEvent(State& s, SimTK::Real, bool& shouldTerminate) const override {
        std::string which;
        guts(s).limitMargin(s, &which);
        std::ostringstream o;
        o << "ReevingSubsystem: run ended at t = " << std::setprecision(10) << s.getTime() << " s: " << which;
        guts(s).recordLimit(o.str());
        shouldTerminate = true;
    }

private:
    // The system owns this handler; the subsystem's guts are looked up through it (a handle
    // object the user keeps may not outlive the set-up code).
    const ReevingSubsystem::Guts& guts(const State&) const {
        return dynamic_cast<const ReevingSubsystem::Guts&>(system_.getSubsystem(reeving_).getSubsystemGuts());
    }

    const SimTK::System& system_;
    SimTK::SubsystemIndex reeving_;
};

}  // namespace

void detail::installLimitHandler(SimTK::System& system, SimTK::SubsystemIndex reeving) {
    system.addEventHandler(new RopeLimitEvent(system, reeving));  // the system owns it
}

// ---- driven-node queries ---------------------------------------------------------------------

namespace {
const RopeRecord::DrivenNode& drivenNodeAt(const RopeRecord& r, int node) {
    if (node < 0 || node >= r.numNodes())
        invalid("node index = " + std::to_string(node) + " is outside 0.." + std::to_string(r.numNodes() - 1));
    const int d = r.drivenIndex(node);
    if (d < 0)
        invalid(std::string("rope '") + r.spec.name + "' node " + std::to_string(node) +
                " is not a WinchDrum, TurningSheave or TractionSheave");
    return r.driven[d];
}
}  // namespace

double PinnedNodeHandle::getTorque(const State& s) const {
    const int rope = getRopeIndex(), node = getNodeIndex();
    const ReevingSubsystem::Guts& g = guts();
    const RopeRecord& r = ropeAt(g, rope);
    const RopeRecord::DrivenNode& d = drivenNodeAt(r, node);
    if (s.getSystemStage() < Stage::Dynamics)
        throw std::logic_error("PinnedNodeHandle::getTorque: realize the state to Stage::Dynamics first");
    const RopeCache& c = g.positionCache(s).ropes[rope];
    const Eigen::VectorXd reaction = g.ropeReaction(s, r, c);
    const int driven = r.drivenIndex(node);  // g'(theta) f_s: the rope's force on s as a torque
    return d.law.slope(c.drivenAngles[driven]) * reaction[r.drivenExternal(driven)];
}

double PinnedNodeHandle::getPower(const State& s) const {
    const double torque = getTorque(s);
    // The torque is the generalized force on the node's angle theta (its pin's, or the sheave
    // body's own when theta includes its parent's turn, DrivenAngle.h): its power is torque thetadot.
    const RopeRecord& r = ropeAt(guts(), getRopeIndex());
    return torque * guts().positionCache(s).ropes[r.index].drivenAngleRates[r.drivenIndex(getNodeIndex())];
}

const std::string& ReevingSubsystem::getLimitReached() const { return getGuts().limitReached(); }

}  // namespace SimbodyReeving
