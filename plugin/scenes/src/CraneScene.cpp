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
    if (scenario != CraneScenario::Cycle && scenario != CraneScenario::LiftOff)
        throw std::invalid_argument("CraneParameters: scenario is not a CraneScenario");
    if (sheaveModel != SheaveModel::Point && sheaveModel != SheaveModel::Wrapped)
        throw std::invalid_argument("CraneParameters: sheaveModel is not a SheaveModel");
    check("hoistSpeed", hoistSpeed, hoistSpeed > 0, "> 0");
    check("hoistRamp", hoistRamp, hoistRamp > 0, "> 0");
    check("slackTime", slackTime, slackTime >= 0, ">= 0");
    check("afterLiftOff", afterLiftOff, afterLiftOff > 0, "> 0");
    check("floorStiffness", floorStiffness, floorStiffness > 0, "> 0");
    check("floorDampingRatio", floorDampingRatio, floorDampingRatio >= 0, ">= 0");
    check("slingStiffness", slingStiffness, slingStiffness > 0, "> 0");
    check("slingDampingRatio", slingDampingRatio, slingDampingRatio >= 0, ">= 0");
}

namespace {

bool isHookNode(int k) { return k % 2 == 1; }  // CraneScene::nodeOnHook

// The reeving's layout in the trolley and hook frames, shared by the scene and CraneCycle::liftOff.
struct CraneLayout {
    std::vector<double> x;               // rope node offsets (k - n/2) pitch
    std::vector<SimTK::Vec3> stations;   // node k in its body's frame
    double hookRestOffset = 0;           // hook block below the trolley at rest, along x [m]
};

bool wrapped(const CraneParameters& p) { return p.sheaveModel == SheaveModel::Wrapped; }

// Wrapped sheaves: where the rope leaves sheave k = 1..n-1 (+1 counter-clockwise about +z: under
// the hook sheaves from fall k - 1 on the left to fall k on the right; -1 over the trolley's).
int wrapSenseOf(int k) { return isHookNode(k) ? 1 : -1; }

// Length of rope on the sheaves at rest, every sheave wrapped half a turn: the rope on the hook
// block's floor(n / 2) sheaves (hookOnly) or on all n - 1 [m]; 0 with point sheaves.
double arcsLength(const CraneParameters& p, bool hookOnly) {
    if (!wrapped(p)) return 0.0;
    const int sheaves = hookOnly ? p.falls / 2 : p.falls - 1;
    return sheaves * SimTK::Pi * p.sheaveRadius;
}

CraneLayout craneLayout(const CraneParameters& p) {
    using SimTK::Vec3;
    const int n = p.falls;
    CraneLayout c;
    // Rope node offsets: point sheaves (k - n/2) pitch; wrapped sheaves between the vertical falls
    // at X_j = (j - (n - 1)/2) 2R, the drum above fall 0, the dead end on fall n - 1. The hook
    // block's nodes shifted to their load centroid (so that it hangs level).
    std::vector<double>& x = c.x;
    x.resize(n + 1);
    if (wrapped(p)) {
        auto fallX = [&](int j) { return (j - 0.5 * (n - 1)) * 2.0 * p.sheaveRadius; };
        // The drum wrapped too: its centre a drum radius right of fall 0, which leaves its left side.
        x[0] = fallX(0) + p.drumRadius;
        for (int k = 1; k < n; ++k) x[k] = 0.5 * (fallX(k - 1) + fallX(k));
        x[n] = fallX(n - 1);
    } else {
        for (int k = 0; k <= n; ++k) x[k] = (k - 0.5 * n) * p.sheavePitch;
    }
    // The hook block's nodes' upward pulls in units of the falls' bottom tension T_b: 2 per sheave
    // and 1 at a dead end; a wrapped sheave's groove also holds up the rope on it (the half turn
    // under the sheave), so its pull is 2 T_b - rhoA g pi R, with n T_b = M g + the hook arcs'
    // weight.
    const double arcWeight = wrapped(p) ? p.rhoA * p.g * SimTK::Pi * p.sheaveRadius : 0.0;
    const double bottomTension = ((p.payloadMass + p.hookMass) * p.g + (n / 2) * arcWeight) / n;
    double sumW = 0, sumWx = 0;
    for (int k = 1; k <= n; k += 2) {
        const double w = k < n ? 2.0 - arcWeight / bottomTension : 1.0;
        sumW += w;
        sumWx += w * x[k];
    }
    const double hookCentroid = sumWx / sumW;
    std::vector<Vec3>& stations = c.stations;
    stations.resize(n + 1);
    stations[0] = Vec3(0);  // drum axis, drum frame
    for (int k = 1; k <= n; ++k) stations[k] = Vec3(isHookNode(k) ? x[k] - hookCentroid : x[k], 0, 0);

    // Wrapped sheaves: the falls hang vertical, the hook block right under the trolley.
    if (wrapped(p)) return c;
    // Hook block's rest offset below the trolley: horizontal balance of n equal tensions,
    // sum_k (top_x - bottom_x - X) / length_k = 0 with nearly vertical falls.
    const double h = p.initialHookDepth;
    double num = 0, den = 0;
    for (int k = 0; k < n; ++k) {
        const int top = isHookNode(k) ? k + 1 : k, bottom = isHookNode(k) ? k : k + 1;
        const double topX = top == 0 ? x[0] : stations[top][0];
        const double length = h + (top == 0 ? p.drumHeight : 0.0);
        num += (topX - stations[bottom][0]) / length;
        den += 1.0 / length;
    }
    c.hookRestOffset = num / den;
    return c;
}

// The falls' summed length with the hook sheave centres `depth` below the trolley's, at the rest
// offset [m].
double fallsLengthAt(const CraneParameters& p, const CraneLayout& c, double depth) {
    using SimTK::Vec3;
    // Wrapped: vertical falls between tangent points level with the sheave centres.
    if (wrapped(p)) return p.falls * depth + p.drumHeight;
    double geometric = 0;
    for (int k = 0; k < p.falls; ++k) {
        auto position = [&](int node) {
            if (node == 0) return Vec3(c.x[0], p.drumHeight, 0);
            return isHookNode(node) ? c.stations[node] + Vec3(c.hookRestOffset, -depth, 0) : c.stations[node];
        };
        geometric += (position(k + 1) - position(k)).norm();
    }
    return geometric;
}

double liftOffSlack(const CraneParameters& p) { return p.hoistSpeed * (0.5 * p.hoistRamp + p.slackTime); }

// Where the rope takes the load: the hook at initialHookDepth (Cycle) or the slack higher (LiftOff).
double loadDepth(const CraneParameters& p) {
    return p.initialHookDepth - (p.scenario == CraneScenario::LiftOff ? liftOffSlack(p) : 0.0);
}

double hookStiffnessOf(const CraneParameters& p, double fallsLength) {
    return p.falls * p.falls * p.EA / fallsLength;
}

// LiftOff's contacts (see the CraneScene class comment): the floor under the payload's two bottom
// corners and the sling from the hook block's pin to the payload's lifting point. A ForceSubsystem
// constructed before the ReevingSubsystem (whose coupled solve must see every applied force): it
// applies their forces, holds their elastic energy as its potential energy and integrates the
// power their dashpots dissipate in one Z entry (weight 1 / (1 J), as the MotionWorkMeter's).
class LiftOffContactsGuts : public SimTK::ForceSubsystem::Guts {
public:
    struct Spec {
        SimTK::MobilizedBodyIndex hook, payload;
        SimTK::Vec3 corners[2];   // payload frame
        SimTK::Vec3 pin, eye;     // sling ends: hook frame, payload frame
        double floorY = 0, cornerStiffness = 0, cornerDamping = 0;
        double slingLength = 0, slingStiffness = 0, slingDamping = 0;
    };
    explicit LiftOffContactsGuts(const Spec& spec) : SimTK::ForceSubsystem::Guts("CraneLiftOffContacts", "0.1"), c_(spec) {}
    LiftOffContactsGuts* cloneImpl() const override { return new LiftOffContactsGuts(*this); }

