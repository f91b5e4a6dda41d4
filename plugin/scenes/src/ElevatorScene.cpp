#include "SimbodyReeving/scenes/ElevatorScene.h"

#include <cmath>
#include <sstream>
#include <stdexcept>

namespace SimbodyReeving {

const char* toString(ElevatorScenario scenario) {
    switch (scenario) {
        case ElevatorScenario::Trip: return "trip";
        case ElevatorScenario::Loading: return "loading";
        case ElevatorScenario::EmergencyStop: return "emergency-stop";
        case ElevatorScenario::Stall: return "stall";
    }
    return "?";
}

ElevatorScenario elevatorScenarioFromString(const std::string& name) {
    for (ElevatorScenario s : {ElevatorScenario::Trip, ElevatorScenario::Loading, ElevatorScenario::EmergencyStop,
                               ElevatorScenario::Stall})
        if (name == toString(s)) return s;
    throw std::invalid_argument("elevator scenario '" + name + "' is not one of trip, loading, emergency-stop, stall");
}

void ElevatorParameters::validate() const {
    auto check = [](const char* name, double v, bool ok, const char* must) {
        if (!std::isfinite(v) || !ok) {
            std::ostringstream o;
            o << "ElevatorParameters: " << name << " = " << v << " must be " << must;
            throw std::invalid_argument(o.str());
        }
    };
    check("g [m/s^2]", g, g > 0, "finite and > 0");
    check("carMass [kg]", carMass, carMass > 0, "finite and > 0");
    check("ratedLoad [kg]", ratedLoad, ratedLoad >= 0, "finite and >= 0");
    check("counterweightMass [kg]", counterweightMass, counterweightMass >= 0, "finite and >= 0 (0: car + half the rated load)");
    check("hoistway [m]", hoistway, hoistway > 2, "finite and > 2");
    check("sheaveRadius [m]", sheaveRadius, sheaveRadius > 0, "finite and > 0");
    check("sheaveInertia [kg m^2]", sheaveInertia, sheaveInertia > 0, "finite and > 0");
    check("friction [-]", friction, friction >= 0, "finite and >= 0");
    if (wrapAngle) check("wrapAngle [rad]", *wrapAngle, *wrapAngle > 0, "finite and > 0");
    check("carHitchOffset [m]", carHitchOffset, carHitchOffset >= 0 && carHitchOffset < 0.5, "in [0, 0.5)");
    if (carHitchOffset > 0 && roping != 1)
        throw std::invalid_argument("ElevatorParameters: carHitchOffset applies to 1:1 roping (2:1 hangs the car "
                                    "from its own sheave)");
    if (deflector) {
        if (roping != 1 || sheaveModel != SheaveModel::Wrapped)
            throw std::invalid_argument("ElevatorParameters: the deflector needs 1:1 roping and SheaveModel::Wrapped "
                                        "(it sets the wrapped traction sheave's wrap angle)");
        check("deflectorRadius [m]", deflectorRadius, deflectorRadius > 0, "finite and > 0");
        check("deflectorDrop [m]", deflectorDrop, deflectorDrop > 0 && deflectorDrop <= 1, "in (0, 1]");
        const double cx = counterweightRail - deflectorRadius;
        check("counterweightRail [m]", counterweightRail,
              counterweightRail > sheaveRadius &&
                  std::hypot(cx, deflectorDrop) > sheaveRadius + deflectorRadius,
              "> sheaveRadius, with the deflector (centre deflectorRadius left of it) clear of the traction sheave");
    }
    check("rhoA [kg/m]", rhoA, rhoA > 0, "finite and > 0");
    check("EA [N]", EA, EA > 0, "finite and > 0");
    check("retardationTime [s]", retardationTime, retardationTime >= 0, "finite and >= 0");
    check("ratedSpeed [m/s]", ratedSpeed, ratedSpeed > 0, "finite and > 0");
    check("tripDistance [m]", tripDistance, tripDistance > 0 && tripDistance < hoistway - 4, "in (0, hoistway - 4)");
    check("tripRamp [s]", tripRamp, tripRamp > 0, "finite and > 0");
    check("brakeDeceleration [m/s^2]", brakeDeceleration, brakeDeceleration > 0, "finite and > 0");
    check("stallSpeed [m/s]", stallSpeed, stallSpeed > 0, "finite and > 0");
    check("bufferStiffness [N/m]", bufferStiffness, bufferStiffness > 0, "finite and > 0");
    check("roping [-]", roping, roping == 1 || roping == 2, "1 (1:1) or 2 (2:1)");
    check("carSheaveRadius [m]", carSheaveRadius, carSheaveRadius > 0, "finite and > 0");
    check("compensationRhoA [kg/m]", compensationRhoA, compensationRhoA >= 0, "finite and >= 0 (0: rhoA)");
    check("pitSheaveMass [kg]", pitSheaveMass, pitSheaveMass > 0, "finite and > 0");
    if (carLoad) check("carLoad [-]", *carLoad, *carLoad >= 0 && *carLoad <= 1.25, "in [0, 1.25] (of the rated load)");
    if (carPosition) {
        const double z = *carPosition;
        if (scenario == ElevatorScenario::EmergencyStop)
            check("carPosition [m]", z, z >= 2 && z <= hoistway - 2,
                  "in [2, hoistway - 2] in the emergency-stop scenario (car and counterweight 2 m or more below "
                  "the sheave)");
        else
            check("carPosition [m]", z, z >= 0 && z <= hoistway - 2,
                  "in [0, hoistway - 2] (car and counterweight 2 m or more below the sheave)");
        if (scenario == ElevatorScenario::Trip)
            check("carPosition + tripDistance [m]", z + tripDistance, z + tripDistance < hoistway - 4,
                  "< hoistway - 4 in the trip scenario");
    }
}

namespace {

/// The brake's stop of a sheave turning at omega0 at t = 0: omega(t) = omega0 (1 - r(t / T)),
/// r(u) = 6 u^5 - 15 u^4 + 10 u^3 (acceleration continuous, zero at both ends), standstill from T on.
class BrakeStop : public SimTK::Motion::Custom::Implementation {
public:
    BrakeStop(double omega0, double T) : omega0_(omega0), T_(T) {}
    Implementation* clone() const override { return new BrakeStop(*this); }
    SimTK::Motion::Level getLevel(const SimTK::State&) const override { return SimTK::Motion::Position; }
    void calcPrescribedPosition(const SimTK::State& s, int nq, SimTK::Real* q) const override {
        const double u = std::min(std::max(s.getTime() / T_, 0.0), 1.0);
        if (nq == 1) q[0] = omega0_ * T_ * (u - (std::pow(u, 6) - 3 * std::pow(u, 5) + 2.5 * std::pow(u, 4)));
    }
    void calcPrescribedPositionDot(const SimTK::State& s, int nq, SimTK::Real* qdot) const override {
        const double u = std::min(std::max(s.getTime() / T_, 0.0), 1.0);
        if (nq == 1) qdot[0] = omega0_ * (1 - (6 * std::pow(u, 5) - 15 * std::pow(u, 4) + 10 * std::pow(u, 3)));
    }
    void calcPrescribedPositionDotDot(const SimTK::State& s, int nq, SimTK::Real* qdotdot) const override {
        const double u = std::min(std::max(s.getTime() / T_, 0.0), 1.0);
        if (nq == 1) qdotdot[0] = -omega0_ / T_ * (30 * std::pow(u, 4) - 60 * std::pow(u, 3) + 30 * u * u);
    }

private:
    double omega0_, T_;
};

}  // namespace

double ElevatorScene::carTotalMass() const {
    const ElevatorParameters& p = parameters_;
    if (p.carLoad) return p.carMass + *p.carLoad * p.ratedLoad;
    switch (p.scenario) {
        case ElevatorScenario::Stall: return p.carMass;
        case ElevatorScenario::Loading: return p.carMass + 1.25 * p.ratedLoad;
        default: return p.carMass + p.ratedLoad;
    }
}

double ElevatorScene::duration() const {
    const ElevatorParameters& p = parameters_;
    switch (p.scenario) {
        case ElevatorScenario::Trip: return 1.0 + p.tripDistance / p.ratedSpeed + p.tripRamp + 2.0;
        case ElevatorScenario::Loading: return 3.0;
        case ElevatorScenario::EmergencyStop: return brakeTime() + 2.0;
        case ElevatorScenario::Stall: return 6.0;
    }
    return 1.0;
}

// The brake's stop time T: the surface speed roping * ratedSpeed falls to 0 along the quintic
// r(t / T), whose peak rate 15 / 8 of the mean is brakeDeceleration.
double ElevatorScene::brakeTime() const {
    const ElevatorParameters& p = parameters_;
    return 15.0 * p.roping * p.ratedSpeed / (8.0 * p.brakeDeceleration);
}

ElevatorScene::ElevatorScene(const ElevatorParameters& parameters, const SpanOptions& spans) : parameters_(parameters) {
    using namespace SimTK;
    const ElevatorParameters& p = parameters_;
    p.validate();
    system_ = std::make_unique<MultibodySystem>();
    matter_ = std::make_unique<SimbodyMatterSubsystem>(*system_);
    forces_ = std::make_unique<GeneralForceSubsystem>(*system_);
    Force::Gravity(*forces_, *matter_, -YAxis, p.g);
    const double R = p.sheaveRadius;
    sheave_ = std::make_unique<MobilizedBody::Pin>(matter_->Ground(), Transform(),
                                                   Body::Rigid(MassProperties(200, Vec3(0), Inertia(p.sheaveInertia))),
                                                   Transform());
    const Rotation slideUp(Pi / 2, ZAxis);  // the sliders' x axis along Ground's y: q is the height
    const bool twoToOne = p.roping == 2;
    const double r = p.carSheaveRadius;
    car_ = std::make_unique<MobilizedBody::Slider>(matter_->Ground(), Transform(slideUp, Vec3(-carRail(), 0, 0)),
                                                   Body::Rigid(MassProperties(carTotalMass(), Vec3(0), Inertia(500))),
                                                   Transform(slideUp));
    counterweight_ = std::make_unique<MobilizedBody::Slider>(
        matter_->Ground(), Transform(slideUp, Vec3(counterweightRail(), 0, 0)),
        Body::Rigid(MassProperties(p.counterweight(), Vec3(0), Inertia(100))), Transform(slideUp));
    // Heights at t = 0: the car carPosition above the bottom landing (default: at it in Trip, Loading
    // and Stall, mid-shaft in EmergencyStop); the counterweight where the rope puts it (2 m below the
    // sheave with the car at the bottom landing; at depth carPosition in EmergencyStop), so the
    // ropes' lengths are the same in every position.
    const bool emergency = p.scenario == ElevatorScenario::EmergencyStop;
    const double z = p.carPosition ? *p.carPosition : (emergency ? 0.5 * p.hoistway : 0.0);
    carStart_ = -p.hoistway + z;
    cwtStart_ = emergency ? -z : -2.0 - z;
    const double cwtStart = cwtStart_;
    switch (p.scenario) {
        case ElevatorScenario::Trip: {
            MotionProfile lift;  // car height gained; the sheave turns -roping / R rad per metre
            lift.moves.push_back({1.0, p.tripDistance / p.ratedSpeed + p.tripRamp, p.tripRamp, p.tripDistance});
            prescribeProfile(*sheave_, lift, -p.roping / R);
            break;
        }
        case ElevatorScenario::Loading: Motion::Steady(*sheave_, 0.0); break;
        case ElevatorScenario::EmergencyStop:
            // The car runs down: rope towards the car, theta increasing.
            Motion::Custom(*sheave_, new BrakeStop(p.roping * p.ratedSpeed / R, brakeTime()));
            break;
        case ElevatorScenario::Stall: {
            MotionProfile drive;  // the machine's surface drives at stallSpeed after a 1 s ramp
            const double D = 100.0;
            drive.moves.push_back({0.5, D, 1.0, p.stallSpeed * (D - 1.0)});
            prescribeProfile(*sheave_, drive, -1.0 / R);
            // The buffer: 1 cm under the counterweight's start (the drive lowers it onto it).
            Force::MobilityLinearStop(*forces_, *counterweight_, MobilizerQIndex(0), p.bufferStiffness, 0.0,
                                      cwtStart - 0.01, 10.0);
            break;
        }
    }
    reeving_ = std::make_unique<ReevingSubsystem>(*system_);
    RopeSpec rope;
    rope.name = "hoist ropes";
    TractionSheave ts;
    ts.body = *sheave_;
    ts.radius = R;
    ts.frictionCoefficient = p.friction;
    // Given, or (0) the geometry's with the wrapped model; pi for the point model's single wrap.
    ts.wrapAngle = p.wrapAngle ? *p.wrapAngle : (p.sheaveModel == SheaveModel::Wrapped ? 0.0 : Pi);
    ts.sense = 1;
    ts.slipModel = p.tractionSlip;
    // Car, counterweight and pit sheaves: the rope passes under them, turning counter-clockwise
    // about +z (wrap sense +1); wrapped, the half turn pi r on each groove is rope too.
    const bool wrapped = p.sheaveModel == SheaveModel::Wrapped;
    auto underSheave = [](const MobilizedBody& body, double radius) {
        DeviationSheave d{body, Vec3(0), radius};
        d.wrapSense = 1;
        return d;
    };
    rope.sheaveModel = p.sheaveModel;
    // The rope's length at t = 0 follows the path (unstretched there; the static equilibrium then
    // stretches it). Wrapped, the traction sheave's TractionSheave::materialCoordinateAtZeroAngle
    // is the material coordinate at its groove's top (WrapStationMap), a quarter turn (less the car
    // fall's lean psi) past the arriving tangent point.
    if (twoToOne) {
        // From the top hitches down to the car's and the counterweight's sheaves (wrapped: the falls
        // vertical, a diameter apart; points: chords to the centres) and up to the traction sheave.
        const double arc = wrapped ? Pi * r : 0.0, tractionArc = wrapped ? Pi * R : 0.0;
        rope.start = RopeAnchor{matter_->Ground(), Vec3(-(R + 2 * r), 0, 0)};
        ts.materialCoordinateAtZeroAngle = -2 * carStart_ + arc + 0.5 * tractionArc;
        rope.sheaves = {underSheave(*car_, r), ts, underSheave(*counterweight_, r)};
        rope.end = RopeAnchor{matter_->Ground(), Vec3(R + 2 * r, 0, 0)};
        rope.unstretchedLength = -2 * carStart_ - 2 * cwtStart + 2 * arc + tractionArc;
    } else {
        rope.start = RopeAnchor{*car_, Vec3(0)};
        rope.end = RopeAnchor{*counterweight_, Vec3(0)};
        if (!wrapped) {
            // The falls' depths (the chords to the centre are about R^2 / 2 H longer: the static
            // equilibrium takes that up).
            ts.materialCoordinateAtZeroAngle = -carStart_;
            rope.sheaves = {ts};
            rope.unstretchedLength = -carStart_ - cwtStart;
        } else {
            // The car's fall from its hitch P = (-(R + e), y) to its tangent point: length
            // sqrt(|C - P|^2 - R^2), leaning by psi, (R + e) cos psi - |y| sin psi = R.
            const double e = p.carHitchOffset, depth = -carStart_;
            const double rho = std::hypot(R + e, depth);
            const double psi = std::acos(R / rho) - std::atan2(depth, R + e);
            const double carFall = std::sqrt(rho * rho - R * R);
            ts.materialCoordinateAtZeroAngle = carFall + R * (0.5 * Pi - psi);
            double length = carFall + R * (Pi - psi);
            if (p.deflector) {
                // The lead-off span, an outer tangent of the two grooves (both turned clockwise):
                // theta = atan2(dx, drop) + asin((r_d - R) / |d|) from vertical, the traction
                // sheave's wrap pi - theta - psi, the deflector's theta; the fall below it vertical.
                const double rd = p.deflectorRadius, dx = p.counterweightRail - rd, drop = p.deflectorDrop;
                const double centres = std::hypot(dx, drop);
                const double theta = std::atan2(dx, drop) + std::asin((rd - R) / centres);
                length += -theta * R + std::sqrt(centres * centres - (R - rd) * (R - rd)) + rd * theta +
                          (-drop - cwtStart);
                DeviationSheave d{matter_->Ground(), Vec3(dx, -drop, 0), rd};
                d.wrapSense = -1;  // clockwise about +z, as over the traction sheave
                rope.sheaves = {ts, d};
            } else {
                length += -cwtStart;
                rope.sheaves = {ts};
            }
            rope.unstretchedLength = length;
        }
    }
    rope.properties = {p.rhoA, p.EA, 0.0, true};
    rope.properties.axialRetardationTime = p.retardationTime;
    rope.spanDefaults = spans;
    rope.planeNormal = Vec3(0, 0, 1);
    reeving_->addRope(rope);
    if (p.compensation) {
        // Hitch offsets under car and counterweight, and the pit sheave 6 m under the car's bottom at
        // the bottom landing (the point sheave's chords then lean at most 3 degrees).
        const double carBottom = -2.5, cwtBottom = -3.0;
        pitStart_ = -p.hoistway + carBottom - 6.0;
        // Its groove spans the two rails: centre between them, radius half their distance.
        const double pitX = 0.5 * (counterweightRail() - carRail()), pitRadius = 0.5 * (counterweightRail() + carRail());
        pitSheave_ = std::make_unique<MobilizedBody::Slider>(
            matter_->Ground(), Transform(slideUp, Vec3(pitX, 0, 0)),
            Body::Rigid(MassProperties(p.pitSheaveMass, Vec3(0), Inertia(10))), Transform(slideUp));
        RopeSpec comp;
        comp.name = "compensating ropes";
        comp.start = RopeAnchor{*car_, Vec3(0, carBottom, 0)};
        comp.sheaves = {underSheave(*pitSheave_, pitRadius)};
        comp.sheaveModel = p.sheaveModel;
        comp.end = RopeAnchor{*counterweight_, Vec3(0, cwtBottom, 0)};
        comp.properties = {p.compensationRhoA > 0 ? p.compensationRhoA : p.rhoA, p.EA, 0.0, true};
        comp.properties.axialRetardationTime = p.retardationTime;
        comp.unstretchedLength =
            (carStart_ + carBottom - pitStart_) + (cwtStart + cwtBottom - pitStart_) + (wrapped ? Pi * pitRadius : 0.0);
        comp.spanDefaults = spans;
        comp.planeNormal = Vec3(0, 0, 1);
        reeving_->addRope(comp);
    }
    reeving_->setDecorationForceScale(1.5 * (p.carMass + p.ratedLoad) * p.g / p.roping);
    workMeter_ = std::make_unique<MotionWorkMeter>(*system_);
    system_->realizeTopology();
}

SimTK::State ElevatorScene::makeInitialState() const {
    using namespace SimTK;
    const ElevatorParameters& p = parameters_;
    State s = system_->getDefaultState();
    s.setTime(0);
    car_->setOneQ(s, 0, carStart_);
    counterweight_->setOneQ(s, 0, cwtStart_);
    if (pitSheave_) pitSheave_->setOneQ(s, 0, pitStart_);
    system_->realize(s, Stage::Time);
    system_->prescribe(s);
    reeving_->findStaticEquilibrium(s, 1e-10);
    if (p.scenario == ElevatorScenario::EmergencyStop) {  // everything at rated speed, car down
        car_->setOneU(s, 0, -p.ratedSpeed);
        counterweight_->setOneU(s, 0, p.ratedSpeed);
    }
    system_->prescribe(s);
    reeving_->updateTractionModes(s);
    workMeter_->setWork(s, 0);
    system_->realize(s, Stage::Velocity);
    return s;
}

double ElevatorScene::carRail() const {
    const ElevatorParameters& p = parameters_;
    return p.roping == 2 ? p.sheaveRadius + p.carSheaveRadius : p.sheaveRadius + p.carHitchOffset;
}
double ElevatorScene::counterweightRail() const {
    const ElevatorParameters& p = parameters_;
    if (p.roping == 2) return p.sheaveRadius + p.carSheaveRadius;
    return p.deflector ? p.counterweightRail : p.sheaveRadius;
}
double ElevatorScene::tractionWrapAngle(const SimTK::State& s) const {
    return reeving_->getWrapAngle(s, 0, tractionNode());
}

double ElevatorScene::carHeight(const SimTK::State& s) const { return car_->getOneQ(s, 0); }
double ElevatorScene::counterweightHeight(const SimTK::State& s) const { return counterweight_->getOneQ(s, 0); }
double ElevatorScene::pitSheaveHeight(const SimTK::State& s) const {
    return pitSheave_ ? pitSheave_->getOneQ(s, 0) : SimTK::NaN;
}
double ElevatorScene::carVelocity(const SimTK::State& s) const { return car_->getOneU(s, 0); }
double ElevatorScene::carAcceleration(const SimTK::State& s) const { return car_->getOneUDot(s, 0); }
double ElevatorScene::ropeTravel(const SimTK::State& s) const { return parameters_.sheaveRadius * sheave_->getOneQ(s, 0); }
TractionSheaveHandle ElevatorScene::tractionSheave() const { return reeving_->getRope(0).getTractionSheave(tractionNode()); }

// Spans tractionNode() - 1 and tractionNode() meet at the traction sheave.
double ElevatorScene::carSideForce(const SimTK::State& s) const {
    const int span = tractionNode() - 1;
    const auto range = reeving_->getSpanMaterialRange(s, 0, span);
    return reeving_->getAxialForce(s, 0, span, range.second);
}
double ElevatorScene::counterweightSideForce(const SimTK::State& s) const {
    const int span = tractionNode();
    const auto range = reeving_->getSpanMaterialRange(s, 0, span);
    return reeving_->getAxialForce(s, 0, span, range.first);
}
double ElevatorScene::energyResidual(const SimTK::State& s, double e0) const {
    return reeving_->calcMechanicalEnergy(s) - e0 + reeving_->getTotalFrictionWork(s) + reeving_->getDampingWork(s) -
           workMeter_->getWork(s);
}

}  // namespace SimbodyReeving
