#include "SimbodyReeving/scenes/BoomCraneScene.h"

#include "SimbodyReeving/element/WrapGeometry.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <cmath>
#include <sstream>
#include <stdexcept>

namespace SimbodyReeving {

void BoomCraneParameters::validate() const {
    auto check = [](const char* name, double v, bool ok, const char* range) {
        if (!std::isfinite(v) || !ok) {
            std::ostringstream o;
            o << "BoomCraneParameters: " << name << " = " << v << " must be finite and " << range;
            throw std::invalid_argument(o.str());
        }
    };
    auto checkPoint = [](const char* name, const SimTK::Vec3& p) {
        if (!(std::isfinite(p[0]) && std::isfinite(p[1]) && std::isfinite(p[2])))
            throw std::invalid_argument(std::string("BoomCraneParameters: ") + name + " must be finite");
    };
    check("g", g, g > 0, "> 0");
    check("superstructureMass", superstructureMass, superstructureMass > 0, "> 0");
    check("superstructureInertia", superstructureInertia, superstructureInertia > 0, "> 0");
    checkPoint("boomFoot", boomFoot);
    check("boomLength", boomLength, boomLength > 2, "> 2");
    check("boomMass", boomMass, boomMass > 0, "> 0");
    const double deg = 180.0 / SimTK::Pi;
    check("boomAngle [deg]", boomAngle * deg, boomAngle * deg > 10 && boomAngle * deg < 85, "in (10, 85)");
    checkPoint("aFrameTop", aFrameTop);
    checkPoint("luffDrumCentre", luffDrumCentre);
    check("luffSheaveRadius", luffSheaveRadius, luffSheaveRadius > 0, "> 0");
    check("luffSheaveSpacing", luffSheaveSpacing, luffSheaveSpacing > 0, "> 0");
    checkPoint("hoistDrumCentre", hoistDrumCentre);
    check("footSheaveOffset", footSheaveOffset, footSheaveOffset > 0 && footSheaveOffset < boomLength, "in (0, boomLength)");
    check("footSheaveHeight", footSheaveHeight, footSheaveHeight > 0, "> 0");
    check("hoistSheaveRadius", hoistSheaveRadius, hoistSheaveRadius > 0, "> 0");
    check("drumRadius", drumRadius, drumRadius > 0, "> 0");
    check("drumMass", drumMass, drumMass > 0, "> 0");
    check("drumInertia", drumInertia, drumInertia > 0, "> 0");
    check("ropeOnDrum", ropeOnDrum, ropeOnDrum > 0, "> 0");
    check("drumPitch", drumPitch, drumPitch >= 0 && drumPitch < 2 * SimTK::Pi * drumRadius, "in [0, 2 pi drumRadius)");
    check("hookMass", hookMass, hookMass > 0, "> 0");
    check("hookInertia", hookInertia, hookInertia > 0, "> 0");
    check("hookComBelow", hookComBelow, hookComBelow >= 0, ">= 0");
    check("hookPinBelow", hookPinBelow, hookPinBelow >= 0, ">= 0");
    check("initialHookDepth", initialHookDepth, initialHookDepth > 2, "> 2");
    check("payloadMass", payloadMass, payloadMass > 0, "> 0");
    check("payloadInertia", payloadInertia, payloadInertia > 0, "> 0");
    check("slingLength", slingLength, slingLength > 0, "> 0");
    check("rhoA", rhoA, rhoA > 0, "> 0");
    check("EA", EA, EA > 0, "> 0");
    check("EI", EI, EI >= 0, ">= 0");
    check("minimumSpanLength", minimumSpanLength, minimumSpanLength > 0, "> 0");
    if (sheaveModel != SheaveModel::Point && sheaveModel != SheaveModel::Wrapped)
        throw std::invalid_argument("BoomCraneParameters: sheaveModel is not a SheaveModel");
    // The A-frame must stand behind the boom's foot and above it, the drums clear of the sheaves.
    if (!(aFrameTop[0] < boomFoot[0] && aFrameTop[1] > boomFoot[1]))
        throw std::invalid_argument("BoomCraneParameters: aFrameTop must lie behind (smaller x) and above the boomFoot");
    if (!((luffDrumCentre - aFrameTop).norm() > luffSheaveRadius + 0.5))
        throw std::invalid_argument("BoomCraneParameters: luffDrumCentre must be at least 0.5 m clear of the A-frame sheaves");
}

namespace {

using SimTK::Vec3;

bool wrapped(const BoomCraneParameters& p) { return p.sheaveModel == SheaveModel::Wrapped; }

// A point of the boom's frame (x along the boom, y its normal in the luffing plane) in the
// superstructure's frame, the boom at `angle`.
Vec3 boomToSuper(const BoomCraneParameters& p, double angle, const Vec3& b) {
    const double c = std::cos(angle), s = std::sin(angle);
    return p.boomFoot + Vec3(c * b[0] - s * b[1], s * b[0] + c * b[1], b[2]);
}
Vec3 superToBoom(const BoomCraneParameters& p, double angle, const Vec3& x) {
    const Vec3 d = x - p.boomFoot;
    const double c = std::cos(angle), s = std::sin(angle);
    return Vec3(c * d[0] + s * d[1], -s * d[0] + c * d[1], d[2]);
}

// The reeving at rest, the boom at its nominal angle, in the superstructure's frame (= Ground's
// at slew 0) and in the nodes' body frames.
struct BoomLayout {
    // Luffing rope: drum, A-frame 1, tip sheave, A-frame 2, dead end; hoist rope: drum, foot, tip,
    // hook, dead end. Positions (superstructure frame).
    std::array<Vec3, 5> luff, hoist;
    // Stations on the boom (boom frame) of the luffing rope's nodes 2 and 4 and the hoist rope's 1, 2, 4.
    Vec3 luffTip, luffDeadEnd, hoistFoot, hoistTip, hoistDeadEnd;
    Vec3 hookCentre;  // hook sheave centre at rest (superstructure frame)
};

Vec3 unit(const Vec3& v) { return v / v.norm(); }

BoomLayout boomLayout(const BoomCraneParameters& p) {
    BoomLayout c;
    const double beta = p.boomAngle, Rl = p.luffSheaveRadius, Rh = p.hoistSheaveRadius;
    const Vec3 tip = boomToSuper(p, beta, Vec3(p.boomLength, 0, 0));
    // Luffing rope: the dead end a sheave radius off the tip on the A-frame's upper side of the
    // falls (where the last fall leaves A-frame sheave 2 in the wrapped model).
    const Vec3 toA = unit(p.aFrameTop - tip);
    const Vec3 upper(-toA[1], toA[0], 0);  // toA turned +90 degrees about z: above the falls
    c.luff = {p.luffDrumCentre, p.aFrameTop - Vec3(0, 0, p.luffSheaveSpacing), tip,
              p.aFrameTop + Vec3(0, 0, p.luffSheaveSpacing),
              tip + Rl * (upper[1] > 0 ? 1.0 : -1.0) * upper + Vec3(0, 0, p.luffSheaveSpacing)};
    // Hoist rope: the falls hang from the tip sheave's front (wrapped) or its centre (point), a
    // hook sheave diameter apart across the boom's plane.
    const Vec3 foot = boomToSuper(p, beta, Vec3(p.footSheaveOffset, p.footSheaveHeight, 0));
    const Vec3 tipSheave = tip - Vec3(0, 0, Rh);
    const double fallX = tip[0] + (wrapped(p) ? Rh : 0.0);
    c.hookCentre = Vec3(fallX, tip[1] - p.initialHookDepth, 0);
    c.hoist = {p.hoistDrumCentre, foot, tipSheave, c.hookCentre, Vec3(fallX, tip[1], Rh)};
    c.luffTip = superToBoom(p, beta, c.luff[2]);
    c.luffDeadEnd = superToBoom(p, beta, c.luff[4]);
    c.hoistFoot = superToBoom(p, beta, foot);
    c.hoistTip = superToBoom(p, beta, tipSheave);
    c.hoistDeadEnd = superToBoom(p, beta, c.hoist[4]);
    return c;
}

Eigen::Vector3d eig(const Vec3& v) { return Eigen::Vector3d(v[0], v[1], v[2]); }

// Groove axes and wrap senses of the sheaves (nodes 1..3) at rest. Every luffing sheave and the
// foot and tip sheaves turn about the superstructure's z, the hook sheave about the hook's x. The
// rope turns half a turn round the boom tip's luffing sheave and A-frame sheave 2, where the path
// through the centres cannot tell the sense (its turn lies across the groove's plane): clockwise
// seen from +z, round the tip sheave's far side and A-frame sheave 2's back (falls 1 and 3 above
// the falls' line, fall 2 below it). The other sheaves deflect the rope: their sense is the
// path's (wrapSenseFromPath).
struct SheaveGroove {
    Vec3 axis;
    int sense;
    double radius;
};
SheaveGroove grooveOf(const BoomCraneParameters& p, int rope, int k, const std::array<Vec3, 5>& nodes) {
    SheaveGroove g{Vec3(0, 0, 1), -1, rope == BoomCraneScene::kLuffingRope ? p.luffSheaveRadius : p.hoistSheaveRadius};
    if (rope == BoomCraneScene::kHoistRope && k == 3) g.axis = Vec3(1, 0, 0);
    if (rope == BoomCraneScene::kLuffingRope && k != 1) return g;
    GrooveCircle c;
    c.centre = eig(nodes[k]);
    c.axis = eig(g.axis);
    c.radius = g.radius;
    g.sense = wrapSenseFromPath(eig(nodes[k - 1]), c, eig(nodes[k + 1]));
    return g;
}

// Geometric length of a rope through `nodes` at rest [m], from the drum's node to the dead end,
// and its spans' part (`spans`). Point sheaves: the chords between the nodes. Wrapped: the spans
// between tangent points (WrapGeometry), the arcs R alpha on the sheaves (nodes 1..3), and on the
// drum the rope from its top to where it leaves, sigma R phi: a wrapped drum's material coordinate
// is counted from its top ("up", phi measured from there counter-clockwise about its axis, as the
// station map does; sigma = +1, the rope paid out by a positive angle leaving counter-clockwise
// about z).
double pathLength(const BoomCraneParameters& p, int rope, const std::array<Vec3, 5>& nodes, double& spans) {
    spans = 0;
    if (!wrapped(p)) {
        for (int k = 0; k < 4; ++k) spans += (nodes[k + 1] - nodes[k]).norm();
        return spans;
    }
    std::array<GrooveCircle, 4> circles;
    circles[0].centre = eig(nodes[0]);
    circles[0].axis = Eigen::Vector3d::UnitZ();
    circles[0].radius = p.drumRadius;
    circles[0].wrapSense = 1;
    std::array<TangencyEnd, 5> ends = {TangencyEnd::circle(circles[0]), TangencyEnd::point(eig(nodes[0])),
                                       TangencyEnd::point(eig(nodes[0])), TangencyEnd::point(eig(nodes[0])),
                                       TangencyEnd::point(eig(nodes[4]))};
    for (int k = 1; k <= 3; ++k) {
        const SheaveGroove g = grooveOf(p, rope, k, nodes);
        circles[k].centre = eig(nodes[k]);
        circles[k].axis = eig(g.axis);
        circles[k].radius = g.radius;
        circles[k].wrapSense = g.sense;
        ends[k] = TangencyEnd::circle(circles[k]);
    }
    std::array<SpanTangency, 4> t;
    for (int k = 0; k < 4; ++k) {
        t[k] = computeSpanTangency(ends[k], ends[k + 1]);
        spans += t[k].length;
    }
    double arcs = 0;
    for (int k = 1; k <= 3; ++k) arcs += circles[k].radius * wrapAngle(circles[k], t[k - 1].endRadial, t[k].startRadial);
    const Eigen::Vector3d up = Eigen::Vector3d::UnitY(), e = t[0].startRadial;
    const double phi = std::atan2(Eigen::Vector3d::UnitZ().dot(up.cross(e)), up.dot(e));
    return spans + arcs + p.drumRadius * phi;
}

// Moment about the boom's foot (+z) of a force f at point x (superstructure frame, in-plane).
double footMoment(const BoomCraneParameters& p, const Vec3& x, const Vec3& f) {
    const Vec3 r = x - p.boomFoot;
    return r[0] * f[1] - r[1] * f[0];
}

}  // namespace

BoomCraneCycle BoomCraneCycle::liftSlewLower(const BoomCraneParameters& p, double lift, double slewAngle, double luffAngle) {
    p.validate();
    const double deg = 180.0 / SimTK::Pi, top = p.boomAngle + luffAngle;
    if (!(std::isfinite(luffAngle) && top * deg > 10 && top * deg < 85))
        throw std::invalid_argument("BoomCraneCycle::liftSlewLower: luffAngle takes the boom to " +
                                    std::to_string(top * deg) + " degrees, outside (10, 85)");
    // The luffing rope's change between the two angles (point geometry of the falls).
    BoomCraneParameters q = p;
    auto falls = [&](double angle) {
        q.boomAngle = angle;
        const BoomLayout c = boomLayout(q);
        return (c.luff[2] - c.luff[1]).norm() + (c.luff[3] - c.luff[2]).norm() + (c.luff[4] - c.luff[3]).norm();
    };
    BoomCraneCycle c;
    c.hoist.moves = {{1.0, 8.0, 2.0, lift}, {28.0, 8.0, 2.0, -lift}};
    c.slew.moves = {{10.0, 16.0, 4.0, slewAngle}};
    c.luff.moves = {{10.0, 16.0, 4.0, falls(p.boomAngle) - falls(top)}};
    c.duration = 40.0;
    c.validate();
    return c;
}

void BoomCraneCycle::validate() const {
    hoist.validate();
    luff.validate();
    slew.validate();
    if (!std::isfinite(duration) || !(duration > 0))
        throw std::invalid_argument("BoomCraneCycle: duration = " + std::to_string(duration) + " must be finite and > 0");
}

double BoomCraneScene::luffingRopeLength(double angle) const {
    BoomCraneParameters q = parameters_;
    q.boomAngle = angle;
    const BoomLayout c = boomLayout(q);
    return (c.luff[2] - c.luff[1]).norm() + (c.luff[3] - c.luff[2]).norm() + (c.luff[4] - c.luff[3]).norm();
}

BoomCraneScene::BoomCraneScene(const BoomCraneParameters& p, const BoomCraneCycle& cycle, const SpanOptions& spans)
    : parameters_(p), cycle_(cycle) {
    p.validate();
    cycle.validate();
    using namespace SimTK;
    const BoomLayout layout = boomLayout(p);
    hookStart_ = layout.hookCentre;

    system_ = std::make_unique<MultibodySystem>();
    matter_ = std::make_unique<SimbodyMatterSubsystem>(*system_);
    forces_ = std::make_unique<GeneralForceSubsystem>(*system_);
    gravity_ = std::make_unique<Force::Gravity>(*forces_, *matter_, Vec3(0, -p.g, 0));

    // Superstructure: a Pin about Ground's y (the Pin turns about its frames' z: both frames map z to y).
    const Rotation zUp(UnitVec3(0, 1, 0), ZAxis);
    const Body::Rigid superBody(MassProperties(p.superstructureMass, Vec3(0),
                                               Inertia(p.superstructureInertia, p.superstructureInertia, p.superstructureInertia)));
    superstructure_ = std::make_unique<MobilizedBody::Pin>(matter_->updGround(), Transform(zUp), superBody, Transform(zUp));
    prescribeProfile(*superstructure_, cycle.slew, 1.0);
    // Boom: a slender beam along its x, centre of mass half-way; a Pin about the superstructure's z.
    const double Lb = p.boomLength, mb = p.boomMass;
    const Vec3 boomCom(0.5 * Lb, 0, 0);
    const Inertia boomAboutCom(0.02 * mb, mb * Lb * Lb / 12.0, mb * Lb * Lb / 12.0);
    const Body::Rigid boomBody(MassProperties(mb, boomCom, boomAboutCom.shiftFromMassCenter(boomCom, mb)));
    boom_ = std::make_unique<MobilizedBody::Pin>(*superstructure_, Transform(p.boomFoot), boomBody, Transform());
    boom_->setDefaultAngle(p.boomAngle);
    // Drums: Pins about the superstructure's z, prescribed (rope hauled in: a negative angle).
    const Body::Rigid drumBody(MassProperties(p.drumMass, Vec3(0), Inertia(p.drumInertia)));
    luffDrum_ = std::make_unique<MobilizedBody::Pin>(*superstructure_, Transform(p.luffDrumCentre), drumBody, Transform());
    prescribeProfile(*luffDrum_, cycle.luff, -1.0 / p.drumRadius);
    hoistDrum_ = std::make_unique<MobilizedBody::Pin>(*superstructure_, Transform(p.hoistDrumCentre), drumBody, Transform());
    prescribeProfile(*hoistDrum_, cycle.hoist, -2.0 / p.drumRadius);
    // Hook block: free, frame origin at its sheave's centre, centre of mass below it.
    const Vec3 hookCom(0, -p.hookComBelow, 0);
    const Body::Rigid hookBody(MassProperties(p.hookMass, hookCom,
                                              Inertia(p.hookInertia).shiftFromMassCenter(hookCom, p.hookMass)));
    hook_ = std::make_unique<MobilizedBody::Free>(matter_->updGround(), Transform(), hookBody, Transform());
    // Payload: a ball joint under the hook block, its frame origin at its centre of mass.
    const Body::Rigid payloadBody(MassProperties(p.payloadMass, Vec3(0), Inertia(p.payloadInertia)));
    payload_ = std::make_unique<MobilizedBody::Ball>(*hook_, Transform(Vec3(0, -p.hookPinBelow, 0)), payloadBody,
                                                     Transform(Vec3(0, p.slingLength, 0)));

    reeving_ = std::make_unique<ReevingSubsystem>(*system_, Vec3(0, -p.g, 0));
    workMeter_ = std::make_unique<MotionWorkMeter>(*system_);
    addDecorations();

    const MobilizedBody &super = *superstructure_, &boom = *boom_, &hook = *hook_;
    nodes_ = {{{luffDrum_.get(), Vec3(0)}, {&super, layout.luff[1]}, {&boom, layout.luffTip}, {&super, layout.luff[3]},
               {&boom, layout.luffDeadEnd}},
              {{hoistDrum_.get(), Vec3(0)}, {&boom, layout.hoistFoot}, {&boom, layout.hoistTip}, {&hook, Vec3(0)},
               {&boom, layout.hoistDeadEnd}}};

    // Static tensions at rest, for the unstretched lengths: the hoist falls share the hook load;
    // the luffing falls balance the moments about the boom's foot (boom weight, the hoist rope's
    // pulls on the foot and tip sheaves and the dead end, in the boom's plane).
    const double hoistTension = (p.hookMass + p.payloadMass) * p.g / 2.0;
    const Vec3 down(0, -1, 0);
    const std::array<Vec3, 5>& h = layout.hoist;
    double moment = footMoment(p, boomToSuper(p, p.boomAngle, boomCom), mb * p.g * down);
    moment += footMoment(p, h[1], hoistTension * (unit(h[0] - h[1]) + unit(h[2] - h[1])));
    moment += footMoment(p, h[2], hoistTension * (unit(h[1] - h[2]) + down));
    moment += footMoment(p, h[4], hoistTension * down);
    const std::array<Vec3, 5>& l = layout.luff;
    const double perUnit = footMoment(p, l[2], unit(l[1] - l[2]) + unit(l[3] - l[2])) + footMoment(p, l[4], unit(l[3] - l[4]));
    const double luffTension = -moment / perUnit;
    if (!(luffTension > 0))
        throw std::invalid_argument("BoomCraneParameters: the luffing rope cannot hold the boom at boomAngle (its falls "
                                    "would have to push): raise aFrameTop or lower the boom");

    auto addRope = [&](int r, const char* name, double tension, const SimTK::MobilizedBody& drumBodyRef) {
        RopeSpec rope;
        rope.name = name;
        WinchDrum drum;
        drum.body = drumBodyRef;
        drum.radius = p.drumRadius;
        drum.ropeOnDrum = p.ropeOnDrum;
        drum.pitch = wrapped(p) ? p.drumPitch : 0.0;
        drum.payoutSense = 1;
        rope.start = drum;
        for (int k = 1; k <= 3; ++k) {
            const SheaveGroove g = grooveOf(p, r, k, r == kLuffingRope ? layout.luff : layout.hoist);
            DeviationSheave sheave;
            sheave.body = *nodes_[r][k].first;
            sheave.centre = nodes_[r][k].second;
            sheave.radius = g.radius;
            sheave.wrapSense = g.sense;
            sheave.axis = g.axis;
            rope.sheaves.push_back(sheave);
        }
        RopeAnchor deadEnd;
        deadEnd.body = *nodes_[r][4].first;
        deadEnd.station = nodes_[r][4].second;
        rope.end = deadEnd;
        rope.properties = {p.rhoA, p.EA, p.EI, true};
        // The spans stretched by the static tension; the rope on the grooves is inextensible (GrooveArc).
        double spanLength = 0;
        const double total = pathLength(p, r, r == kLuffingRope ? layout.luff : layout.hoist, spanLength);
        rope.unstretchedLength = spanLength / std::sqrt(1.0 + 2.0 * tension / p.EA) + (total - spanLength);
        rope.spanDefaults = spans;
        rope.sheaveModel = p.sheaveModel;
        rope.minimumSpanLength = p.minimumSpanLength;
        reeving_->addRope(rope);
    };
    addRope(kLuffingRope, "luffing rope", luffTension, *luffDrum_);
    addRope(kHoistRope, "hoist rope", hoistTension, *hoistDrum_);
    // Rope colours (drawing only): red at twice the larger static force.
    reeving_->setDecorationForceScale(2.0 * std::max(luffTension, hoistTension));
    system_->realizeTopology();
}

void BoomCraneScene::addDecorations() {
    // Drawing only (ropes, sheaves and drums are drawn by the ReevingSubsystem).
    using namespace SimTK;
    const BoomCraneParameters& p = parameters_;
    const Vec3 yellow(0.95, 0.75, 0.1), grey(0.35, 0.35, 0.38), dark(0.2, 0.2, 0.2);
    // Superstructure: a deck over the slewing ring, a counterweight at its rear, the A-frame's legs.
    superstructure_->addBodyDecoration(Transform(Vec3(-1.0, 0.5, 0)), DecorativeBrick(Vec3(3.5, 0.5, 1.4)).setColor(yellow));
    superstructure_->addBodyDecoration(Transform(Vec3(-4.0, 1.6, 0)), DecorativeBrick(Vec3(0.6, 0.6, 1.3)).setColor(grey));
    for (double sz : {-0.8, 0.8}) {
        superstructure_->addBodyDecoration(Transform(), DecorativeLine(Vec3(p.aFrameTop[0], p.aFrameTop[1], 0.4 * sz),
                                                                       Vec3(p.aFrameTop[0] - 1.5, 1.0, sz))
                                                            .setColor(dark)
                                                            .setLineThickness(4));
        superstructure_->addBodyDecoration(Transform(), DecorativeLine(Vec3(p.aFrameTop[0], p.aFrameTop[1], 0.4 * sz),
                                                                       Vec3(p.boomFoot[0], 1.0, sz))
                                                            .setColor(dark)
                                                            .setLineThickness(4));
    }
    // Ground: the slewing ring's base.
    matter_->updGround().addBodyDecoration(Transform(Vec3(0, -0.1, 0)), DecorativeCylinder(2.0, 0.1).setColor(grey));
    // Boom: four chords of a lattice, from the foot to the tip.
    for (double sy : {-0.35, 0.35})
        for (double sz : {-0.4, 0.4})
            boom_->addBodyDecoration(Transform(), DecorativeLine(Vec3(0.3, sy, sz), Vec3(p.boomLength - 0.3, 0.5 * sy, 0.5 * sz))
                                                      .setColor(yellow)
                                                      .setLineThickness(3));
    // Hook block: a plate about its sheave, the ball joint below it; the payload a block.
    hook_->addBodyDecoration(Transform(Vec3(0, -0.1, 0)),
                             DecorativeBrick(Vec3(0.05, p.hoistSheaveRadius + 0.15, p.hoistSheaveRadius + 0.1)).setColor(yellow));
    hook_->addBodyDecoration(Transform(Vec3(0, -p.hookPinBelow, 0)), DecorativeSphere(0.08).setColor(dark));
    payload_->addBodyDecoration(Transform(), DecorativeBrick(Vec3(0.8, 0.6, 0.8)).setColor(Vec3(0.2, 0.6, 0.3)));
    payload_->addBodyDecoration(Transform(), DecorativeLine(Vec3(0, p.slingLength, 0), Vec3(0, 0.6, 0)).setColor(dark).setLineThickness(3));
}

SimTK::State BoomCraneScene::makeInitialState() const {
    using namespace SimTK;
    State s = system_->getDefaultState();
    s.setTime(0);
    boom_->setOneQ(s, 0, parameters_.boomAngle);
    hook_->setQToFitTransform(s, Transform(hookStart_));
    system_->realize(s, Stage::Time);
    system_->prescribe(s);
    reeving_->findStaticEquilibrium(s, 1e-9);
    system_->prescribe(s);
    workMeter_->setWork(s, 0);
    system_->realize(s, Stage::Velocity);
    return s;
}

double BoomCraneScene::slewAngle(const SimTK::State& s) const { return superstructure_->getOneQ(s, 0); }

double BoomCraneScene::boomAngle(const SimTK::State& s) const { return boom_->getOneQ(s, 0); }

SimTK::Vec3 BoomCraneScene::hookPosition(const SimTK::State& s) const { return hook_->getBodyOriginLocation(s); }

SimTK::Vec3 BoomCraneScene::payloadPosition(const SimTK::State& s) const { return payload_->getBodyOriginLocation(s); }

double BoomCraneScene::hookRadius(const SimTK::State& s) const {
    const SimTK::Vec3 h = hookPosition(s);
    return std::hypot(h[0], h[2]);
}

namespace {
// The boom tip and the payload in the superstructure's frame.
std::pair<SimTK::Vec3, SimTK::Vec3> tipAndPayload(const SimTK::State& s, const SimTK::MobilizedBody& super,
                                                 const SimTK::MobilizedBody& boom, const SimTK::MobilizedBody& payload,
                                                 double boomLength) {
    const SimTK::Vec3 tip = boom.findStationLocationInAnotherBody(s, SimTK::Vec3(boomLength, 0, 0), super);
    const SimTK::Vec3 load = payload.findStationLocationInAnotherBody(s, SimTK::Vec3(0), super);
    return {tip, load};
}
}  // namespace

double BoomCraneScene::outOfPlaneSwing(const SimTK::State& s) const {
    const auto [tip, load] = tipAndPayload(s, *superstructure_, *boom_, *payload_, parameters_.boomLength);
    return std::atan2(load[2] - tip[2], tip[1] - load[1]);
}

double BoomCraneScene::inPlaneSwing(const SimTK::State& s) const {
    const auto [tip, load] = tipAndPayload(s, *superstructure_, *boom_, *payload_, parameters_.boomLength);
    const double restX = tip[0] + (wrapped(parameters_) ? parameters_.hoistSheaveRadius : 0.0);
    return std::atan2(load[0] - restX, tip[1] - load[1]);
}

double BoomCraneScene::largestFleetAngle(const SimTK::State& s, int rope) const {
    double largest = 0;
    for (int k = 0; k < kSpans; ++k) {
        const auto f = reeving_->getFleetAngles(s, rope, k);
        largest = std::max({largest, std::abs(f.first), std::abs(f.second)});
    }
    return largest;
}

double BoomCraneScene::drumFleetAngle(const SimTK::State& s, int rope) const {
    if (rope != kLuffingRope && rope != kHoistRope)
        throw std::invalid_argument("BoomCraneScene::drumFleetAngle: rope = " + std::to_string(rope) + " must be 0 or 1");
    return std::abs(reeving_->getFleetAngles(s, rope, 0).first);
}

namespace {
void checkRopeNode(const char* what, int rope, int k, int lo, int hi) {
    if (rope != BoomCraneScene::kLuffingRope && rope != BoomCraneScene::kHoistRope)
        throw std::invalid_argument(std::string("BoomCraneScene::") + what + ": rope " + std::to_string(rope) + " is not 0 or 1");
    if (k < lo || k > hi)
        throw std::invalid_argument(std::string("BoomCraneScene::") + what + ": " + std::to_string(k) + " is outside " +
                                    std::to_string(lo) + ".." + std::to_string(hi));
}
}  // namespace

double BoomCraneScene::wrapAngle(const SimTK::State& s, int rope, int k) const {
    checkRopeNode("wrapAngle", rope, k, 1, 3);
    return wrapped(parameters_) ? reeving_->getWrapAngle(s, rope, k) : 0.0;
}

double BoomCraneScene::spanForce(const SimTK::State& s, int rope, int span) const {
    checkRopeNode("spanForce", rope, span, 0, kSpans - 1);
    const std::vector<SimTK::Vec3> ends = reeving_->sampleSpan(s, rope, span, 2);
    const auto range = reeving_->getSpanMaterialRange(s, rope, span);
    return reeving_->getAxialForce(s, rope, span, ends[0][1] >= ends[1][1] ? range.first : range.second);
}

double BoomCraneScene::slewTorque(const SimTK::State& s) const { return -superstructure_->getOneTau(s, SimTK::MobilizerUIndex(0)); }
double BoomCraneScene::luffTorque(const SimTK::State& s) const { return -luffDrum_->getOneTau(s, SimTK::MobilizerUIndex(0)); }
double BoomCraneScene::hoistTorque(const SimTK::State& s) const { return -hoistDrum_->getOneTau(s, SimTK::MobilizerUIndex(0)); }

double BoomCraneScene::ropeOnDrum(const SimTK::State& s, int rope) const {
    checkRopeNode("ropeOnDrum", rope, 0, 0, 0);
    return reeving_->getRope(rope).getWinchDrum(0).getRopeOnDrum(s);
}

double BoomCraneScene::energyResidual(const SimTK::State& s, double e0) const {
    return reeving_->calcMechanicalEnergy(s) - e0 - workMeter_->getWork(s);
}

std::vector<SimTK::Vec3> BoomCraneScene::nodePositions(const SimTK::State& s, int rope) const {
    checkRopeNode("nodePositions", rope, 0, 0, 0);
    std::vector<SimTK::Vec3> r;
    for (const auto& [body, station] : nodes_[rope]) r.push_back(body->findStationLocationInGround(s, station));
    return r;
}

}  // namespace SimbodyReeving
