#pragma once
/// @file
/// A traction elevator, roped 1:1 or 2:1, as a ready Simbody scene: car and counterweight on vertical
/// guide rails (sliders), one rope (the rope set as one rope of the set's rhoA and EA) over a traction
/// sheave (a TractionSheave node) at the top of the hoistway, and the four scenarios of
/// EN 81-50's traction checks.

#include "SimbodyReeving/scenes/MotionProfile.h"
#include "SimbodyReeving/simbody/MotionWorkMeter.h"
#include "SimbodyReeving/simbody/ReevingSubsystem.h"

#include <Simbody.h>

#include <memory>
#include <optional>
#include <string>

namespace SimbodyReeving {

/// What the elevator does (ElevatorParameters::scenario):
///   - Trip: a floor-to-floor trip upwards of the fully loaded car, the machine sheave on a smooth
///     speed profile (MotionProfile: acceleration continuous, jerk bounded).
///   - Loading: the car stands at the bottom landing loaded to 125 % of the rated load, the brake
///     holding the sheave (EN 81-50's loading case, a static check): the run starts from the static
///     equilibrium with that load and lasts a few seconds, so the traction table reports whether
///     the groove holds the 125 % load at rest (the load is not applied as a step).
///   - EmergencyStop: the fully loaded car runs down at rated speed; from t = 0 the machine brake
///     stops the sheave with a smooth deceleration profile peaking at brakeDeceleration (its
///     surface): the sheave is prescribed, so the brake's work is the machine's (MotionWorkMeter).
///   - Stall: the counterweight rests on its buffer (a stop force) while the machine keeps driving the
///     empty car up: the rope must slip, so the car cannot be hauled into the overhead.
enum class ElevatorScenario { Trip, Loading, EmergencyStop, Stall };

/// "trip", "loading", "emergency-stop", "stall".
const char* toString(ElevatorScenario scenario);
/// @throws std::invalid_argument for any other name.
ElevatorScenario elevatorScenarioFromString(const std::string& name);

/// Physical parameters (SI units). The defaults: a 630 kg passenger elevator, 1.6 m/s, 1:1 roping,
/// four 10 mm ropes over a 640 mm traction sheave with an undercut U groove.
struct ElevatorParameters {
    ElevatorScenario scenario = ElevatorScenario::Trip;  ///< which traction check the scene runs
    double g = 9.81;                ///< [m/s^2], > 0
    double carMass = 1000.0;        ///< empty car with its sling [kg], > 0
    double ratedLoad = 630.0;       ///< [kg], >= 0
    double counterweightMass = 0;   ///< [kg]; 0: car + half the rated load
    double hoistway = 40.0;         ///< sheave axis above the car's rope hitch at the bottom landing [m], > 2
    double sheaveRadius = 0.32;     ///< [m], > 0
    double sheaveInertia = 25.0;    ///< machine sheave, rotor and brake drum about the axis [kg m^2], > 0
    double friction = 0.2;          ///< effective groove friction coefficient mu [-], >= 0
    /// The wrap angle alpha [rad] > 0 given to the traction sheave's capstan law (a double wrap,
    /// an arrangement the model does not see). Unset: pi with SheaveModel::Point (the single wrap
    /// of a point sheave); with SheaveModel::Wrapped the geometry's, from the tangent points at every
    /// evaluation (pi with vertical falls; pi - theta - psi with a deflector that leads the
    /// counterweight's fall off at theta from vertical and a car fall leaning by psi).
    std::optional<double> wrapAngle;
    double rhoA = 1.4;              ///< rope set [kg/m], > 0 (4 x 0.35)
    double EA = 1.6e7;              ///< rope set [N], > 0 (4 x 4 MN)
    double retardationTime = 0.0;   ///< Kelvin-Voigt c of the rope [s], >= 0
    double ratedSpeed = 1.6;        ///< [m/s], > 0
    double tripDistance = 12.0;     ///< Trip: [m], in (0, hoistway - 4)
    double tripRamp = 2.5;          ///< Trip: acceleration time of the speed profile [s], > 0
    double brakeDeceleration = 3.0; ///< EmergencyStop: peak deceleration of the sheave surface [m/s^2], > 0
    double stallSpeed = 0.5;        ///< Stall: surface speed the machine keeps driving at [m/s], > 0
    double bufferStiffness = 2e6;   ///< Stall: counterweight buffer [N/m], > 0
    /// 1 (1:1: the rope's ends on car and counterweight) or 2 (2:1: the rope's ends on the hoistway's
    /// top, passing under a sheave on the car and a sheave on the counterweight; the car moves half
    /// the rope travel and each fall carries half its weight).
    int roping = 1;
    double carSheaveRadius = 0.2;   ///< 2:1: radius of the car's and the counterweight's sheaves [m], > 0
    /// The model of every sheave: the traction sheave, the deflector, the car's and the
    /// counterweight's (2:1) and the compensating rope's pit sheave. SheaveModel::Wrapped (the
    /// default): the rope on their grooves (R alpha of rope with its mass on each), the falls
    /// vertical, the traction sheave's wrap angle from the geometry; SheaveModel::Point: the paper's
    /// point sheaves, the falls chords to their centres, the traction sheave's wrap angle
    /// wrapAngle (pi unset).
    SheaveModel sheaveModel = SheaveModel::Wrapped;
    /// How the rope slips over the traction sheave (TractionSheave::slipModel): the massless
    /// contact point (TractionSlip::CapstanConstraint, the default) or the rope's momentum on the
    /// groove with the centrifugal term (TractionSlip::RopeMomentum; its axial mode at the sheave
    /// rings after each slip onset unless retardationTime damps it).
    TractionSlip tractionSlip = TractionSlip::CapstanConstraint;
    /// 1:1 with SheaveModel::Wrapped: a deflector sheave (a DeviationSheave on Ground, radius
    /// deflectorRadius, centre deflectorDrop below the traction sheave's axis and
    /// deflectorRadius left of counterweightRail): the rope runs from the traction sheave down to
    /// it and around its right side, and the counterweight hangs at x = counterweightRail. It sets
    /// the traction sheave's wrap angle to pi - theta, theta the lead-off span's angle from vertical.
    bool deflector = false;
    double deflectorRadius = 0.2;     ///< [m], > 0
    double deflectorDrop = 0.8;       ///< its centre below the traction sheave's axis [m], in (0, 1]
    /// x of the counterweight's fall with the deflector [m]: > sheaveRadius, the deflector clear of
    /// the traction sheave (centres more than sheaveRadius + deflectorRadius apart).
    double counterweightRail = 0.7;
    /// 1:1: the car's rope hitch carHitchOffset [m] left of the traction sheave's tangent line
    /// x = -sheaveRadius (>= 0, < 0.5): the car's fall leans by about carHitchOffset / its length,
    /// so the wrap angle changes as the car moves (0: vertical).
    double carHitchOffset = 0;
    /// A compensating rope: from under the car (2.5 m below its hitch) down around a weighted pit
    /// sheave and up to under the counterweight (3 m below its hitch), a second rope in the same
    /// ReevingSubsystem. It balances the hoist ropes' weight moving from one side to the other.
    bool compensation = false;
    double compensationRhoA = 0;          ///< its mass per length [kg/m], >= 0 (0: rhoA, full compensation)
    double pitSheaveMass = 500.0;         ///< pit sheave with its tensioning weight, on a vertical guide [kg], > 0
    /// The car's load as a fraction of the rated load [-], in [0, 1.25] (empty to EN 81-50's 125 %);
    /// unset: the scenario's own (Trip and EmergencyStop 1, Loading 1.25, Stall 0). The
    /// counterweight keeps its mass (counterweight()).
    std::optional<double> carLoad;
    /// The car's height above the bottom landing at t = 0 [m] (of its rope hitch; 2:1: of its
    /// sheave's centre); unset: the scenario's own (the bottom landing, 0; mid-shaft, hoistway / 2,
    /// in EmergencyStop). The counterweight starts where the rope's length puts it (as much higher
    /// than its own start as the car is, the same rope in every position). Range: car and
    /// counterweight at least 2 m below the traction sheave's axis and not below their bottom
    /// positions: [0, hoistway - 2] ([2, hoistway - 2] in EmergencyStop, where the counterweight
    /// starts at depth carPosition); Trip also needs carPosition + tripDistance < hoistway - 4.
    std::optional<double> carPosition;
    /// @throws std::invalid_argument naming the first parameter out of range (carPosition's range
    /// depends on `scenario`).
    void validate() const;
    /// The counterweight's mass [kg]: counterweightMass if > 0, else carMass + ratedLoad / 2.
    double counterweight() const { return counterweightMass > 0 ? counterweightMass : carMass + 0.5 * ratedLoad; }
};

/// The elevator in the x-y plane (y up). Bodies: the machine sheave, a MobilizedBody::Pin (axis z) at
/// the origin, prescribed in every scenario (the trip's speed profile, held in Loading, the brake's
/// stop in EmergencyStop, the stalled drive); the car and the counterweight, MobilizedBody::Sliders
/// along y (q = the height of the rope hitch, in 2:1 of the sheave's centre [m]).
/// - 1:1: car and counterweight at x = -R and x = +R. Rope: car hitch (start) -> TractionSheave
///   (node 1) -> counterweight hitch (end). With the deflector: the car at x = -(R + carHitchOffset),
///   the counterweight at x = counterweightRail, the rope car hitch -> TractionSheave (node 1) ->
///   deflector (node 2) -> counterweight hitch.
/// - 2:1: car and counterweight at x = -(R + r) and x = +(R + r), r = carSheaveRadius. Rope: hitch on
///   Ground at (-(R + 2 r), 0) (start) -> DeviationSheave on the car -> TractionSheave (node 2) ->
///   DeviationSheave on the counterweight -> hitch on Ground at (R + 2 r, 0) (end).
/// With compensation: a pit sheave (MobilizedBody::Slider along y at x = 0, free: its weight
/// tensions the rope) of radius x_rail, its centre 6 m below the car's bottom at the bottom landing;
/// rope 1: car (start) -> DeviationSheave on the pit sheave -> counterweight (end), EA as the hoist
/// ropes', tension-only.
/// The traction sheave's sense is +1: a positive sheave angle moves rope towards the car, lowering
/// it. Tension-only rope, spans with the given options. A MotionWorkMeter holds the machine's work:
/// energy residual = E(t) - E(0) + W_friction + W_damping - W_machine.
class ElevatorScene {
public:
    /// @throws std::invalid_argument for bad parameters or span options.
    ElevatorScene(const ElevatorParameters& parameters, const SpanOptions& spans);

