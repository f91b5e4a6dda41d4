#include "SimbodyReeving/simbody/RopeLifeMonitor.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>
#include <limits>
#include <string>
#include <tuple>
#include <utility>

namespace SimbodyReeving {

namespace {

constexpr double kLifeInf = std::numeric_limits<double>::infinity();

[[noreturn]] void lifeMonitorInvalid(const std::string& what) { throw std::invalid_argument("RopeLifeMonitor: " + what); }

std::string lifeNumber(double v) {
    std::ostringstream o;
    o << v;
    return o.str();
}

}  // namespace

// ---- FeyrerBendingLaw ------------------------------------------------------------------------

bool FeyrerBendingLaw::complete() const {
    for (double c : {b0, b1, b2, b3, b4, wireGradeTerm})
        if (!std::isfinite(c)) return false;
    return true;
}

double FeyrerBendingLaw::cyclesToFailure(double tension, double ropeDiameter, double diameterRatio) const {
    if (!complete())
        throw std::invalid_argument(
            "FeyrerBendingLaw: every constant (b0, b1, b2, b3, b4, wireGradeTerm) must be given for the rope's "
            "construction (Feyrer, Wire Ropes, 2nd ed. 2015); one is missing (not finite)");
    if (!std::isfinite(ropeDiameter) || !(ropeDiameter > 0))
        throw std::invalid_argument("FeyrerBendingLaw: rope diameter d [m] = " + lifeNumber(ropeDiameter) +
                                    " must be finite and > 0");
    if (!std::isfinite(diameterRatio) || !(diameterRatio >= 1))
        throw std::invalid_argument("FeyrerBendingLaw: D/d = " + lifeNumber(diameterRatio) + " must be finite and >= 1");
    if (!(tension > 0)) return kLifeInf;
    const double dmm = 1000.0 * ropeDiameter;
    const double lgRatio = std::log10(diameterRatio);
    const double lgN = b0 + (b1 + b4 * lgRatio) * (std::log10(tension / (dmm * dmm)) - wireGradeTerm) +
                       b2 * lgRatio + b3 * std::log10(dmm);
    return std::pow(10.0, lgN);
}

// ---- RopeLifeMonitor --------------------------------------------------------------------------

RopeLifeMonitor::RopeLifeMonitor(const ReevingSubsystem& reeving, int rope, const RopeLifeOptions& options)
    : reeving_(reeving), rope_(rope), options_(options) {
    if (rope < 0 || rope >= reeving.getNumRopes())
        lifeMonitorInvalid("rope index = " + std::to_string(rope) + " is outside 0.." + std::to_string(reeving.getNumRopes() - 1));
    const double d = options.ropeDiameter;
    if (!std::isfinite(d) || !(d > 0)) lifeMonitorInvalid("ropeDiameter d [m] = " + lifeNumber(d) + " must be finite and > 0");
    if (!std::isfinite(options.sectionLength) || !(options.sectionLength > 0))
        lifeMonitorInvalid("sectionLength [m] = " + lifeNumber(options.sectionLength) + " must be finite and > 0");
    if (std::isnan(options.reverseBendFactor))
        lifeMonitorInvalid("reverseBendFactor [-] is not given: the weight of a reverse bending cycle against a simple one "
                "depends on the rope and the reeving (Feyrer 2015; Verreet 1998) and has no built-in value; "
                "give it (>= 1; 1 counts reverse bends as simple ones)");
    if (!std::isfinite(options.reverseBendFactor) || !(options.reverseBendFactor >= 1))
        lifeMonitorInvalid("reverseBendFactor [-] = " + lifeNumber(options.reverseBendFactor) + " must be finite and >= 1");
    for (std::size_t j = 0; j < options.tensionBinEdges.size(); ++j) {
        const double e = options.tensionBinEdges[j];
        if (!std::isfinite(e)) lifeMonitorInvalid("tensionBinEdges[" + std::to_string(j) + "] = " + lifeNumber(e) + " is not finite");
        if (j > 0 && !(e > options.tensionBinEdges[j - 1]))
            lifeMonitorInvalid("tensionBinEdges must increase: [" + std::to_string(j) + "] = " + lifeNumber(e) + " <= [" +
                    std::to_string(j - 1) + "] = " + lifeNumber(options.tensionBinEdges[j - 1]));
    }
    const RopeSpec& spec = reeving.getRopeSpec(rope);
    const int numNodes = reeving.getNumSpans(rope) + 1;
    for (int k = 0; k < numNodes; ++k) {
        const double radius = reeving.getNodeRadius(rope, k);
        if (!(radius > 0)) continue;  // an Anchor: the rope ends there unbent
        const double ratio = 2.0 * radius / d;
        if (!(ratio >= 1))
            lifeMonitorInvalid("rope '" + spec.name + "', node " + std::to_string(k) + ": D/d = 2 R / d = 2 * " + lifeNumber(radius) +
                    " / " + lifeNumber(d) + " = " + lifeNumber(ratio) + " is below 1 (a sheave narrower than the rope)");
        watchedNodes_.push_back(k);
        diameterRatios_.push_back(ratio);
    }
}

double RopeLifeMonitor::sectionLength(int section) const {
    if (section < 0 || section >= numSections())
        lifeMonitorInvalid("section index = " + std::to_string(section) + " is outside 0.." + std::to_string(numSections() - 1));
    const double start = sMin_ + section * options_.sectionLength;
    return std::min(options_.sectionLength, sMax_ - start);
}

std::vector<RopeLifeMonitor::NodeSample> RopeLifeMonitor::sampleNodes(const SimTK::State& state) const {
    reeving_.getSystem().realize(state, SimTK::Stage::Position);
    const int numSpans = reeving_.getNumSpans(rope_);
    std::vector<NodeSample> out(watchedNodes_.size());
    for (std::size_t w = 0; w < watchedNodes_.size(); ++w) {
        const int k = watchedNodes_[w];
        NodeSample& n = out[w];
        // The rope on the node (a drum's unbounded on its stored side) and the tension where it
        // arrives and where it leaves (at an end node, the one span's end there).
        std::tie(n.lower, n.upper) = reeving_.getNodeMaterialInterval(state, rope_, k);
        n.tensionLower = k > 0 ? reeving_.getAxialForce(state, rope_, k - 1, n.lower)
                               : reeving_.getAxialForce(state, rope_, 0, n.upper);
        n.tensionUpper = k < numSpans ? reeving_.getAxialForce(state, rope_, k, n.upper)
                                      : reeving_.getAxialForce(state, rope_, numSpans - 1, n.lower);
        n.bendAxis = reeving_.getNodeBendAxis(state, rope_, k);
    }
    return out;
}

int RopeLifeMonitor::sideOf(double sigma, const NodeSample& n) {
    return sigma < n.lower ? -1 : sigma > n.upper ? 1 : 0;
}

int RopeLifeMonitor::wholeSideOf(double sigma, double halfLength, const NodeSample& n, int previous) {
    if (sigma + halfLength < n.lower) return -1;  // wholly before the interval
    if (sigma - halfLength > n.upper) return 1;   // wholly after it
    if (sigma - halfLength >= n.lower && sigma + halfLength <= n.upper) return 0;  // wholly on it
    return previous;  // partly on: where it was
}

int RopeLifeMonitor::binOf(double tension) const {
    const auto& e = options_.tensionBinEdges;
    return static_cast<int>(std::lower_bound(e.begin(), e.end(), tension) - e.begin());
}

void RopeLifeMonitor::addEvent(int section, int w, bool onto, double time, double tension, const SimTK::Vec3& axis) {
    SectionState& st = sectionStates_[section];
    RopeBendEvent ev;
    ev.time = time;
    ev.section = section;
    ev.node = watchedNodes_[w];
    ev.onto = onto;
    ev.diameterRatio = diameterRatios_[w];
    ev.tension = tension;
    if (onto) {
        if (st.lastBendAxis.normSqr() == 0 || axis.normSqr() == 0)
            ev.relation = BendRelation::First;
        else
            ev.relation = SimTK::dot(axis, st.lastBendAxis) < 0 ? BendRelation::Reverse : BendRelation::Same;
        st.currentWeight = ev.relation == BendRelation::Reverse ? options_.reverseBendFactor : 1.0;
        st.currentRelation = ev.relation;
        if (axis.normSqr() > 0) st.lastBendAxis = axis;
    } else {
        ev.relation = st.currentRelation;
    }
    ev.cycles = 0.5 * st.currentWeight;
    RopeSectionCount& c = sections_[section];
    c.cycles += ev.cycles;
    (ev.relation == BendRelation::Reverse ? c.reverseCycles : c.simpleCycles) += 0.5;
    c.maxTension = std::max(c.maxTension, tension);
    const int bin = binOf(tension);
    c.cyclesByTension[bin] += ev.cycles;
    NodeBin& b = bins_[section][w][bin];
    b.cycles += ev.cycles;
    b.maxTension = std::max(b.maxTension, tension);
    events_.push_back(ev);
}

void RopeLifeMonitor::record(const SimTK::State& state) {
    const double t = state.getTime();
    if (numSamples_ > 0 && t < lastTime_)
        lifeMonitorInvalid("the state's time " + lifeNumber(t) + " s is earlier than the previous sample's " + lifeNumber(lastTime_) +
                " s: record states in time order");
    const std::vector<NodeSample> nodes = sampleNodes(state);
    const int numWatched = static_cast<int>(watchedNodes_.size());
    const double ls = options_.sectionLength;
    auto centreOf = [&](int i) {
        const double start = sMin_ + i * ls;
        return 0.5 * (start + std::min(start + ls, sMax_));
    };
    auto halfLengthOf = [&](int i) { return 0.5 * (std::min(sMin_ + (i + 1) * ls, sMax_) - (sMin_ + i * ls)); };
    if (numSamples_ == 0) {  // fix the sections and where they lie
        const int numSpans = reeving_.getNumSpans(rope_);
        // The rope's material range, the rope stored at its ends (on drums) included.
        sMin_ = reeving_.getSpanMaterialRange(state, rope_, 0).first;
        sMax_ = reeving_.getSpanMaterialRange(state, rope_, numSpans - 1).second;
        sMin_ -= reeving_.getStoredRope(state, rope_, 0);
        sMax_ += reeving_.getStoredRope(state, rope_, numSpans);
        const int numSections = std::max(1, static_cast<int>(std::ceil((sMax_ - sMin_) / ls - 1e-9)));
        const int numBins = static_cast<int>(options_.tensionBinEdges.size()) + 1;
        sections_.assign(numSections, RopeSectionCount{});
        sectionStates_.assign(numSections, SectionState{});
        bins_.assign(numSections, std::vector<std::vector<NodeBin>>(numWatched, std::vector<NodeBin>(numBins)));
        for (int i = 0; i < numSections; ++i) {
            sections_[i].start = sMin_ + i * ls;
            sections_[i].cyclesByTension.assign(numBins, 0.0);
            SectionState& st = sectionStates_[i];
            st.side.resize(numWatched);
            for (int w = 0; w < numWatched; ++w) {
                st.side[w] = sideOf(centreOf(i), nodes[w]);
                if (st.side[w] == 0) st.lastBendAxis = nodes[w].bendAxis;  // bent there before the run
            }
        }
    } else {
        const double t0 = lastTime_;
        for (int w = 0; w < numWatched; ++w) {
            const NodeSample &a = lastNodes_[w], &b = nodes[w];
            // Where the lower (upper) end of the node's interval passed the section's centre sigma (in
            // this sample interval or, clamped, at its start: the section may have straddled it before),
            // and the tension there.
            auto crossing = [&](double sigma, bool lowerEnd, double& time, double& tension) {
                const double e0 = lowerEnd ? a.lower : a.upper, e1 = lowerEnd ? b.lower : b.upper;
                const double lambda = e1 != e0 ? std::clamp((sigma - e0) / (e1 - e0), 0.0, 1.0) : 1.0;
                const double T0 = lowerEnd ? a.tensionLower : a.tensionUpper,
                             T1 = lowerEnd ? b.tensionLower : b.tensionUpper;
                time = t0 + lambda * (t - t0);
                tension = T0 + lambda * (T1 - T0);
            };
            // A section's side of the interval changes only where an end of the interval swept over
            // part of it since the previous sample: visit the sections over each end's sweep (with
            // one section's margin), in ascending order; a section met twice has changed already.
            for (const auto& [e0, e1] : {std::pair{a.lower, b.lower}, std::pair{a.upper, b.upper}}) {
                if (!std::isfinite(e0) || !std::isfinite(e1)) continue;  // a drum's open side
                const int first = std::max(0, static_cast<int>(std::floor((std::min(e0, e1) - sMin_) / ls)) - 1);
                const int last = std::min(numSections() - 1, static_cast<int>(std::floor((std::max(e0, e1) - sMin_) / ls)) + 1);
                for (int i = first; i <= last; ++i) {
                    int& side = sectionStates_[i].side[w];
                    const int now = wholeSideOf(centreOf(i), halfLengthOf(i), b, side);
                    if (now == side) continue;
                    const double sigma = centreOf(i);
                    double time = t, tension = 0;
                    if (side != 0) {  // onto, over the end of the interval on its side
                        crossing(sigma, side < 0, time, tension);
                        addEvent(i, w, true, time, tension, b.bendAxis);
                    }
                    if (now != 0) {  // off, over the end on the side it leaves to
                        crossing(sigma, now < 0, time, tension);
                        addEvent(i, w, false, time, tension, b.bendAxis);
                    }
                    side = now;
                }
            }
        }
    }
    lastNodes_ = nodes;
    lastTime_ = t;
    ++numSamples_;
}

int RopeLifeMonitor::mostBentSection() const {
    if (sections_.empty()) return -1;
    int best = 0;
    for (int i = 1; i < numSections(); ++i)
        if (sections_[i].cycles > sections_[best].cycles) best = i;
    return best;
}

RopeDamageEstimate RopeLifeMonitor::estimateDamage(const FeyrerBendingLaw& law, double workCycles) const {
    if (!law.complete())
        lifeMonitorInvalid("estimateDamage: the life law's constants are missing (b0, b1, b2, b3, b4 and wireGradeTerm must all "
                "be given for the rope's construction; none is built in)");
    if (!std::isfinite(workCycles) || !(workCycles > 0))
        lifeMonitorInvalid("estimateDamage: workCycles = " + lifeNumber(workCycles) + " must be finite and > 0");
    RopeDamageEstimate out;
    out.damagePerWorkCycle.assign(sections_.size(), 0.0);
    for (int i = 0; i < numSections(); ++i) {
        double damage = 0;
        for (std::size_t w = 0; w < watchedNodes_.size(); ++w)
            for (const NodeBin& b : bins_[i][w])
                if (b.cycles > 0)
                    damage += b.cycles / law.cyclesToFailure(b.maxTension, options_.ropeDiameter, diameterRatios_[w]);
        out.damagePerWorkCycle[i] = damage / workCycles;
        if (out.worstSection < 0 || out.damagePerWorkCycle[i] > out.worstDamagePerWorkCycle) {
            out.worstSection = i;
            out.worstDamagePerWorkCycle = out.damagePerWorkCycle[i];
        }
    }
    if (out.worstSection >= 0) {
        const double start = sMin_ + out.worstSection * options_.sectionLength;
        out.worstSectionCentre = 0.5 * (start + std::min(start + options_.sectionLength, sMax_));
    }
    return out;
}

}  // namespace SimbodyReeving
