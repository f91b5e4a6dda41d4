#pragma once
/// @file
/// The paper's two-branch pendulum (section 3, Fig 1, Table 1) as a ready Simbody scene.

#include "SimbodyReeving/simbody/ReevingSubsystem.h"

#include <Simbody.h>

#include <memory>
#include <optional>

namespace SimbodyReeving {

/// Table 1 of the paper (SI units); defaults are the paper's values.
struct PendulumParameters {
    double a = 3.0;         ///< horizontal span between the sheaves [m], > 0
    double L = 20.0;        ///< unstretched length of the vertical span [m], > 0
    double d = 0.3;         ///< rope attachment above the payload's centre of mass [m], >= 0
    double r = 0.1;         ///< sheave radius [m], > 0
    double g = 9.81;        ///< gravitational acceleration [m/s^2], >= 0
    double rhoA = 0.6205;   ///< rope mass per length [kg/m], > 0
    double EA = 16.5e6;     ///< axial stiffness [N], > 0
    double EI = 30.9;       ///< bending stiffness [N m^2], >= 0
    double M = 1000.0;      ///< payload mass [kg], > 0
    double J = 36.0;        ///< payload moment of inertia about every axis through its centre [kg m^2], > 0
    bool tensionOnly = true;  ///< RopeProperties::tensionOnly of the rope (the paper's linear law: false)
    /// The deviation sheave: the paper's point sheave (default, reproduces its Table 1 and figures)
    /// or SheaveModel::Wrapped (the rope over the top of a groove of radius r; planar rope only).
    SheaveModel sheaveModel = SheaveModel::Point;
    /// @throws std::invalid_argument naming the first parameter out of range or not finite.
    void validate() const;
};

/// The pendulum: rope anchored at the first sheave (Ground, origin), horizontal span a to the
/// deviation sheave (Ground, (a, 0, 0)), vertical span down to the payload, a Simbody free body
/// (quaternions) with the rope attached d above its centre of mass. Motion in the x-y plane, y up;
/// the rope is planar (plane normal z). Drawing (any SimTK::Visualizer): the payload as the cube of
/// its M and J (side sqrt(6 J / M)), the deviation sheave at radius r, the anchor, the rope coloured blue (slack) ... red
/// (2 M g, ReevingSubsystem::setDecorationForceScale).
class PendulumScene {
public:
    /// @param parameters the machine (Table 1 defaults), checked by PendulumParameters::validate.
    /// @param spans      options of both spans (mode counts, quasi-static modes, ...).
    /// @param planarRope true (default): planar spans in the x-y plane; false: spatial spans (same
    ///        physics for this in-plane motion, with out-of-plane modes and work).
    /// @param horizontalSpan if given, the options of the horizontal span a (span 0, between the two
    ///        Ground points) instead of spans: e.g. its transverse modes condensed
    ///        (TransverseDynamics::QuasiStatic) while the vertical span keeps its string vibration.
    /// @throws std::invalid_argument for bad parameters or span options.
    PendulumScene(const PendulumParameters& parameters, const SpanOptions& spans, bool planarRope = true,
                  const std::optional<SpanOptions>& horizontalSpan = std::nullopt);

    SimTK::MultibodySystem& system() { return *system_; }  ///< the scene's system (the scene owns it)
    const SimTK::MultibodySystem& system() const { return *system_; }  ///< the scene's system
    const SimTK::SimbodyMatterSubsystem& matter() const { return *matter_; }  ///< its matter subsystem
    /// The rope: rope 0, span 0 the horizontal one, span 1 the vertical one.
    const ReevingSubsystem& reeving() const { return *reeving_; }
    const SimTK::MobilizedBody::Free& payload() const { return *payload_; }  ///< the payload, a free body
    const PendulumParameters& parameters() const { return parameters_; }  ///< as given, validated

    /// Realizes the topology, starts from the straight hanging guess, moves the state to static
    /// equilibrium (relative residual <= 1e-9; its round-off floor grows with EA: 4e-10 at 100 x Table 1) and then sets the payload's velocity (vx, vy) [m/s].
    SimTK::State makeInitialState(double vx, double vy) const;

    // Observables at a state realized to Stage::Position (energy: Stage::Velocity).
    SimTK::Vec3 payloadPosition(const SimTK::State& s) const;  ///< centre of mass [m]
    double payloadAngle(const SimTK::State& s) const;          ///< rotation about z [rad]
    /// Axial force P = EA eps [N] of the vertical span at its payload end (not the tension
    /// T = P |dr/ds| that ReevingSubsystem::getTension returns).
    double axialForceAtPayload(const SimTK::State& s) const;
    double axialForceAtSheave(const SimTK::State& s) const;    ///< the same at the sheave end [N]
    double sheaveMaterialCoordinate(const SimTK::State& s) const;  ///< s at the deviation sheave [m]

private:
    PendulumParameters parameters_;
    std::unique_ptr<SimTK::MultibodySystem> system_;
    std::unique_ptr<SimTK::SimbodyMatterSubsystem> matter_;
    std::unique_ptr<SimTK::GeneralForceSubsystem> forces_;
    std::unique_ptr<SimTK::Force::Gravity> gravity_;
    std::unique_ptr<ReevingSubsystem> reeving_;
    std::unique_ptr<SimTK::MobilizedBody::Free> payload_;
};

}  // namespace SimbodyReeving
