#pragma once
// One's own machine from Python: a System owning a SimTK::MultibodySystem with its matter,
// general force and reeving subsystems and one Force::Gravity; rigid bodies on the mobilizers the
// bundled scenes use; rope specs over the node kinds (RopeAnchor, DeviationSheave, WinchDrum,
// TurningSheave, TractionSheave); add_rope's typed handles with the queries of their kind; runs
// through the scenes' Simulation.

#include <pybind11/pybind11.h>

namespace simbody_reeving_python {

void bindMachine(pybind11::module_& m);

}  // namespace simbody_reeving_python
