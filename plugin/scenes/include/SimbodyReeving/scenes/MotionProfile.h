#pragma once
/// @file
/// Smooth rest-to-rest motion profiles (a trolley's traverse, a hoist's lift) and a Simbody
/// Motion that prescribes one on a single-mobility body.

#include <Simbody.h>

#include <vector>

namespace SimbodyReeving {

/// One rest-to-rest move of a coordinate: `distance` covered between `start` and
/// `start + duration` with a smooth speed profile: the speed rises from 0 to the peak speed
/// during `ramp`, holds, and falls back to 0 during the last `ramp`:
///     v(t) = v_peak r(tau / ramp) while accelerating (tau = t - start), v_peak while holding,
///     r(u) = 6 u^5 - 15 u^4 + 10 u^3  (0 -> 1, r' and r'' zero at both ends),
///     v_peak = distance / (duration - ramp).
/// Position, speed and acceleration are continuous everywhere and the acceleration's derivative
/// (jerk) too: velocity and acceleration are zero at both ends of the move. With
/// ramp = duration / 2 there is no hold phase (a pure S-curve of peak speed 2 distance / duration).
/// Units follow the coordinate: [m] and [m/s] for a translation, [rad] and [rad/s] for an angle.
struct SmoothMove {
    double start = 0;     ///< time the move starts [s], finite
    double duration = 1;  ///< [s], finite, > 0
    double ramp = 0.5;    ///< acceleration (and deceleration) time [s], in (0, duration / 2]
    double distance = 0;  ///< displacement over the move (signed), finite

    /// Displacement since the start of the move at time t: 0 before it, `distance` after it.
    double position(double t) const;
    /// d position / dt at time t.
    double velocity(double t) const;
    /// d^2 position / dt^2 at time t.
    double acceleration(double t) const;
    /// Speed of the hold phase, distance / (duration - ramp) (signed).
    double peakVelocity() const { return distance / (duration - ramp); }
    /// Largest |acceleration|: |v_peak| / ramp * 15/8.
    double peakAcceleration() const;
    double end() const { return start + duration; }  ///< time the move ends [s]
    /// @throws std::invalid_argument naming the field out of range or not finite.
    void validate() const;
};

/// The sum of any number of SmoothMoves (usually one after the other): a coordinate's displacement
/// from its initial value as a function of time. Empty: always 0.
struct MotionProfile {
    std::vector<SmoothMove> moves;  ///< the moves, summed (they may overlap)

    double position(double t) const;      ///< sum of the moves' positions
    double velocity(double t) const;      ///< sum of the moves' velocities
    double acceleration(double t) const;  ///< sum of the moves' accelerations
    /// Time the last move ends [s] (0 when empty).
    double endTime() const;
    /// @throws std::invalid_argument if a move is invalid (SmoothMove::validate).
    void validate() const;
};

/// Prescribes q(t) = offset + scale * profile.position(t) on `body`, a MobilizedBody::Slider (q in
/// [m]) or MobilizedBody::Pin (q in [rad]), at position level with
/// the profile's exact first and second derivatives (Motion::Position). The body adopts the
/// Motion (it must have none yet); Simbody then computes the generalized force that enforces it
/// (MobilizedBody::getOneTau, SimbodyMatterSubsystem::calcMotionPower).
/// @param body the Slider or Pin to drive; it must have no Motion yet.
/// @param profile the moves, in the profile's units (e.g. [m] of hook lift); valid (MotionProfile::validate).
/// @param scale units of q per unit of the profile (e.g. -n / R [rad/m] turns a hook lift into a
///        drum angle); finite.
/// @param offset q at zero profile; finite.
/// @throws std::invalid_argument if body is not a Slider or Pin, or profile, scale or offset is bad.
void prescribeProfile(SimTK::MobilizedBody& body, const MotionProfile& profile, double scale, double offset = 0);

}  // namespace SimbodyReeving
