// RopeLifeMonitor: bending cycles per rope section against hand counts of the passes over the
// sheaves and the drum (a two-fall hook block lifted and lowered through a stroke longer than the
// rope between its sheaves; an S-shaped reeving whose sheaves bend the rope to alternate sides),
// the Palmgren-Miner damage of a constant-tension case against cycles / N of Feyrer's law, and bad
// input rejected with a message. Counting rules (docs/rope-life.md): a pass over a sheave (onto and
// off) is one bending cycle, onto and off a drum half a cycle each (Feyrer, Wire Ropes, 2nd ed.
// 2015; Verreet, Calculating the service life of running steel wire ropes, CASAR 1998); a bend to
// the other side of the rope than the section's previous bend is a reverse bend, weighted by the
// user's reverseBendFactor.
#include "SimbodyReeving/simbody/ReevingSubsystem.h"
#include "SimbodyReeving/simbody/RopeLifeMonitor.h"
#include "support/ExpectThrowMessage.h"

#include <gtest/gtest.h>

#include <Simbody.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <memory>
#include <vector>

using namespace SimbodyReeving;
using SimTK::MobilizedBody;
using SimTK::Stage;
using SimTK::State;
using SimTK::Vec3;

namespace {

constexpr double kG = 9.81;
constexpr double kPi = 3.14159265358979323846;

SimTK::Body::Rigid pointMass(double m) { return SimTK::Body::Rigid(SimTK::MassProperties(m, Vec3(0), SimTK::Inertia(1e-3 * m))); }
SimTK::Body::Rigid wheel(double J) { return SimTK::Body::Rigid(SimTK::MassProperties(1.0, Vec3(0), SimTK::Inertia(J, J, J))); }
// A frame whose x axis is Ground's y: a Slider along it moves vertically.
SimTK::Transform vertical(const Vec3& p) {
    const SimTK::Mat33 R(0, -1, 0,  //
                         1, 0, 0,   //
                         0, 0, 1);
    return SimTK::Transform(SimTK::Rotation(R, true), p);
}

/// A rope from a winch drum (a Pin about Ground's z at the origin, radius 0.25 m,
/// payoutSense -1: a growing pin angle hauls rope in, s_0 = R theta) over sheaves of radius 0.2 m,
/// planar (normal z), point sheaves unless `model` says otherwise, to a load of 1000 kg on a vertical Slider. The drum turns from rest to rest,
/// theta(t) = -A cos(pi t / T_lift) (Motion::Sinusoid): it hauls in 2 A R over T_lift and pays the
/// same out over the next T_lift. A stiff rope (EA 1e7 N) without modes: the falls stay straight.
struct DrumScene {
    static constexpr double R = 0.25, M = 1000.0, liftTime = 20.0;
    SimTK::MultibodySystem system;
    SimTK::SimbodyMatterSubsystem matter{system};
    SimTK::GeneralForceSubsystem forces{system};
    SimTK::Force::Gravity gravity{forces, matter, Vec3(0, -kG, 0)};
    MobilizedBody::Pin drum{matter.Ground(), SimTK::Transform(), wheel(2.0), SimTK::Transform()};
    std::unique_ptr<MobilizedBody::Slider> load;
    std::unique_ptr<ReevingSubsystem> reeving;
    double amplitude;  // A [rad]

    /// `haul` [m] = 2 A R. `build` fills the path (sheaves and end) given the load body.
    DrumScene(double haul, double loadX, double loadY, double unstretchedLength,
              const std::function<void(RopeSpec&, const MobilizedBody& ground, const MobilizedBody& load)>& build,
              SheaveModel model = SheaveModel::Point)
        : amplitude(haul / (2 * R)) {
        SimTK::Motion::Sinusoid(drum, SimTK::Motion::Position, amplitude, kPi / liftTime, -0.5 * kPi);
        load = std::make_unique<MobilizedBody::Slider>(matter.Ground(), vertical(Vec3(loadX, 0, 0)), pointMass(M),
                                                       vertical(Vec3(0)));
        reeving = std::make_unique<ReevingSubsystem>(system, Vec3(0, -kG, 0));
        RopeSpec spec;
        spec.name = "hoist rope";
        spec.start = WinchDrum{drum, R, 30.0, -1};
        build(spec, matter.Ground(), *load);
        spec.properties = RopeProperties{0.05, 1e7, 0.0};
        spec.unstretchedLength = unstretchedLength;
        spec.spanDefaults.axialModes = 0;
        spec.spanDefaults.transverseModes = 0;
        spec.planeNormal = Vec3(0, 0, 1);
        spec.sheaveModel = model;
        reeving->addRope(spec);
        system.realizeTopology();
        initialLoadY = loadY;
    }
    double initialLoadY;

