#pragma once
/// @file
/// Bending history and bending-cycle count per section of a rope, taken from the rope's material
/// coordinates over the states of a run (docs/rope-life.md); an optional Palmgren-Miner damage
/// estimate with Feyrer's bending-fatigue law, every constant given by the user.

#include "SimbodyReeving/simbody/ReevingSubsystem.h"

#include <Simbody.h>

#include <limits>
#include <vector>

namespace SimbodyReeving {

/// The bend's sense relative to the section's previous bend (RopeBendEvent::relation).
enum class BendRelation {
    First,    ///< no earlier bend of this section is known (counted as a simple bend)
    Same,     ///< bent to the same side of the rope as its previous bend: a simple bend
    Reverse,  ///< bent to the other side: a reverse bend (weighted by reverseBendFactor)
};

/// One passage of a rope section onto or off a sheave, drum or traction sheave.
struct RopeBendEvent {
    double time = 0;           ///< [s], interpolated linearly between the two samples around it
    int section = 0;           ///< the section's index (section i covers [i, i + 1) sectionLength of s)
    int node = 0;              ///< the rope node (0 = start, ReevingSubsystem node numbering)
    bool onto = true;          ///< true: onto the sheave (bent); false: off it (straightened)
    double diameterRatio = 0;  ///< D / d [-]: 2 R of the node over the rope diameter
    double tension = 0;        ///< axial force of the span the section comes from (onto) or goes to (off) [N]
    BendRelation relation = BendRelation::First;  ///< the bend's sense against the section's previous bend
    double cycles = 0;         ///< bending cycles credited: 1/2, times reverseBendFactor for a reverse bend
};

/// How the rope is divided and counted (RopeLifeMonitor's constructor).
struct RopeLifeOptions {
    /// Rope diameter d [m], > 0 (the nominal diameter; there is no default).
    double ropeDiameter = 0;
    /// Unstretched length of each section [m], > 0 (default 0.1 m).
    double sectionLength = 0.1;
    /// Weight w_r [-] of a reverse bending cycle against a simple one, >= 1, required (NaN: not
    /// given). The literature weights a reverse bend higher (Feyrer, Wire Ropes, 2nd ed. 2015, on
    /// reverse bending; Verreet, Calculating the service life of running steel wire ropes, CASAR
    /// 1998, on its weighting): its value depends on the rope and on the free length between the
    /// sheaves and is not built in here. 1 counts reverse bends as simple ones.
    double reverseBendFactor = std::numeric_limits<double>::quiet_NaN();
    /// Upper edges T_1 < T_2 < ... < T_m of the tension bins [N], finite, increasing; bin j
    /// (0..m) holds the half cycles with tension in (T_j, T_{j+1}] (T_0 = -inf, T_{m+1} = +inf),
    /// so there are m + 1 bins. Empty: one bin.
    std::vector<double> tensionBinEdges;
};

/// Feyrer's bending-fatigue regression for the number of simple bending cycles N a rope survives
/// on a sheave (Feyrer, Wire Ropes: Tension, Endurance, Reliability, 2nd ed., Springer 2015,
/// chapter 3, bending over sheaves), in the form
///     lg N = b0 + (b1 + b4 lg(D/d)) (lg(S / d^2) - c_R) + b2 lg(D/d) + b3 lg(d),
/// lg the base-10 logarithm, S the rope's tensile force [N], d the rope diameter [mm] (so S / d^2
/// in N/mm^2), D/d the diameter ratio [-], b0..b4 the constants Feyrer tabulates per rope
/// construction and c_R the wire-grade term (Feyrer writes 0.4 lg(R_0 / 1770), R_0 the wires'
/// nominal tensile strength in N/mm^2). The constants decide what N means (the mean cycles to
/// break or to discard, with Feyrer's factors for the groove, the lubrication... folded into b0).
/// No constant has a default: every field is NaN until given, and RopeLifeMonitor::estimateDamage
/// throws when one is missing. Check the form and the constants against the book together: this
/// project does not ship them.
struct FeyrerBendingLaw {
    double b0 = std::numeric_limits<double>::quiet_NaN();  ///< [-]
    double b1 = std::numeric_limits<double>::quiet_NaN();  ///< [-]
    double b2 = std::numeric_limits<double>::quiet_NaN();  ///< [-]
    double b3 = std::numeric_limits<double>::quiet_NaN();  ///< [-] (per lg of d in mm)
    double b4 = std::numeric_limits<double>::quiet_NaN();  ///< [-]
    double wireGradeTerm = std::numeric_limits<double>::quiet_NaN();  ///< c_R [-]