    // Floor: penetration d_i [m] (Stage::Position), its rate [m/s] and the force on corner i [N]
    // (Stage::Velocity).
    double penetration(const SimTK::State& s, int i) const {
        return c_.floorY - payload().findStationLocationInGround(s, c_.corners[i])[1];
    }
    double penetrationRate(const SimTK::State& s, int i) const {
        return -payload().findStationVelocityInGround(s, c_.corners[i])[1];
    }
    double cornerForce(const SimTK::State& s, int i) const {
        const double d = penetration(s, i);
        return d > 0 ? std::max(0.0, c_.cornerStiffness * d + c_.cornerDamping * penetrationRate(s, i)) : 0.0;
    }
    double floorForce(const SimTK::State& s) const { return cornerForce(s, 0) + cornerForce(s, 1); }
    double lowestCornerHeight(const SimTK::State& s) const {
        return -std::max(penetration(s, 0), penetration(s, 1));
    }
    // Sling: the pin-to-eye vector (Ground), its extension e [m] (Stage::Position), rate e' [m/s]
    // and force f [N] (Stage::Velocity).
    SimTK::Vec3 slingVector(const SimTK::State& s) const {
        return hook().findStationLocationInGround(s, c_.pin) - payload().findStationLocationInGround(s, c_.eye);
    }
    double slingExtension(const SimTK::State& s) const { return slingVector(s).norm() - c_.slingLength; }
    double slingRate(const SimTK::State& s) const {
        const SimTK::Vec3 r = slingVector(s);
        const SimTK::Vec3 v = hook().findStationVelocityInGround(s, c_.pin) - payload().findStationVelocityInGround(s, c_.eye);
        return SimTK::dot(r, v) / r.norm();
    }
    double slingForce(const SimTK::State& s) const {
        const double e = slingExtension(s);
        return e > 0 ? std::max(0.0, c_.slingStiffness * e + c_.slingDamping * slingRate(s)) : 0.0;
    }
    // The dashpots' power [W], >= 0 (Stage::Velocity).
    double dissipatedPower(const SimTK::State& s) const {
        double p = 0;
        for (int i = 0; i < 2; ++i) {
            const double d = penetration(s, i);
            if (d > 0) p += (cornerForce(s, i) - c_.cornerStiffness * d) * penetrationRate(s, i);
        }
        const double e = slingExtension(s);
        if (e > 0) p += (slingForce(s) - c_.slingStiffness * e) * slingRate(s);
        return p;
    }
    double getDissipation(const SimTK::State& s) const { return getZ(s)[0]; }
    void setDissipation(SimTK::State& s, double w) const { updZ(s)[0] = w; }