    /// Static equilibrium at t = 0 (the drum at -A), then the run to `endTime`, the monitor fed
    /// every 0.05 s.
    void run(RopeLifeMonitor& monitor, double endTime) {
        State s = system.getDefaultState();
        load->setOneQ(s, 0, initialLoadY);
        reeving->findStaticEquilibrium(s, 1e-12);
        SimTK::RungeKuttaMersonIntegrator integ(system);
        integ.setAccuracy(1e-9);
        SimTK::TimeStepper ts(system, integ);
        ts.initialize(s);
        monitor.record(integ.getState());
        const int steps = static_cast<int>(std::lround(endTime / 0.05));
        for (int k = 1; k <= steps; ++k) {
            ts.stepTo(0.05 * k);
            monitor.record(integ.getState());
        }
    }
};

/// The sections whose centres lie in (lo + margin, hi - margin).
std::vector<int> sectionsInside(const RopeLifeMonitor& m, double lo, double hi, double margin) {
    std::vector<int> out;
    for (int i = 0; i < m.numSections(); ++i) {
        const double c = m.sections()[i].start + 0.5 * m.sectionLength(i);
        if (c > lo + margin && c < hi - margin) out.push_back(i);
    }
    return out;
}

RopeLifeOptions options(double reverseBendFactor) {
    RopeLifeOptions o;
    o.ropeDiameter = 0.02;
    o.sectionLength = 0.1;
    o.reverseBendFactor = reverseBendFactor;
    return o;
}

}  // namespace

