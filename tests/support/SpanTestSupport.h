#pragma once
// Shared helpers of the span-element tests: random states, finite differences, a fixed-step RK4.

#include "SimbodyReeving/element/SpanModel.h"

#include <Eigen/Core>

#include <functional>
#include <random>

namespace SimbodyReeving::test {

/// A deformed, strained state of a span of unstretched length `length`: random end nodes (chord
/// within 50 degrees of the reference direction in 3D), stretch 1 +- 5 %, modal amplitudes of a few
/// percent of the length, random s1.
template <int Dim>
Eigen::VectorXd randomState(const SpanModel<Dim>& model, std::mt19937& rng, double length = 2.0);

/// Random velocities of order `scale` for every coordinate (material coordinates included).
template <int Dim>
Eigen::VectorXd randomVelocity(const SpanModel<Dim>& model, std::mt19937& rng, double scale = 1.0);

/// Central-difference gradient of f at x with step h.
Eigen::VectorXd centralGradient(const std::function<double(const Eigen::VectorXd&)>& f, const Eigen::VectorXd& x,
                                double h);

/// max |a - b| / max |b| (infinity-norm relative error).
double relativeError(const Eigen::VectorXd& a, const Eigen::VectorXd& b);

/// Classical fixed-step RK4 on y' = f(y).
void rk4Step(const std::function<Eigen::VectorXd(const Eigen::VectorXd&)>& f, Eigen::VectorXd& y, double h);

}  // namespace SimbodyReeving::test
