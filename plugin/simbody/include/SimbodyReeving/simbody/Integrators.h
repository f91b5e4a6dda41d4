#pragma once
/// @file
/// Simbody integrators by name, so applications and benchmarks can swap them from the command line.

#include <Simbody.h>

#include <memory>
#include <string>
#include <vector>

namespace SimbodyReeving {

/// The names accepted by makeIntegrator, in a stable order:
/// rk-merson, rk3, rk-feldberg, cpodes, verlet, semi-explicit-euler2, explicit-euler.
const std::vector<std::string>& integratorNames();

/// Creates the Simbody integrator called `name` (see integratorNames) for `system`.
/// @throws std::invalid_argument for an unknown name (the message lists the known ones).
std::unique_ptr<SimTK::Integrator> makeIntegrator(const std::string& name, const SimTK::System& system);

}  // namespace SimbodyReeving