// A two-fall hook block: drum (0, 0) -> top sheave (0, H) on Ground -> hook sheave on the block at
// x = 0.5 -> dead end on Ground at (1, H), H = 12 m; the block starts at y0 = 1 m. The drum hauls in
// Delta = 14 m and pays it out again (one work cycle), so the block rises Delta / 2 = 7 m: more
// than the rope between the two sheaves (l0 = sqrt(0.5^2 + 11^2) = 11.011 m), so the sections
// between s_2(0) and s_1(0) + Delta run over the hook sheave and then over the top sheave.
//
// Hand count, material coordinates s (s_0 = R theta at the drum, -7 m at the start):
//   s_0 (drum):  -7 -> 7            (the drum's R theta, exact)
//   s_1 (top):   -7 + H = 5 -> 19   (span 0 is H long and fixed)
//   s_2 (hook):  5 + l0 = 16.011 -> 16.011 + 7 = 23.011  (each fall shortens by Delta / 2)
// Lifting moves the rope towards the drum: a section at s is passed by the hook sheave, then the
// top sheave, then reaches the drum; lowering runs it back. Bend senses (the rope running from the
// drum to the dead end, about +z): drum clockwise (payoutSense -1 about +z), top sheave clockwise
// (up, then down to the right), hook sheave counter-clockwise (down, under, up): the hook and top
// sheaves bend the rope to opposite sides.
//   s in (16.011, 19):  hook (first bend, simple) 1, top (reverse) 1; lowering: top (same as its
//                       previous bend, at the top: simple) 1, hook (reverse) 1
//                       -> 4 cycles: 2 simple + 2 reverse; weighted 2 + 2 w_r
//   s in (19, 23.011):  hook 1 up, 1 down (same side): 2 simple
//   s in (7, 16.011):   top 1 up, 1 down: 2 simple
//   s in (5, 7):        top 1 + drum 1/2 up, drum 1/2 + top 1 down (drum and top both clockwise):
//                       3 simple
//   s in (-7, 5):       drum 1/2 on, 1/2 off: 1 simple
//   s < -7 or s > 23.011: 0
// The edges carry the rope's strain (T / EA = 5e-4: about 6 mm over 12 m): sections within 0.15 m
// of an edge are left out (a 0.1 m section straddling it collects part of a pass).
TEST(RopeLifeMonitor, TwoFallHookBlockCollectsTheHandCountedCycles) {
    const double H = 12.0, y0 = 1.0, haul = 14.0, l0 = std::hypot(0.5, H - y0);
    const double length = H + 2 * l0 - 0.5 * haul;  // s_N - s_0 = H + 2 l0 with s_0 = -7 at the start
    DrumScene scene(haul, 0.5, y0, length, [&](RopeSpec& spec, const MobilizedBody& ground, const MobilizedBody& block) {
        spec.sheaves = {DeviationSheave{ground, Vec3(0, H, 0), 0.2}, DeviationSheave{block, Vec3(0), 0.2}};
        spec.end = RopeAnchor{ground, Vec3(1, H, 0)};
    });
    const double reverseWeight = 2.0;  // a test input, not a literature value
    RopeLifeMonitor monitor(*scene.reeving, 0, options(reverseWeight));
    scene.run(monitor, 2 * DrumScene::liftTime);

    struct Band {
        double lo, hi, simple, reverse;
    };
    const double s1 = -7 + H, s2 = s1 + l0;
    const std::vector<Band> bands = {{s2, s1 + haul, 2, 2},         {s1 + haul, s2 + 0.5 * haul, 2, 0},
                                     {-7 + haul, s2, 2, 0},         {s1, -7 + haul, 3, 0},
                                     {-7, s1, 1, 0},                {-37, -7, 0, 0},
                                     {s2 + 0.5 * haul, length, 0, 0}};
    int checked = 0;
    double worst = 0;
    for (const Band& b : bands) {
        for (int i : sectionsInside(monitor, b.lo, b.hi, 0.15)) {
            const RopeSectionCount& c = monitor.sections()[i];
            EXPECT_EQ(c.simpleCycles, b.simple) << "section " << i << " at s = " << c.start;
            EXPECT_EQ(c.reverseCycles, b.reverse) << "section " << i << " at s = " << c.start;
            EXPECT_EQ(c.cycles, b.simple + reverseWeight * b.reverse) << "section " << i;
            worst = std::max(worst, std::abs(c.simpleCycles + c.reverseCycles - b.simple - b.reverse));
            ++checked;
        }
    }
    const int both = static_cast<int>(sectionsInside(monitor, s2, s1 + haul, 0.15).size());
    const RopeSectionCount& most = monitor.sections()[monitor.mostBentSection()];
    std::printf("[ life ] two-fall hook block, 14 m hauled in and out: %d of %d sections checked, %d pass both "
                "sheaves; largest count difference %.3g; most bent section at s = %.2f m: %.1f cycles (%.1f reverse), "
                "largest tension %.1f N; %zu events\n",
                checked, monitor.numSections(), both, worst, most.start, most.cycles, most.reverseCycles,
                most.maxTension, monitor.events().size());
    EXPECT_GE(both, 25);  // (16.011, 19) less the margins: 2.6 m of 0.1 m sections
    // Left out: the sections within 0.15 m of one of the 8 band edges (the rope's ends included),
    // at most 3 per edge (measured: 20 in all).
    EXPECT_GE(checked, monitor.numSections() - 3 * 8);
    EXPECT_EQ(most.cycles, 2 + 2 * reverseWeight);
    // The tension at the events: about M g / 2 = 4905 N per fall (the falls lean by 4 to 7 degrees
    // and the block accelerates by A R (pi / T)^2 / 2 = 0.086 m/s^2 at most).
    EXPECT_GT(most.maxTension, 4800.0);
    EXPECT_LT(most.maxTension, 5100.0);
}

