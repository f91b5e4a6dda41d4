#include "SimbodyReeving/scenes/CraneScene.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

namespace SimbodyReeving {

void CraneParameters::validate() const {
    auto check = [](const char* name, double v, bool ok, const char* range) {
        if (!std::isfinite(v) || !ok) {
            std::ostringstream o;
            o << "CraneParameters: " << name << " = " << v << " must be finite and " << range;
            throw std::invalid_argument(o.str());
        }
    };
    if (falls < 1 || falls > 12)
        throw std::invalid_argument("CraneParameters: falls = " + std::to_string(falls) + " must be in 1..12");
    check("g", g, g >= 0, ">= 0");
    check("railHeight", railHeight, railHeight > 0, "> 0");
    check("trolleyX0", trolleyX0, true, "any value");
    check("trolleyMass", trolleyMass, trolleyMass > 0, "> 0");
    check("sheavePitch", sheavePitch, sheavePitch > 0, "> 0");
    check("sheaveRadius", sheaveRadius, sheaveRadius > 0, "> 0");
    check("drumRadius", drumRadius, drumRadius > 0, "> 0");
    check("drumHeight", drumHeight, true, "any value");
    check("drumMass", drumMass, drumMass > 0, "> 0");
    check("drumInertia", drumInertia, drumInertia > 0, "> 0");
    check("ropeOnDrum", ropeOnDrum, ropeOnDrum > 0, "> 0");
    check("hookMass", hookMass, hookMass > 0, "> 0");
    check("hookInertia", hookInertia, hookInertia > 0, "> 0");
    check("hookComBelow", hookComBelow, hookComBelow >= 0, ">= 0");
    check("hookPinBelow", hookPinBelow, hookPinBelow >= 0, ">= 0");
    check("initialHookDepth", initialHookDepth, initialHookDepth > 0, "> 0");
    check("payloadMass", payloadMass, payloadMass > 0, "> 0");
    check("payloadInertia", payloadInertia, payloadInertia > 0, "> 0");
    check("slingLength", slingLength, slingLength > 0, "> 0");
    check("payloadWidth", payloadWidth, payloadWidth > 0, "> 0");
    check("payloadHeight", payloadHeight, payloadHeight > 0, "> 0");
    check("rhoA", rhoA, rhoA > 0, "> 0");
    check("EA", EA, EA > 0, "> 0");
    check("EI", EI, EI >= 0, ">= 0");
    check("minimumSpanLength", minimumSpanLength, minimumSpanLength > 0, "> 0");
    if (!(initialHookDepth > minimumSpanLength))
        throw std::invalid_argument("CraneParameters: initialHookDepth must exceed minimumSpanLength");
}

CraneCycle CraneCycle::liftTraverseLower(double lift, double traverse) {
    CraneCycle c;
    c.hoist.moves = {{1.0, 9.0, 2.0, lift}, {23.5, 9.0, 2.0, -lift}};
    c.traverse.moves = {{10.5, 12.0, 3.0, traverse}};
    c.duration = 36.0;
    return c;
}

void CraneCycle::validate() const {
    hoist.validate();
    traverse.validate();
    if (!std::isfinite(duration) || !(duration > 0))
        throw std::invalid_argument("CraneCycle: duration = " + std::to_string(duration) + " must be finite and > 0");
}

CraneScene::CraneScene(const CraneParameters& p, const CraneCycle& cycle, const SpanOptions& spans)
    : parameters_(p), cycle_(cycle) {
    p.validate();
    cycle.validate();
    using namespace SimTK;
    const int n = p.falls;

    // Rope node offsets (k - n/2) pitch; the hook block's shifted to their load centroid.
    std::vector<double> x(n + 1);
    for (int k = 0; k <= n; ++k) x[k] = (k - 0.5 * n) * p.sheavePitch;
    double sumW = 0, sumWx = 0;
    for (int k = 1; k <= n; k += 2) {
        const double w = k < n ? 2.0 : 1.0;
        sumW += w;
        sumWx += w * x[k];
    }
    const double hookCentroid = sumWx / sumW;
    stations_.resize(n + 1);
    stations_[0] = Vec3(0);  // drum axis, drum frame
    for (int k = 1; k <= n; ++k) stations_[k] = Vec3(nodeOnHook(k) ? x[k] - hookCentroid : x[k], 0, 0);

    // Hook block's rest offset below the trolley: horizontal balance of n equal tensions,
    // sum_k (top_x - bottom_x - X) / length_k = 0 with nearly vertical falls.
    const double h = p.initialHookDepth;
    double num = 0, den = 0;
    for (int k = 0; k < n; ++k) {
        const int top = nodeOnHook(k) ? k + 1 : k, bottom = nodeOnHook(k) ? k : k + 1;
        const double topX = top == 0 ? x[0] : stations_[top][0];
        const double length = h + (top == 0 ? p.drumHeight : 0.0);
        num += (topX - stations_[bottom][0]) / length;
        den += 1.0 / length;
    }
    hookRestOffset_ = num / den;

    system_ = std::make_unique<MultibodySystem>();
    matter_ = std::make_unique<SimbodyMatterSubsystem>(*system_);
    forces_ = std::make_unique<GeneralForceSubsystem>(*system_);
    gravity_ = std::make_unique<Force::Gravity>(*forces_, *matter_, Vec3(0, -p.g, 0));
    reeving_ = std::make_unique<ReevingSubsystem>(*system_, Vec3(0, -p.g, 0));
    workMeter_ = std::make_unique<MotionWorkMeter>(*system_);

    // Trolley: slides along Ground's x at rail height. Its inertia only matters to the drive.
    const Body::Rigid trolleyBody(MassProperties(p.trolleyMass, Vec3(0), Inertia(p.trolleyMass)));
    trolley_ = std::make_unique<MobilizedBody::Slider>(matter_->updGround(), Transform(Vec3(p.trolleyX0, p.railHeight, 0)),
                                                       trolleyBody, Transform());
    prescribeProfile(*trolley_, cycle.traverse, 1.0);
    // Drum: a Pin (axis z) above the first rope node.
    const Body::Rigid drumBody(MassProperties(p.drumMass, Vec3(0), Inertia(p.drumInertia)));
    drum_ = std::make_unique<MobilizedBody::Pin>(*trolley_, Transform(Vec3(x[0], p.drumHeight, 0)), drumBody, Transform());
    prescribeProfile(*drum_, cycle.hoist, -n / p.drumRadius);
    // Hook block: planar from Ground, frame origin at its sheave centres.
    const Body::Rigid hookBody(MassProperties(p.hookMass, Vec3(0, -p.hookComBelow, 0),
                                              Inertia(p.hookInertia).shiftFromMassCenter(Vec3(0, -p.hookComBelow, 0), p.hookMass)));
    hook_ = std::make_unique<MobilizedBody::Planar>(matter_->updGround(), Transform(), hookBody, Transform());
    // Payload: a Pin under the sling pin, frame origin at its centre of mass.
    const Body::Rigid payloadBody(MassProperties(p.payloadMass, Vec3(0), Inertia(p.payloadInertia)));
    payload_ = std::make_unique<MobilizedBody::Pin>(*hook_, Transform(Vec3(0, -p.hookPinBelow, 0)), payloadBody,
                                                    Transform(Vec3(0, p.slingLength, 0)));

    addDecorations();

    RopeSpec rope;
    rope.name = "hoist rope";
    WinchDrum drum;
    drum.body = *drum_;
    drum.radius = p.drumRadius;
    drum.ropeOnDrum = p.ropeOnDrum;
    drum.payoutSense = 1;
    rope.start = drum;
    for (int k = 1; k < n; ++k) {
        DeviationSheave sheave;
        sheave.body = nodeOnHook(k) ? static_cast<const MobilizedBody&>(*hook_) : static_cast<const MobilizedBody&>(*trolley_);
        sheave.centre = stations_[k];
        sheave.radius = p.sheaveRadius;
        rope.sheaves.push_back(sheave);
    }
    RopeAnchor deadEnd;
    deadEnd.body = nodeOnHook(n) ? static_cast<const MobilizedBody&>(*hook_) : static_cast<const MobilizedBody&>(*trolley_);
    deadEnd.station = stations_[n];
    rope.end = deadEnd;
    rope.properties = {p.rhoA, p.EA, p.EI, p.tensionOnly};
    // Unstretched length: the falls' lengths with the hook at its initial depth, shortened by the
    // stretch of the static tension (M g / n per fall).
    double geometric = 0;
    for (int k = 0; k < n; ++k) {
        auto position = [&](int node) {
            if (node == 0) return Vec3(x[0], p.drumHeight, 0);
            return nodeOnHook(node) ? stations_[node] + Vec3(hookRestOffset_, -h, 0) : stations_[node];
        };
        geometric += (position(k + 1) - position(k)).norm();
    }
    const double tension = (p.payloadMass + p.hookMass) * p.g / n;
    rope.unstretchedLength = geometric / std::sqrt(1.0 + 2.0 * tension / p.EA);
    rope.spanDefaults = spans;
    rope.planeNormal = Vec3(0, 0, 1);
    rope.minimumSpanLength = p.minimumSpanLength;
    reeving_->addRope(rope);
    // Rope colours (drawing only): red at twice the static load of a fall, (M + m_hook) g / n.
    reeving_->setDecorationForceScale(2.0 * tension);
    system_->realizeTopology();
}

void CraneScene::addDecorations() {
    // Drawing only (the rope, sheaves and drum are drawn by the ReevingSubsystem). The rope plane is
    // z = 0; the structure sits behind it (z < 0) or above it so that the reeving stays in view.
    using namespace SimTK;
    const CraneParameters& p = parameters_;
    double xMin = stations_[0][0], xMax = xMin, hookMin = 1e300, hookMax = -1e300;
    for (int k = 1; k <= p.falls; ++k) {
        if (nodeOnHook(k)) {
            hookMin = std::min(hookMin, stations_[k][0]);
            hookMax = std::max(hookMax, stations_[k][0]);
        } else {
            xMin = std::min(xMin, stations_[k][0]);
            xMax = std::max(xMax, stations_[k][0]);
        }
    }
    xMin = std::min(xMin, -p.drumRadius);
    xMax = std::max(xMax, p.drumRadius);
    // Trolley: a back plate behind its sheaves and drum, a deck above the drum, four wheels.
    const Vec3 steel(0.55, 0.58, 0.62), frame(0.25, 0.35, 0.6);
    const double top = p.drumHeight + p.drumRadius + 0.3, halfX = 0.5 * (xMax - xMin) + 0.5;
    const double midX = 0.5 * (xMin + xMax);
    trolley_->addBodyDecoration(Transform(Vec3(midX, 0.5 * (top - 0.4), -0.6)),
                                DecorativeBrick(Vec3(halfX, 0.5 * (top + 0.4), 0.04)).setColor(frame));
    trolley_->addBodyDecoration(Transform(Vec3(midX, top, 0)), DecorativeBrick(Vec3(halfX, 0.08, 0.65)).setColor(frame));
    // The wheels' axes along z (a cylinder's axis is its y axis). Built from the axis direction:
    // Rotation(angle, XAxis) inlines Row copies that GCC 12 reports as -Warray-bounds under
    // AddressSanitizer (a false positive inside Simbody's header).
    const Rotation wheelAxis(UnitVec3(0, 0, 1), YAxis);
    for (double sx : {-1.0, 1.0})
        for (double sz : {-0.55, 0.55})
            trolley_->addBodyDecoration(Transform(wheelAxis, Vec3(midX + sx * (halfX - 0.25), top + 0.23, sz)),
                                        DecorativeCylinder(0.15, 0.05).setColor(Vec3(0.2, 0.2, 0.2)));
    // Rails (Ground) over the trolley's travel, with 3 m to spare at each end.
    double travelMin = 0, travelMax = 0;
    const double end = std::max(cycle_.traverse.endTime(), cycle_.duration);
    for (int k = 0; k <= 200; ++k) {
        const double x = cycle_.traverse.position(end * k / 200.0);
        travelMin = std::min(travelMin, x);
        travelMax = std::max(travelMax, x);
    }
    const double railA = p.trolleyX0 + travelMin - halfX - 3.0, railB = p.trolleyX0 + travelMax + halfX + 3.0;
    for (double sz : {-0.55, 0.55})
        matter_->updGround().addBodyDecoration(
            Transform(Vec3(0.5 * (railA + railB) + midX, p.railHeight + top + 0.45, sz)),
            DecorativeBrick(Vec3(0.5 * (railB - railA), 0.07, 0.07)).setColor(steel));
    // Hook block: side plate behind its sheaves, shank down to the sling pin, the pin.
    const Vec3 yellow(0.95, 0.75, 0.1);
    const double plateHalf = 0.5 * (hookMax - hookMin) + p.sheaveRadius + 0.12;
    hook_->addBodyDecoration(Transform(Vec3(0.5 * (hookMin + hookMax), -0.05, -0.2)),
                             DecorativeBrick(Vec3(plateHalf, p.sheaveRadius + 0.17, 0.04)).setColor(yellow));
    const double shankTop = p.sheaveRadius + 0.1;
    if (p.hookPinBelow > shankTop)
        hook_->addBodyDecoration(Transform(Vec3(0, -0.5 * (shankTop + p.hookPinBelow), -0.1)),
                                 DecorativeBrick(Vec3(0.08, 0.5 * (p.hookPinBelow - shankTop), 0.08)).setColor(yellow));
    hook_->addBodyDecoration(Transform(Vec3(0, -p.hookPinBelow, 0)), DecorativeSphere(0.07).setColor(Vec3(0.2, 0.2, 0.2)));
    // Payload: its block, slung by two legs from the pin to its top corners.
    payload_->addBodyDecoration(Transform(), DecorativeBrick(Vec3(0.5 * p.payloadWidth, 0.5 * p.payloadHeight, 0.6))
                                                 .setColor(Vec3(0.2, 0.6, 0.3)));
    for (double sx : {-0.4, 0.4})
        payload_->addBodyDecoration(Transform(), DecorativeLine(Vec3(0, p.slingLength, 0),
                                                                Vec3(sx * p.payloadWidth, 0.5 * p.payloadHeight, 0))
                                                     .setColor(Vec3(0.2, 0.2, 0.2))
                                                     .setLineThickness(3));
}

SimTK::State CraneScene::makeInitialState() const {
    using namespace SimTK;
    const CraneParameters& p = parameters_;
    State s = system_->getDefaultState();
    s.setTime(0);
    hook_->setQToFitTransform(s, Transform(Vec3(p.trolleyX0 + hookRestOffset_, p.railHeight - p.initialHookDepth, 0)));
    payload_->setQ(s, 0);
    system_->realize(s, Stage::Time);
    system_->prescribe(s);
    reeving_->findStaticEquilibrium(s, 1e-9);
    system_->prescribe(s);
    workMeter_->setWork(s, 0);
    system_->realize(s, Stage::Velocity);
    return s;
}

double CraneScene::trolleyX(const SimTK::State& s) const { return trolley_->getBodyOriginLocation(s)[0]; }

SimTK::Vec3 CraneScene::hookPosition(const SimTK::State& s) const { return hook_->getBodyOriginLocation(s); }

double CraneScene::swayAngle(const SimTK::State& s) const {
    const SimTK::Vec3 t = trolley_->getBodyOriginLocation(s), h = hook_->getBodyOriginLocation(s);
    return std::atan2(h[0] - t[0] - hookRestOffset_, t[1] - h[1]);
}

double CraneScene::payloadAngle(const SimTK::State& s) const {
    const SimTK::Vec3 pin = hook_->findStationLocationInGround(s, SimTK::Vec3(0, -parameters_.hookPinBelow, 0));
    const SimTK::Vec3 c = payload_->getBodyOriginLocation(s);
    return std::atan2(c[0] - pin[0], pin[1] - c[1]);
}

double CraneScene::fallTopForce(const SimTK::State& s, int fall) const {
    if (fall < 0 || fall >= parameters_.falls)
        throw std::invalid_argument("CraneScene::fallTopForce: fall " + std::to_string(fall) + " out of range");
    const auto range = reeving_->getSpanMaterialRange(s, 0, fall);
    return reeving_->getAxialForce(s, 0, fall, nodeOnHook(fall) ? range.second : range.first);
}

double CraneScene::drumSpeed(const SimTK::State& s) const { return drum_->getOneU(s, 0); }

double CraneScene::ropeOnDrum(const SimTK::State& s) const { return reeving_->getRopeOnDrum(s, 0, 0); }

double CraneScene::motorTorque(const SimTK::State& s) const {
    return -drum_->getOneTau(s, SimTK::MobilizerUIndex(0));
}

double CraneScene::trolleyForce(const SimTK::State& s) const {
    return -trolley_->getOneTau(s, SimTK::MobilizerUIndex(0));
}

std::vector<SimTK::Vec3> CraneScene::nodePositions(const SimTK::State& s) const {
    std::vector<SimTK::Vec3> r(parameters_.falls + 1);
    r[0] = drum_->getBodyOriginLocation(s);
    for (int k = 1; k <= parameters_.falls; ++k)
        r[k] = (nodeOnHook(k) ? static_cast<const SimTK::MobilizedBody&>(*hook_)
                              : static_cast<const SimTK::MobilizedBody&>(*trolley_))
                   .findStationLocationInGround(s, stations_[k]);
    return r;
}

}  // namespace SimbodyReeving
