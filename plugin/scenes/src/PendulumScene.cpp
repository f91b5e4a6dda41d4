#include "SimbodyReeving/scenes/PendulumScene.h"

#include <cmath>
#include <sstream>
#include <stdexcept>

namespace SimbodyReeving {

void PendulumParameters::validate() const {
    auto check = [](const char* name, double v, bool ok, const char* range) {
        if (!std::isfinite(v) || !ok) {
            std::ostringstream o;
            o << "PendulumParameters: " << name << " = " << v << " must be finite and " << range;
            throw std::invalid_argument(o.str());
        }
    };
    check("a", a, a > 0, "> 0");
    check("L", L, L > 0, "> 0");
    check("d", d, d >= 0, ">= 0");
    check("r", r, r > 0, "> 0");
    check("g", g, g >= 0, ">= 0");
    check("rhoA", rhoA, rhoA > 0, "> 0");
    check("EA", EA, EA > 0, "> 0");
    check("EI", EI, EI >= 0, ">= 0");
    check("M", M, M > 0, "> 0");
    check("J", J, J > 0, "> 0");
}

PendulumScene::PendulumScene(const PendulumParameters& p, const SpanOptions& spans, bool planarRope,
                             const std::optional<SpanOptions>& horizontalSpan)
    : parameters_(p) {
    p.validate();
    using namespace SimTK;
    system_ = std::make_unique<MultibodySystem>();
    matter_ = std::make_unique<SimbodyMatterSubsystem>(*system_);
    forces_ = std::make_unique<GeneralForceSubsystem>(*system_);
    gravity_ = std::make_unique<Force::Gravity>(*forces_, *matter_, Vec3(0, -p.g, 0));
    reeving_ = std::make_unique<ReevingSubsystem>(*system_, Vec3(0, -p.g, 0));
    const Body::Rigid body(MassProperties(p.M, Vec3(0), Inertia(p.J)));
    payload_ = std::make_unique<MobilizedBody::Free>(matter_->updGround(), Transform(), body, Transform());
    // Drawing: the payload as the cube of its mass and inertia (J = M side^2 / 6), a link up to the
    // rope's attachment d above its centre.
    const double side = std::sqrt(6.0 * p.J / p.M);
    payload_->addBodyDecoration(Transform(), DecorativeBrick(Vec3(0.5 * side)).setColor(Vec3(0.2, 0.6, 0.3)));
    if (p.d > 0.5 * side)
        payload_->addBodyDecoration(Transform(), DecorativeLine(Vec3(0, 0.5 * side, 0), Vec3(0, p.d, 0))
                                                     .setColor(Vec3(0.2, 0.2, 0.2))
                                                     .setLineThickness(3));

    RopeSpec rope;
    rope.name = "pendulum rope";
    rope.start = RopeAnchor{matter_->Ground(), Vec3(0)};
    DeviationSheave sheave{matter_->Ground(), Vec3(p.a, 0, 0), p.r};
    sheave.wrapSense = -1;  // from the anchor along the top and down the far side: clockwise about +z
    rope.sheaves = {sheave};
    rope.sheaveModel = p.sheaveModel;
    rope.end = RopeAnchor{*payload_, Vec3(0, p.d, 0)};
    rope.properties = {p.rhoA, p.EA, p.EI, p.tensionOnly};
    rope.unstretchedLength = p.a + p.L;
    rope.spanDefaults = spans;
    if (horizontalSpan) rope.spanOverrides = {{0, *horizontalSpan}};
    rope.planeNormal = planarRope ? Vec3(0, 0, 1) : Vec3(0);
    reeving_->addRope(rope);
    // Rope colours (drawing only): red at twice the payload's weight.
    reeving_->setDecorationForceScale(2.0 * p.M * p.g);  // g = 0: the largest force of each frame
    system_->realizeTopology();
}

SimTK::State PendulumScene::makeInitialState(double vx, double vy) const {
    using namespace SimTK;
    const PendulumParameters& p = parameters_;
    State s = system_->getDefaultState();
    // Straight hanging guess: both spans at the tension of the hanging weight.
    const double P = (p.M + p.rhoA * p.L) * p.g;
    const double stretch = std::sqrt(1.0 + 2.0 * P / p.EA);
    // (A wrapped sheave lets the vertical span go at its groove's far side, r from its centre.)
    const double x = p.sheaveModel == SheaveModel::Wrapped ? p.a + p.r : p.a;
    payload_->setQToFitTranslation(s, Vec3(x, -p.L * stretch - p.d, 0));
    reeving_->findStaticEquilibrium(s, 1e-9);
    payload_->setUToFitLinearVelocity(s, Vec3(vx, vy, 0));
    system_->realize(s, Stage::Velocity);
    return s;
}

SimTK::Vec3 PendulumScene::payloadPosition(const SimTK::State& s) const {
    return payload_->getBodyOriginLocation(s);
}
double PendulumScene::payloadAngle(const SimTK::State& s) const {
    const SimTK::Vec3 x = payload_->getBodyRotation(s).x();
    return std::atan2(x[1], x[0]);
}
double PendulumScene::axialForceAtPayload(const SimTK::State& s) const {
    const auto range = reeving_->getSpanMaterialRange(s, 0, 1);
    return reeving_->getAxialForce(s, 0, 1, range.second);
}
double PendulumScene::axialForceAtSheave(const SimTK::State& s) const {
    const auto range = reeving_->getSpanMaterialRange(s, 0, 1);
    return reeving_->getAxialForce(s, 0, 1, range.first);
}
double PendulumScene::sheaveMaterialCoordinate(const SimTK::State& s) const {
    return reeving_->getMaterialCoordinate(s, 0, 1);
}

}  // namespace SimbodyReeving