// The same hook block with the rope on the grooves (SheaveModel::Wrapped): the drum (radius 0.25 m,
// turning clockwise about +z) at the origin, the top sheave at (-0.05, H), the hook sheave at
// x = 0.35, the dead end at (0.55, H), so every fall hangs vertically and each sheave carries half a
// turn, pi 0.2 = 0.628 m of rope. A section is on a sheave between the arrival and departure
// tangent points, so beside the full passes there are sections that run only partly over a
// sheave: on it at the start, or on it where the lift turns into the lowering; those are bent and
// straightened once (1 cycle). Hand count in x = s - d0, d0 = -7 - 0.25 pi / 2 the drum's tangent
// point at the start (the rope leaves the drum a quarter turn before its top, s_0 = R theta = -7):
//   drum (0, 14); top sheave on (12, 12.628) at the start, at the turn (26, 26.628), passed fully
//   by (12.628, 26); hook sheave on (23.628, 24.257) at the start, (30.628, 31.257) at the turn,
//   passed fully by (24.257, 30.628) (the top's arrival point a_1 = d0 + 12, its departure
//   b_1 = a_1 + 0.628, the hook's arrival a_2 = b_1 + 11, b_2 = a_2 + 0.628; the top's points move
//   by 14, the hook's by 7). Per band, simple + reverse cycles over the lift and the lowering:
//   (0, 12)            drum 1/2 + 1/2:                                              1 + 0
//   (12, 12.628)       top off 1/2, drum 1, top on 1/2:                             2 + 0
//   (12.628, 14)       top 1, drum 1, top 1:                                        3 + 0
//   (14, 23.628)       top 1 + 1:                                                   2 + 0
//   (23.628, 24.257)   hook off 1/2 (first), top 1 (reverse), top 1 (same),
//                      hook on 1/2 (reverse):                                     1.5 + 1.5
//   (24.257, 26)       hook 1 (first), top 1 (reverse), top 1 (same), hook 1 (reverse): 2 + 2
//   (26, 26.628)       hook 1 (first), top on 1/2 and off 1/2 (reverse), hook 1 (reverse): 1 + 2
//   (26.628, 30.628)   hook 1 + 1:                                                  2 + 0
//   (30.628, 31.257)   hook on 1/2, off 1/2:                                        1 + 0
TEST(RopeLifeMonitor, WrappedHookBlockCountsFullAndPartialPasses) {
    const double H = 12.0, y0 = 1.0, haul = 14.0, arc = kPi * 0.2, quarter = 0.25 * kPi / 2;
    const double fall = H - y0, length = (H - quarter + 2 * arc + 2 * fall) - 0.5 * haul;
    DrumScene scene(
        haul, 0.35, y0, length,
        [&](RopeSpec& spec, const MobilizedBody& ground, const MobilizedBody& block) {
            DeviationSheave top{ground, Vec3(-0.05, H, 0), 0.2}, hook{block, Vec3(0), 0.2};
            top.wrapSense = -1;  // up its left side, over, down its right side: clockwise about +z
            hook.wrapSense = 1;  // down its left side, under, up its right side: counter-clockwise
            spec.sheaves = {top, hook};
            spec.end = RopeAnchor{ground, Vec3(0.55, H, 0)};
        },
        SheaveModel::Wrapped);
    const double reverseWeight = 2.0;  // a test input
    RopeLifeMonitor monitor(*scene.reeving, 0, options(reverseWeight));
    scene.run(monitor, 2 * DrumScene::liftTime);
    const double d0 = -7 - quarter, a1 = 12, b1 = a1 + arc, a2 = b1 + fall, b2 = a2 + arc;
    struct Band {
        double lo, hi, simple, reverse;
    };
    const std::vector<Band> bands = {{-30, 0, 0, 0},
                                     {0, a1, 1, 0},
                                     {a1, b1, 2, 0},
                                     {b1, 14, 3, 0},
                                     {14, a2, 2, 0},
                                     {a2, b2, 1.5, 1.5},
                                     {b2, a1 + haul, 2, 2},
                                     {a1 + haul, b1 + haul, 1, 2},
                                     {b1 + haul, a2 + 0.5 * haul, 2, 0},
                                     {a2 + 0.5 * haul, b2 + 0.5 * haul, 1, 0},
                                     {b2 + 0.5 * haul, length + 7 - d0, 0, 0}};
    int checked = 0, partial = 0;
    for (const Band& b : bands)
        for (int i : sectionsInside(monitor, d0 + b.lo, d0 + b.hi, 0.15)) {
            const RopeSectionCount& c = monitor.sections()[i];
            EXPECT_EQ(c.simpleCycles, b.simple) << "section " << i << " at x = " << c.start - d0;
            EXPECT_EQ(c.reverseCycles, b.reverse) << "section " << i << " at x = " << c.start - d0;
            EXPECT_EQ(c.cycles, b.simple + reverseWeight * b.reverse) << "section " << i;
            ++checked;
            if (b.hi - b.lo < 1) ++partial;
        }
    std::printf("[ life ] wrapped two-fall hook block, 14 m hauled in and out: %d of %d sections checked, %d of "
                "them in the bands that run partly over a sheave\n",
                checked, monitor.numSections(), partial);
    EXPECT_GE(partial, 4 * 3);  // 4 bands 0.628 m wide less the 0.15 m margins: 3 or 4 sections each (measured 12)
    // Left out: at most 3 sections at each of the 12 band edges (measured in the message).
    EXPECT_GE(checked, monitor.numSections() - 3 * 12);
}