    SimTK::Real calcPotentialEnergy(const SimTK::State& s) const override {
        double u = 0;
        for (int i = 0; i < 2; ++i) {
            const double d = penetration(s, i);
            if (d > 0) u += 0.5 * c_.cornerStiffness * d * d;
        }
        const double e = slingExtension(s);
        if (e > 0) u += 0.5 * c_.slingStiffness * e * e;
        return u;
    }
    int realizeSubsystemTopologyImpl(SimTK::State& s) const override {
        allocateZ(s, SimTK::Vector(1, 0.0));
        return 0;
    }
    int realizeSubsystemDynamicsImpl(const SimTK::State& s) const override {
        SimTK::Vector_<SimTK::SpatialVec>& forces = mbs().updRigidBodyForces(s, SimTK::Stage::Dynamics);
        for (int i = 0; i < 2; ++i) {
            const double f = cornerForce(s, i);
            if (f > 0) payload().applyForceToBodyPoint(s, c_.corners[i], SimTK::Vec3(0, f, 0), forces);
        }
        const double f = slingForce(s);
        if (f > 0) {
            const SimTK::Vec3 r = slingVector(s), pull = f * r / r.norm();  // on the payload, towards the pin
            payload().applyForceToBodyPoint(s, c_.eye, pull, forces);
            hook().applyForceToBodyPoint(s, c_.pin, -pull, forces);
        }
        return 0;
    }
    int realizeSubsystemAccelerationImpl(const SimTK::State& s) const override {
        updZDot(s)[0] = dissipatedPower(s);
        return 0;
    }
    // The sling's legs, from the pin to the payload's top corners (drawing only).
    int calcDecorativeGeometryAndAppendImpl(const SimTK::State& s, SimTK::Stage stage,
                                            SimTK::Array_<SimTK::DecorativeGeometry>& geometry) const override {
        if (stage != SimTK::Stage::Position) return 0;
        const SimTK::Vec3 pin = hook().findStationLocationInGround(s, c_.pin);
        for (double side : {-0.4, 0.4}) {
            const SimTK::Vec3 corner(side * 2.0 * std::abs(c_.corners[0][0]), c_.eye[1], 0);
            geometry.push_back(SimTK::DecorativeLine(pin, payload().findStationLocationInGround(s, corner))
                                   .setColor(SimTK::Vec3(0.2, 0.2, 0.2))
                                   .setLineThickness(3));
        }
        return 0;
    }

private:
    const SimTK::MultibodySystem& mbs() const { return SimTK::MultibodySystem::downcast(getSystem()); }
    const SimTK::MobilizedBody& hook() const { return mbs().getMatterSubsystem().getMobilizedBody(c_.hook); }
    const SimTK::MobilizedBody& payload() const { return mbs().getMatterSubsystem().getMobilizedBody(c_.payload); }
    Spec c_;
};

class LiftOffContacts : public SimTK::ForceSubsystem {
public:
    LiftOffContacts(SimTK::MultibodySystem& system, const LiftOffContactsGuts::Spec& spec) {
        adoptSubsystemGuts(new LiftOffContactsGuts(spec));
        system.addForceSubsystem(*this);
    }
};

const LiftOffContactsGuts& contactsGuts(const SimTK::ForceSubsystem& sub) {
    return static_cast<const LiftOffContactsGuts&>(sub.getSubsystemGuts());
}

}  // namespace

