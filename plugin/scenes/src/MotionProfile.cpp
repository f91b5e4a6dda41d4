#include "SimbodyReeving/scenes/MotionProfile.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

namespace SimbodyReeving {
namespace {

// The speed ramp r(u) = 6u^5 - 15u^4 + 10u^3 on [0, 1], its integral R(u) (R(1) = 1/2) and its
// derivative r'(u) = 30 u^2 (1 - u)^2.
double speedRamp(double u) { return u * u * u * (10.0 + u * (-15.0 + 6.0 * u)); }
double rampIntegral(double u) { return u * u * u * u * (2.5 + u * (-3.0 + u)); }
double rampSlope(double u) { return 30.0 * u * u * (1.0 - u) * (1.0 - u); }

}  // namespace

double SmoothMove::position(double t) const {
    const double tau = t - start;
    if (tau <= 0) return 0;
    if (tau >= duration) return distance;
    const double v = peakVelocity();
    if (tau < ramp) return v * ramp * rampIntegral(tau / ramp);
    const double left = duration - tau;
    if (left < ramp) return distance - v * ramp * rampIntegral(left / ramp);
    return v * (0.5 * ramp + (tau - ramp));
}

double SmoothMove::velocity(double t) const {
    const double tau = t - start;
    if (tau <= 0 || tau >= duration) return 0;
    const double v = peakVelocity();
    if (tau < ramp) return v * speedRamp(tau / ramp);
    const double left = duration - tau;
    if (left < ramp) return v * speedRamp(left / ramp);
    return v;
}

double SmoothMove::acceleration(double t) const {
    const double tau = t - start;
    if (tau <= 0 || tau >= duration) return 0;
    const double v = peakVelocity();
    if (tau < ramp) return v / ramp * rampSlope(tau / ramp);
    const double left = duration - tau;
    if (left < ramp) return -v / ramp * rampSlope(left / ramp);
    return 0;
}

double SmoothMove::peakAcceleration() const { return std::abs(peakVelocity()) / ramp * 15.0 / 8.0; }

void SmoothMove::validate() const {
    auto fail = [](const char* name, double v, const char* range) {
        std::ostringstream o;
        o << "SmoothMove: " << name << " = " << v << " must be finite and " << range;
        throw std::invalid_argument(o.str());
    };
    if (!std::isfinite(start)) fail("start", start, "any value");
    if (!std::isfinite(duration) || !(duration > 0)) fail("duration", duration, "> 0");
    if (!std::isfinite(ramp) || !(ramp > 0) || !(ramp <= 0.5 * duration)) fail("ramp", ramp, "in (0, duration / 2]");
    if (!std::isfinite(distance)) fail("distance", distance, "any value");
}

double MotionProfile::position(double t) const {
    double x = 0;
    for (const SmoothMove& m : moves) x += m.position(t);
    return x;
}
double MotionProfile::velocity(double t) const {
    double v = 0;
    for (const SmoothMove& m : moves) v += m.velocity(t);
    return v;
}
double MotionProfile::acceleration(double t) const {
    double a = 0;
    for (const SmoothMove& m : moves) a += m.acceleration(t);
    return a;
}
double MotionProfile::endTime() const {
    double t = 0;
    for (const SmoothMove& m : moves) t = std::max(t, m.end());
    return t;
}
void MotionProfile::validate() const {
    for (const SmoothMove& m : moves) m.validate();
}

namespace {

class ProfileMotion : public SimTK::Motion::Custom::Implementation {
public:
    ProfileMotion(MotionProfile profile, double scale, double offset)
        : profile_(std::move(profile)), scale_(scale), offset_(offset) {}
    Implementation* clone() const override { return new ProfileMotion(*this); }
    SimTK::Motion::Level getLevel(const SimTK::State&) const override { return SimTK::Motion::Position; }
    void calcPrescribedPosition(const SimTK::State& s, int nq, SimTK::Real* q) const override {
        if (nq == 1) q[0] = offset_ + scale_ * profile_.position(s.getTime());
    }
    void calcPrescribedPositionDot(const SimTK::State& s, int nq, SimTK::Real* qdot) const override {
        if (nq == 1) qdot[0] = scale_ * profile_.velocity(s.getTime());
    }
    void calcPrescribedPositionDotDot(const SimTK::State& s, int nq, SimTK::Real* qdotdot) const override {
        if (nq == 1) qdotdot[0] = scale_ * profile_.acceleration(s.getTime());
    }

private:
    MotionProfile profile_;
    double scale_, offset_;
};

}  // namespace

void prescribeProfile(SimTK::MobilizedBody& body, const MotionProfile& profile, double scale, double offset) {
    if (body.isEmptyHandle()) throw std::invalid_argument("prescribeProfile: empty body handle");
    if (!SimTK::MobilizedBody::Pin::isInstanceOf(body) && !SimTK::MobilizedBody::Slider::isInstanceOf(body))
        throw std::invalid_argument("prescribeProfile: the body must be a MobilizedBody::Pin or ::Slider");
    if (!std::isfinite(scale)) throw std::invalid_argument("prescribeProfile: scale must be finite");
    if (!std::isfinite(offset)) throw std::invalid_argument("prescribeProfile: offset must be finite");
    profile.validate();
    SimTK::Motion::Custom(body, new ProfileMotion(profile, scale, offset));
}

}  // namespace SimbodyReeving