    SimTK::MultibodySystem& system() { return *system_; }  ///< the scene's system (the scene owns it)
    const SimTK::MultibodySystem& system() const { return *system_; }  ///< the scene's system
    const ReevingSubsystem& reeving() const { return *reeving_; }  ///< the hoist rope (and the compensating rope)
    const MotionWorkMeter& workMeter() const { return *workMeter_; }  ///< work of the machine (the prescribed sheave)
    const ElevatorParameters& parameters() const { return parameters_; }  ///< as given, validated
    const SimTK::MobilizedBody::Pin& sheave() const { return *sheave_; }  ///< the machine's traction sheave
    /// The car's mass in this scenario (empty in Stall, rated load in Trip and EmergencyStop, 125 % of
    /// it in Loading; carMass + carLoad ratedLoad when carLoad is set) [kg].
    double carTotalMass() const;
    /// The end of the scenario's run [s].
    double duration() const;
    /// The traction sheave's node in the hoist rope (rope 0): 1 in 1:1, 2 in 2:1.
    int tractionNode() const { return parameters_.roping; }
    /// The traction sheave's handle: its mode, slip and friction (TractionSheaveHandle).
    TractionSheaveHandle tractionSheave() const;

    /// The state at t = 0: static equilibrium (in stick) of car, counterweight and rope (in Loading
    /// with the car's mass at 125 % of the rated load; in Stall with the counterweight settled on
    /// its buffer); in EmergencyStop every body then moving at rated speed (car down);
    /// the traction modes updated (ReevingSubsystem::updateTractionModes); realized to Stage::Velocity.
    SimTK::State makeInitialState() const;