/// The S-shaped reeving: drum (0, 0) -> sheave A (0, 5) -> sheave B (0.5, 0) -> sheave C (6, 0) ->
/// load on a Slider at x = 6.5, 10 m below C; point sheaves on Ground. The drum hauls in 8 m (half a
/// period of its sinusoid) and the load rises 8 m.
struct SReeving {
    static constexpr double haul = 8.0, fallX = 0.5, fall0 = 10.0;
    static double lengthAB() { return std::hypot(0.5, 5.0); }
    static double length() { return 5 + lengthAB() + 5.5 + std::hypot(fallX, fall0) - 0.5 * haul; }
    DrumScene scene;
    RopeLifeMonitor monitor;
    explicit SReeving(const RopeLifeOptions& o)
        : scene(haul, 6.0 + fallX, -fall0, length(),
                [](RopeSpec& spec, const MobilizedBody& ground, const MobilizedBody& load) {
                    spec.sheaves = {DeviationSheave{ground, Vec3(0, 5, 0), 0.2},
                                    DeviationSheave{ground, Vec3(0.5, 0, 0), 0.2},
                                    DeviationSheave{ground, Vec3(6, 0, 0), 0.2}};
                    spec.end = RopeAnchor{load, Vec3(0)};
                }),
          monitor(*scene.reeving, 0, o) {
        scene.run(monitor, DrumScene::liftTime);
    }
};

// Turning senses about +z, the rope running from the drum to the load: the drum clockwise
// (payoutSense -1), A clockwise (from up to down towards B), B counter-clockwise (from down to +x),
// C clockwise (from +x down to the load): A, B and C each bend the rope to the other side than the
// sheave before. Hand count with s_0 = R theta = -4 m at the start and the span lengths 5 (drum-A),
// sqrt(0.5^2 + 5^2) = 5.025 (A-B) and 5.5 (B-C): s_1 (A) = 1 -> 9, s_2 (B) = 6.025 -> 14.025,
// s_3 (C) = 11.525 -> 19.525, s_0 (drum) = -4 -> 4. Hauling in moves the rope towards the drum,
// so a section meets C, B, A, the drum in that order:
//   s in (11.525, 14.025):  C (first bend) 1 simple, then B (reverse) 1 reverse
//   s in (6.025, 9):        B (first) 1 simple, then A (reverse) 1 reverse
//   s in (14.025, 19.525):  C only: 1 simple;   (9, 11.525): B only: 1 simple
//   s in (4, 6.025):        A only: 1 simple;   (1, 4): A 1 + drum 1/2 (clockwise like A): 1.5 simple
//   s in (-4, 1):           drum 1/2 simple;    the rest: 0
TEST(RopeLifeMonitor, SShapedReevingCountsItsReverseBends) {
    const double reverseWeight = 3.0;  // a test input, not a literature value
    SReeving s(options(reverseWeight));
    const RopeLifeMonitor& monitor = s.monitor;
    const double sB = 1 + SReeving::lengthAB(), sC = sB + 5.5, L = SReeving::length();
    struct Band {
        double lo, hi, simple, reverse;
    };
    const std::vector<Band> bands = {{sC, sB + 8, 1, 1}, {sB, 9, 1, 1},   {sB + 8, sC + 8, 1, 0}, {9, sC, 1, 0},
                                     {4, sB, 1, 0},      {1, 4, 1.5, 0},  {-4, 1, 0.5, 0},        {-34, -4, 0, 0},
                                     {sC + 8, L, 0, 0}};
    int checked = 0, reverse = 0;
    for (const Band& b : bands)
        for (int i : sectionsInside(monitor, b.lo, b.hi, 0.15)) {
            const RopeSectionCount& c = monitor.sections()[i];
            EXPECT_EQ(c.simpleCycles, b.simple) << "section " << i << " at s = " << c.start;
            EXPECT_EQ(c.reverseCycles, b.reverse) << "section " << i << " at s = " << c.start;
            EXPECT_EQ(c.cycles, b.simple + reverseWeight * b.reverse) << "section " << i;
            ++checked;
            if (c.reverseCycles > 0) ++reverse;
        }
    int reverseEvents = 0;
    for (const RopeBendEvent& e : monitor.events())
        if (e.relation == BendRelation::Reverse && e.onto) {
            ++reverseEvents;
            EXPECT_TRUE(e.node == 1 || e.node == 2) << "a reverse bend onto node " << e.node;  // onto A or B only
        }
    std::printf("[ life ] S reeving, 8 m hauled in: %d of %d sections checked, %d with reverse bends, %d reverse "
                "bends onto A or B\n",
                checked, monitor.numSections(), reverse, reverseEvents);
    EXPECT_GE(reverse, 2 * 24);  // (11.525, 14.025) and (6.025, 9) less the margins
    // Left out: at most 3 sections at each of the 10 band edges (the rope's ends included; measured: 26).
    EXPECT_GE(checked, monitor.numSections() - 3 * 10);
}