const char* toString(CraneScenario scenario) {
    switch (scenario) {
        case CraneScenario::Cycle: return "cycle";
        case CraneScenario::LiftOff: return "lift-off";
    }
    return "?";
}

CraneScenario craneScenarioFromString(const std::string& name) {
    for (CraneScenario s : {CraneScenario::Cycle, CraneScenario::LiftOff})
        if (name == toString(s)) return s;
    throw std::invalid_argument("crane scenario '" + name + "' is not one of cycle, lift-off");
}

CraneCycle CraneCycle::liftTraverseLower(double lift, double traverse) {
    CraneCycle c;
    c.hoist.moves = {{1.0, 9.0, 2.0, lift}, {23.5, 9.0, 2.0, -lift}};
    c.traverse.moves = {{10.5, 12.0, 3.0, traverse}};
    c.duration = 36.0;
    return c;
}

CraneCycle CraneCycle::liftOff(const CraneParameters& p) {
    p.validate();
    CraneParameters q = p;
    q.scenario = CraneScenario::LiftOff;
    const double k = hookStiffnessOf(q, fallsLengthAt(q, craneLayout(q), loadDepth(q)));
    // The sling is taut at t_taut; the rope's force then grows from the hook block's weight by
    // k v_h per second until it carries the payload too.
    const double taut = p.hoistRamp + p.slackTime;
    const double liftOffTime = taut + p.payloadMass * p.g / (k * p.hoistSpeed);
    const double bouncePeriod = 2.0 * SimTK::Pi * std::sqrt((p.payloadMass + p.hookMass) / k);
    CraneCycle c;
    c.duration = liftOffTime + p.afterLiftOff * bouncePeriod;
    // One move from t = 0 whose hold phase lasts to the cycle's end: duration - ramp of the move
    // = c.duration, peak speed v_h.
    const double moveDuration = c.duration + p.hoistRamp;
    c.hoist.moves = {{0.0, moveDuration, p.hoistRamp, p.hoistSpeed * c.duration}};
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
    const bool liftOff = p.scenario == CraneScenario::LiftOff;

    if (liftOff) {
        // The slack v_h (hoistRamp / 2 + slackTime) must leave the falls and the sling some length.
        std::ostringstream o;
        o << "CraneParameters: lift-off: the slack hoistSpeed (hoistRamp / 2 + slackTime) = " << liftOffSlack(p) << " m";
        if (!(loadDepth(p) > p.minimumSpanLength))
            throw std::invalid_argument(o.str() + " must be less than initialHookDepth - minimumSpanLength");
        if (!(p.slingLength - 0.5 * p.payloadHeight - liftOffSlack(p) > 0))
            throw std::invalid_argument(o.str() + " must be less than the sling's length, slingLength - payloadHeight / 2");
    }
    const CraneLayout layout = craneLayout(p);
    const std::vector<double>& x = layout.x;
    stations_ = layout.stations;
    hookRestOffset_ = layout.hookRestOffset;
    fallsLength_ = fallsLengthAt(p, layout, loadDepth(p));
    loadedRopeLength_ = fallsLength_ + arcsLength(p, false);

    system_ = std::make_unique<MultibodySystem>();
    matter_ = std::make_unique<SimbodyMatterSubsystem>(*system_);
    forces_ = std::make_unique<GeneralForceSubsystem>(*system_);
    gravity_ = std::make_unique<Force::Gravity>(*forces_, *matter_, Vec3(0, -p.g, 0));

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
    // Payload, frame origin at its centre of mass: a Pin under the sling pin; lift-off: planar
    // from Ground, on the floor, hung from the hook block by the sling.
    const Body::Rigid payloadBody(MassProperties(p.payloadMass, Vec3(0), Inertia(p.payloadInertia)));
    if (!liftOff)
        payload_ = std::make_unique<MobilizedBody>(MobilizedBody::Pin(*hook_, Transform(Vec3(0, -p.hookPinBelow, 0)),
                                                                      payloadBody, Transform(Vec3(0, p.slingLength, 0))));
    else
        payload_ = std::make_unique<MobilizedBody>(MobilizedBody::Planar(matter_->updGround(), Transform(), payloadBody, Transform()));

    // Lift-off: the floor under the payload's bottom (the hook at its initial depth, the sling
    // slack by ropeSlack) and the sling. A force subsystem of its own, constructed before the
    // ReevingSubsystem (which must come after every force subsystem that applies forces).
    if (liftOff) {
        floorHeight_ = p.railHeight - p.initialHookDepth - p.hookPinBelow - p.slingLength + ropeSlack() - 0.5 * p.payloadHeight;
        LiftOffContactsGuts::Spec c;
        c.hook = hook_->getMobilizedBodyIndex();
        c.payload = payload_->getMobilizedBodyIndex();
        c.corners[0] = Vec3(-0.5 * p.payloadWidth, -0.5 * p.payloadHeight, 0);
        c.corners[1] = Vec3(0.5 * p.payloadWidth, -0.5 * p.payloadHeight, 0);
        c.pin = Vec3(0, -p.hookPinBelow, 0);
        c.eye = Vec3(0, 0.5 * p.payloadHeight, 0);
        c.floorY = floorHeight_;
        c.cornerStiffness = 0.5 * p.floorStiffness;
        c.cornerDamping = p.floorDampingRatio * std::sqrt(p.floorStiffness * p.payloadMass);  // half of 2 zeta sqrt(k M)
        c.slingLength = p.slingLength - 0.5 * p.payloadHeight;
        c.slingStiffness = p.slingStiffness;
        c.slingDamping = 2.0 * p.slingDampingRatio * std::sqrt(p.slingStiffness * p.hookMass);
        contacts_ = std::make_unique<LiftOffContacts>(*system_, c);
    }
    reeving_ = std::make_unique<ReevingSubsystem>(*system_, Vec3(0, -p.g, 0));
    workMeter_ = std::make_unique<MotionWorkMeter>(*system_);

    addDecorations();

    RopeSpec rope;
    rope.name = "hoist rope";
    WinchDrum drum;
    drum.body = *drum_;
    drum.radius = p.drumRadius;
    // Wrapped, WinchDrum::ropeOnDrum counts the rope up to the drum's top: the quarter turn from
    // there to the tangent point on its left is stored too, so that ropeOnDrum stays the rope
    // stored at t = 0.
    drum.ropeOnDrum = p.ropeOnDrum - (wrapped(p) ? 0.5 * SimTK::Pi * p.drumRadius : 0.0);
    drum.payoutSense = 1;
    rope.start = drum;
    for (int k = 1; k < n; ++k) {
        DeviationSheave sheave;
        sheave.body = nodeOnHook(k) ? static_cast<const MobilizedBody&>(*hook_) : static_cast<const MobilizedBody&>(*trolley_);
        sheave.centre = stations_[k];
        sheave.radius = p.sheaveRadius;
        sheave.wrapSense = wrapSenseOf(k);
        rope.sheaves.push_back(sheave);
    }
    RopeAnchor deadEnd;
    deadEnd.body = nodeOnHook(n) ? static_cast<const MobilizedBody&>(*hook_) : static_cast<const MobilizedBody&>(*trolley_);
    deadEnd.station = stations_[n];
    rope.end = deadEnd;
    rope.properties = {p.rhoA, p.EA, p.EI, p.tensionOnly};
    // Unstretched length: the falls' lengths with the hook at its initial depth, shortened by the
    // stretch of the static tension (M g / n per fall; lift-off: the hook block's weight alone).
    const double geometric = fallsLengthAt(p, layout, p.initialHookDepth);
    const double tension = (p.payloadMass + p.hookMass) * p.g / n;
    const double hanging = liftOff ? p.hookMass * p.g / n : tension;
    // The rope on the grooves is inextensible (GrooveArc): it adds its geometric length. A wrapped
    // drum's s = s_ref + dsdTheta theta is the material coordinate at its top: the rope's s starts
    // a quarter turn before the tangent point on its left, so the rope is that much longer.
    rope.unstretchedLength = geometric / std::sqrt(1.0 + 2.0 * hanging / p.EA) + arcsLength(p, false) +
                             (wrapped(p) ? 0.5 * SimTK::Pi * p.drumRadius : 0.0);
    rope.spanDefaults = spans;
    rope.planeNormal = Vec3(0, 0, 1);
    rope.sheaveModel = p.sheaveModel;
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
    // Lift-off: the floor slab the payload stands on (its top at floorHeight).
    if (std::isfinite(floorHeight_))
        matter_->updGround().addBodyDecoration(
            Transform(Vec3(p.trolleyX0 + hookRestOffset_, floorHeight_ - 0.1, 0)),
            DecorativeBrick(Vec3(0.5 * p.payloadWidth + 1.5, 0.1, 1.2)).setColor(Vec3(0.45, 0.42, 0.38)));
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
    // (Lift-off: the sling's legs are drawn by its subsystem, between the bodies.)
    for (double sx : {-0.4, 0.4})
        if (!contacts_) payload_->addBodyDecoration(Transform(), DecorativeLine(Vec3(0, p.slingLength, 0),
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
    if (contacts_) {
        // On the floor, pressed in by its weight (the equilibrium's first guess), under the pin.
        const double sink = p.payloadMass * p.g / p.floorStiffness;
        payload_->setQToFitTransform(
            s, Transform(Vec3(p.trolleyX0 + hookRestOffset_, floorHeight_ + 0.5 * p.payloadHeight - sink, 0)));
    } else {
        payload_->setOneQ(s, 0, 0.0);
    }
    system_->realize(s, Stage::Time);
    system_->prescribe(s);
    reeving_->findStaticEquilibrium(s, 1e-9);
    system_->prescribe(s);
    workMeter_->setWork(s, 0);
    if (contacts_) contactsGuts(*contacts_).setDissipation(s, 0);
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

double CraneScene::ropeOnDrum(const SimTK::State& s) const { return reeving_->getRope(0).getWinchDrum(0).getRopeOnDrum(s); }

double CraneScene::motorTorque(const SimTK::State& s) const {
    return -drum_->getOneTau(s, SimTK::MobilizerUIndex(0));
}

double CraneScene::trolleyForce(const SimTK::State& s) const {
    return -trolley_->getOneTau(s, SimTK::MobilizerUIndex(0));
}

double CraneScene::ropeForce(const SimTK::State& s) const {
    double f = 0;
    for (int k = 0; k < parameters_.falls; ++k) f += fallTopForce(s, k);
    return f;
}

double CraneScene::hookStiffness() const { return hookStiffnessOf(parameters_, fallsLength_); }

double CraneScene::staticRopeForce() const {
    const CraneParameters& p = parameters_;
    return liftedMass() * p.g + p.rhoA * p.g * (fallsLength_ + arcsLength(p, true));
}

double CraneScene::largestFallLean(const SimTK::State& s) const {
    double lean = 0;
    for (int k = 0; k < parameters_.falls; ++k) {
        const std::vector<SimTK::Vec3> ends = reeving_->sampleSpan(s, 0, k, 2);
        const SimTK::Vec3 d = ends[1] - ends[0];
        lean = std::max(lean, std::atan2(std::abs(d[0]), std::abs(d[1])));
    }
    return lean;
}

double CraneScene::sheaveWrapAngle(const SimTK::State& s, int k) const {
    if (k < 1 || k >= parameters_.falls)
        throw std::invalid_argument("CraneScene::sheaveWrapAngle: sheave " + std::to_string(k) + " is outside 1.." +
                                    std::to_string(parameters_.falls - 1));
    return wrapped(parameters_) ? reeving_->getWrapAngle(s, 0, k) : 0.0;
}

double CraneScene::ropeLengthError(const SimTK::State& s) const {
    double l = ropeOnSheaves(s) + ropeOnDrum(s);
    for (int k = 0; k < parameters_.falls; ++k) {
        const auto range = reeving_->getSpanMaterialRange(s, 0, k);
        l += range.second - range.first;
    }
    const RopeSpec& spec = reeving_->getRopeSpec(0);  // (wrapped: the rope stored up to the drum's top)
    return l - (spec.unstretchedLength + std::get<WinchDrum>(spec.start).ropeOnDrum);
}

double CraneScene::ropeOnSheaves(const SimTK::State& s) const {
    double l = 0;
    for (int k = 1; k < parameters_.falls; ++k) l += reeving_->getArcLength(s, 0, k);
    return l;
}

double CraneScene::springMassDynamicFactor() const {
    const CraneParameters& p = parameters_;
    return 1.0 + p.hoistSpeed * std::sqrt(hookStiffness() / liftedMass()) / p.g;
}

double CraneScene::ropeSlack() const {
    return parameters_.scenario == CraneScenario::LiftOff ? liftOffSlack(parameters_) : 0.0;
}

double CraneScene::floorForce(const SimTK::State& s) const { return contacts_ ? contactsGuts(*contacts_).floorForce(s) : 0.0; }

double CraneScene::slingForce(const SimTK::State& s) const { return contacts_ ? contactsGuts(*contacts_).slingForce(s) : 0.0; }

double CraneScene::payloadClearance(const SimTK::State& s) const {
    return contacts_ ? contactsGuts(*contacts_).lowestCornerHeight(s) : SimTK::NaN;
}

double CraneScene::contactDissipation(const SimTK::State& s) const {
    return contacts_ ? contactsGuts(*contacts_).getDissipation(s) : 0.0;
}

double CraneScene::energyResidual(const SimTK::State& s, double e0) const {
    return reeving_->calcMechanicalEnergy(s) - e0 + contactDissipation(s) - workMeter_->getWork(s);
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