    /// True if every constant is finite.
    bool complete() const;
    /// N [-] for tension S [N], rope diameter d [m] (converted to mm inside) and D/d [-]; +inf for
    /// S <= 0 (a slack rope is not loaded: the law does not apply and no damage is counted).
    /// @throws std::invalid_argument if a constant is missing (complete() false), d <= 0 or D/d < 1.
    double cyclesToFailure(double tension, double ropeDiameter, double diameterRatio) const;
};

/// Per-section results (RopeLifeMonitor::sections()).
struct RopeSectionCount {
    double start = 0;      ///< material coordinate where the section starts [m]
    double cycles = 0;     ///< bending cycles, reverse bends weighted by reverseBendFactor [-]
    double simpleCycles = 0;   ///< cycles of simple (Same or First) bends, unweighted [-]
    double reverseCycles = 0;  ///< cycles of reverse bends, unweighted [-]
    double maxTension = 0;     ///< largest tension at any of its bend events [N] (0 without any)
    std::vector<double> cyclesByTension;  ///< weighted cycles per tension bin (RopeLifeOptions::tensionBinEdges)
};

/// The damage estimate (RopeLifeMonitor::estimateDamage).
struct RopeDamageEstimate {
    std::vector<double> damagePerWorkCycle;  ///< per section: Miner sum / work cycles [-]
    int worstSection = -1;                   ///< the section with the largest damage (-1: none)
    double worstSectionCentre = 0;           ///< its centre's material coordinate [m]
    double worstDamagePerWorkCycle = 0;      ///< its damage per work cycle [-]
};

/// Counts the bending cycles of each section of one rope of a ReevingSubsystem from the states of
/// a run. A post-processor: the user passes states in time order to record() (from the loop that
/// steps the integrator, e.g. after each TimeStepper::stepTo); the monitor only reads them, adds no
/// event and no state, so the run's results are the same with and without it.
///
/// The rope is divided into sections of unstretched length l_s (RopeLifeOptions::sectionLength):
/// section i covers material coordinates [s_min + i l_s, s_min + (i + 1) l_s), s_min the smallest
/// material coordinate of the rope at the first sample (with rope on a start drum: the drum's
/// stored rope included, ReevingSubsystem::getStoredRope), up to the largest (the last section
/// may be shorter). Each node that bends the rope (ReevingSubsystem::getNodeRadius > 0: every
/// node but an anchor) has an interval of material coordinates
/// (ReevingSubsystem::getNodeMaterialInterval):
///   - a sheave k (DeviationSheave, TurningSheave, TractionSheave): [s_a, s_b], s_a the end of
///     span k - 1 (the arrival tangent point of a wrapped sheave) and s_b the start of span k (the
///     departure tangent point); at a point sheave s_a = s_b, so a pass is one crossing;
///   - a WinchDrum at the start: sigma < s_a of span 0; at the end: sigma > s_b of span N - 1 (the
///     tangent point of a wrapped drum, the node itself of a point drum).
/// A section goes onto a node once it lies wholly in the node's interval, and off once it lies
/// wholly outside (past a point sheave: wholly on its other side); while it straddles an end of
/// the interval it stays where it was. So a rope oscillating by less than a section's length
/// across a tangent point or a point sheave (a bouncing load) adds no cycles. At the first
/// sample, the section's centre sigma_i decides. Between two samples each section's side of
/// each node is compared: getting on is a bend ("onto"), getting off a straightening ("off"),
/// both at the time where the interval's end passed sigma_i (linear between the samples; the
/// earlier sample if that happened before). Each onto and each off counts 1/2 bending cycle:
/// a full pass over a sheave (onto and off) is one cycle, a bend and the straightening
/// (Feyrer 2015; Verreet 1998: straight - bent - straight), winding onto a drum and off it
/// 1/2 each, and a section that goes onto a sheave and back off the same side (a stroke
/// shorter than the arc) is also one cycle (it was bent and straightened). A section that never
/// gets wholly on or past a sheave is not counted; sampling does not affect which passes are
/// counted, only the times and tensions recorded (a node's interval that sweeps over a section
/// and back within one sample interval is missed, so sample finer than such reversals).
///
/// The bend's sense: the side of the rope the sheave or drum is on, as the axis b about which the
/// rope turns when running from its start to its end: at a point sheave from the chords u_in, u_out
/// of the two spans, b = u_in x u_out / |...| (a rope running straight over it has no sense: that
/// bend counts as First and the next is compared with the one before it); at a wrapped sheave its wrap sense (SheaveModel::Wrapped:
/// DeviationSheave::wrapSense about the plane normal or the groove's axis, -sense times the pin
/// axis for a TurningSheave or TractionSheave); at a drum the pin axis times +payoutSense at the
/// start, -payoutSense at the end (ReevingSubsystem::getNodeBendAxis). A bend whose b points
/// against that of the section's previous bend (b . b_prev < 0) is a reverse bend and both its halves count reverseBendFactor times; a planar
/// rope keeps its sides (b = +-n), on a spatial rope b is compared in Ground (the rope's twist
/// between the sheaves is not modelled). A section on a node at the first sample carries that
/// node's sense as its previous bend.
///
/// The tension of an event is the axial force (ReevingSubsystem::getAxialForce) at the end of the
/// span on the section's side of the node, interpolated between the samples; each half cycle is
/// binned by its own event's tension.
class RopeLifeMonitor {
public:
    /// @param reeving the ropes, all added; the monitor keeps a reference to it.
    /// @param rope the rope to count (ReevingSubsystem::addRope's index).
    /// @param options the rope's diameter, the section length, the reverse-bend weight and the
    ///        tension bins (RopeLifeOptions).
    /// @throws std::invalid_argument if rope is out of range, ropeDiameter is not finite and > 0,
    ///         sectionLength is not finite and > 0, reverseBendFactor is not given or < 1, the bin
    ///         edges are not finite and increasing, or a sheave or drum of the rope has D/d = 2 R / d
    ///         below 1 (named in the message).
    RopeLifeMonitor(const ReevingSubsystem& reeving, int rope, const RopeLifeOptions& options);