// Palmgren-Miner with Feyrer's law (RopeLifeMonitor::estimateDamage): a section that ran over one
// sheave once, at the load's tension, has the damage cycles / N(T, d, D/d) of the law, N evaluated
// here from its form (FeyrerBendingLaw): lg N = b0 + (b1 + b4 lg(D/d)) (lg(S / d^2) - c_R)
// + b2 lg(D/d) + b3 lg(d), S [N], d [mm]. The constants are arbitrary test inputs, not a rope's.
TEST(RopeLifeMonitor, ConstantTensionDamageIsCyclesOverN) {
    RopeLifeOptions o = options(3.0);
    o.tensionBinEdges = {5000.0, 20000.0};  // the load's 9810 N falls in the middle bin
    SReeving s(o);
    FeyrerBendingLaw law;
    law.b0 = 1.5;
    law.b1 = 0.8;
    law.b2 = 0.9;
    law.b3 = -0.3;
    law.b4 = -0.1;
    law.wireGradeTerm = 0.05;
    const RopeDamageEstimate damage = s.monitor.estimateDamage(law, 1.0);
    // Sections that ran over C only: s in (14.025, 19.525).
    const double sC = 1 + SReeving::lengthAB() + 5.5;
    double worstRelative = 0, spread = 0;
    const std::vector<int> onlyC = sectionsInside(s.monitor, sC + 2.5, sC + 8, 0.15);
    for (int i : onlyC) {
        const RopeSectionCount& c = s.monitor.sections()[i];
        const double dmm = 20.0, ratio = 0.4 / 0.02;
        const double lgN = law.b0 + (law.b1 + law.b4 * std::log10(ratio)) * (std::log10(c.maxTension / (dmm * dmm)) -
                                                                             law.wireGradeTerm) +
                           law.b2 * std::log10(ratio) + law.b3 * std::log10(dmm);
        const double expected = c.cycles / std::pow(10.0, lgN);
        worstRelative = std::max(worstRelative, std::abs(damage.damagePerWorkCycle[i] - expected) / expected);
        EXPECT_EQ(c.cycles, 1.0);
        EXPECT_EQ(c.cyclesByTension[1], 1.0);
        double lo = INFINITY, hi = 0;
        for (const RopeBendEvent& e : s.monitor.events())
            if (e.section == i) lo = std::min(lo, e.tension), hi = std::max(hi, e.tension);
        spread = std::max(spread, (hi - lo) / hi);
    }
    std::printf("[ life ] constant tension, %zu sections over one sheave: damage vs cycles / N worst relative "
                "%.2e; tension spread between their onto and off %.2e; worst section at s = %.2f m, %.3e per "
                "work cycle\n",
                onlyC.size(), worstRelative, spread, damage.worstSectionCentre, damage.worstDamagePerWorkCycle);
    ASSERT_GE(onlyC.size(), 25u);
    EXPECT_LE(worstRelative, 1e-13);  // round-off of a power of ten
    // The worst section is one with a reverse bend (weighted 3): in (6.025, 9) or (11.525, 14.025).
    EXPECT_TRUE((damage.worstSectionCentre > 6.0 && damage.worstSectionCentre < 9.05) ||
                (damage.worstSectionCentre > 11.5 && damage.worstSectionCentre < 14.05))
        << damage.worstSectionCentre;
}

