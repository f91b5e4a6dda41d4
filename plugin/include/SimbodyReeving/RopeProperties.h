#pragma once
/// @file
/// Cross-section properties of a wire rope, in SI units.

namespace SimbodyReeving {

/// Mechanical properties of a wire rope per unit unstretched length (SI units).
struct RopeProperties {
    /// rhoA: mass per unit unstretched length [kg/m]; finite, > 0.
    double massPerLength = 0.0;
    /// EA: axial stiffness [N]; finite, > 0. Axial force P = EA * epsilon (Green strain).
    double axialStiffness = 0.0;
    /// EI: bending stiffness [N m^2]; finite, >= 0. EI = 0 skips the bending term entirely.
    double bendingStiffness = 0.0;
};

/// Checks the ranges documented on RopeProperties.
/// @throws std::invalid_argument naming the offending parameter and its value.
void validate(const RopeProperties& properties);

}  // namespace SimbodyReeving