    /// Takes one state of the run (realized to Stage::Position here if it is not yet). The first
    /// call fixes the sections and where each one lies; later calls count what passed since the
    /// previous one.
    /// @throws std::invalid_argument if the state's time is earlier than the previous sample's.
    void record(const SimTK::State& state);

    /// Number of samples recorded.
    int numSamples() const { return numSamples_; }
    /// Number of sections (0 before the first sample).
    int numSections() const { return static_cast<int>(sections_.size()); }
    /// The sections' counts.
    const std::vector<RopeSectionCount>& sections() const { return sections_; }
    /// Every onto and off event, in the order detected (by sample; within a sample by node and section).
    const std::vector<RopeBendEvent>& events() const { return events_; }
    /// Length of section i [m] (sectionLength, the last one possibly shorter).
    double sectionLength(int section) const;
    /// The section with the most weighted cycles (the first of equals; -1 before the first sample).
    int mostBentSection() const;

    /// Palmgren-Miner damage per section: D_i = sum over the nodes k and tension bins j of
    /// c_ikj / N(T_ikj, d, D_k / d) / workCycles, c_ikj the weighted cycles section i collected on
    /// node k in bin j and T_ikj the largest tension among them (conservative within a bin; exact
    /// when the tension is constant), N from `law`. The rope is expected to be discarded (or to
    /// break, as the constants define N) when the damage accumulated reaches 1; 1 / D_i work
    /// cycles for the worst section.
    /// @param law Feyrer's bending-fatigue law with every constant given (FeyrerBendingLaw).
    /// @param workCycles how many work cycles the recorded run covers [-], > 0.
    /// @throws std::invalid_argument if a constant of `law` is missing or workCycles is not > 0.
    RopeDamageEstimate estimateDamage(const FeyrerBendingLaw& law, double workCycles) const;

private:
    struct NodeSample {
        double lower = 0, upper = 0;           // the node's interval [m] (drums: one side infinite)
        double tensionLower = 0, tensionUpper = 0;  // axial force of the span below / above it [N]
        SimTK::Vec3 bendAxis{0};               // b, unit vector in Ground
    };
    struct SectionState {
        std::vector<int> side;        // per watched node: -1 below its interval, 0 on it, +1 above
        SimTK::Vec3 lastBendAxis{0};  // b of the previous bend (0: none)
        double currentWeight = 1;     // weight of the bend the section is on (1 or reverseBendFactor)
        BendRelation currentRelation = BendRelation::First;  // that bend's relation
    };
    struct NodeBin {
        double cycles = 0;
        double maxTension = -std::numeric_limits<double>::infinity();
    };

    std::vector<NodeSample> sampleNodes(const SimTK::State& state) const;
    static int sideOf(double sigma, const NodeSample& n);
    static int wholeSideOf(double sigma, double halfLength, const NodeSample& n, int previous);
    void addEvent(int section, int watchedIndex, bool onto, double time, double tension, const SimTK::Vec3& axis);
    int binOf(double tension) const;

    const ReevingSubsystem& reeving_;
    int rope_;
    RopeLifeOptions options_;
    std::vector<int> watchedNodes_;       // node indices of sheaves and drums
    std::vector<double> diameterRatios_;  // D/d per watched node
    double sMin_ = 0, sMax_ = 0;
    int numSamples_ = 0;
    double lastTime_ = 0;
    std::vector<NodeSample> lastNodes_;
    std::vector<SectionState> sectionStates_;
    std::vector<RopeSectionCount> sections_;
    std::vector<std::vector<std::vector<NodeBin>>> bins_;  // [section][watched node][tension bin]
    std::vector<RopeBendEvent> events_;
};

}  // namespace SimbodyReeving