// Bad input: a clear std::invalid_argument naming what is wrong, and no monitor or estimate.
TEST(RopeLifeMonitor, BadInputIsRejectedNamingIt) {
    const double H = 12.0;
    DrumScene scene(2.0, 0.5, 1.0, H + 2 * std::hypot(0.5, 11.0) - 1.0, [&](RopeSpec& spec, const MobilizedBody& ground, const MobilizedBody& block) {
        spec.sheaves = {DeviationSheave{ground, Vec3(0, H, 0), 0.2}, DeviationSheave{block, Vec3(0), 0.2}};
        spec.end = RopeAnchor{ground, Vec3(1, H, 0)};
    });
    const ReevingSubsystem& r = *scene.reeving;
    RopeLifeOptions o = options(2.0);
    o.sectionLength = 0;
    EXPECT_THROW_MESSAGE(RopeLifeMonitor(r, 0, o), std::invalid_argument, "sectionLength [m] = 0 must be finite and > 0");
    o.sectionLength = -0.1;
    EXPECT_THROW_MESSAGE(RopeLifeMonitor(r, 0, o), std::invalid_argument, "sectionLength [m] = -0.1");
    o = options(2.0);
    o.ropeDiameter = 0.45;  // D/d = 0.4 / 0.45 at the sheaves of radius 0.2 m
    EXPECT_THROW_MESSAGE(RopeLifeMonitor(r, 0, o), std::invalid_argument, "node 1: D/d = 2 R / d = 2 * 0.2 / 0.45");
    o.ropeDiameter = 0;
    EXPECT_THROW_MESSAGE(RopeLifeMonitor(r, 0, o), std::invalid_argument, "ropeDiameter d [m] = 0");
    o = options(std::nan(""));
    EXPECT_THROW_MESSAGE(RopeLifeMonitor(r, 0, o), std::invalid_argument, "reverseBendFactor [-] is not given");
    o = options(0.5);
    EXPECT_THROW_MESSAGE(RopeLifeMonitor(r, 0, o), std::invalid_argument, "reverseBendFactor [-] = 0.5 must be");
    o = options(2.0);
    o.tensionBinEdges = {1000.0, 1000.0};
    EXPECT_THROW_MESSAGE(RopeLifeMonitor(r, 0, o), std::invalid_argument, "tensionBinEdges must increase");
    EXPECT_THROW_MESSAGE(RopeLifeMonitor(r, 1, options(2.0)), std::invalid_argument, "rope index = 1");

    RopeLifeMonitor monitor(r, 0, options(2.0));
    scene.run(monitor, 1.0);
    const std::vector<RopeSectionCount> before = monitor.sections();
    FeyrerBendingLaw law;  // no constants given
    law.b0 = 1.0;
    EXPECT_THROW_MESSAGE(monitor.estimateDamage(law, 1.0), std::invalid_argument, "the life law's constants are missing");
    law = FeyrerBendingLaw{1, 1, 1, 1, 1, 0};
    EXPECT_THROW_MESSAGE(monitor.estimateDamage(law, 0.0), std::invalid_argument, "workCycles = 0 must be");
    EXPECT_THROW_MESSAGE(law.cyclesToFailure(1000.0, 0.02, 0.5), std::invalid_argument, "D/d = 0.5 must be");
    ASSERT_EQ(monitor.sections().size(), before.size());
    for (std::size_t i = 0; i < before.size(); ++i) EXPECT_EQ(monitor.sections()[i].cycles, before[i].cycles);
    // States must come in time order.
    State s = scene.system.getDefaultState();
    EXPECT_THROW_MESSAGE(monitor.record(s), std::invalid_argument, "is earlier than the previous sample's");
}