    // ---- observables (Stage::Position unless said otherwise)
    double carHeight(const SimTK::State& s) const;           ///< car hitch height [m]
    double counterweightHeight(const SimTK::State& s) const; ///< [m]
    /// Height of the pit sheave's centre [m]; NaN without compensation.
    double pitSheaveHeight(const SimTK::State& s) const;
    double carVelocity(const SimTK::State& s) const;         ///< [m/s] (Stage::Velocity)
    double carAcceleration(const SimTK::State& s) const;     ///< [m/s^2] (Stage::Acceleration)
    /// The machine's rope travel since t = 0: R (theta - theta_0) [m] (positive: rope towards the car).
    double ropeTravel(const SimTK::State& s) const;
    /// Axial force of the car-side fall at the traction sheave [N] (2:1: one of the two falls that
    /// carry the car).
    double carSideForce(const SimTK::State& s) const;
    double counterweightSideForce(const SimTK::State& s) const;  ///< [N]
    /// The wrap angle the traction sheave's capstan law uses [rad] (ReevingSubsystem::getWrapAngle).
    double tractionWrapAngle(const SimTK::State& s) const;
    /// x of the car's and the counterweight's falls (their sliders' rails) [m].
    double carRail() const;
    double counterweightRail() const;  ///< [m]
    /// E(t) - E(0) + W_friction + W_damping - W_machine [J] (Stage::Velocity), e0 = E(0).
    double energyResidual(const SimTK::State& s, double e0) const;

private:
    double brakeTime() const;

    ElevatorParameters parameters_;
    std::unique_ptr<SimTK::MultibodySystem> system_;
    std::unique_ptr<SimTK::SimbodyMatterSubsystem> matter_;
    std::unique_ptr<SimTK::GeneralForceSubsystem> forces_;
    std::unique_ptr<ReevingSubsystem> reeving_;
    std::unique_ptr<MotionWorkMeter> workMeter_;
    std::unique_ptr<SimTK::MobilizedBody::Pin> sheave_;
    std::unique_ptr<SimTK::MobilizedBody::Slider> car_, counterweight_, pitSheave_;
    double carStart_ = 0, cwtStart_ = 0, pitStart_ = 0;
};

}  // namespace SimbodyReeving
