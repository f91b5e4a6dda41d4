#pragma once
// The bundled scenes (plugin/scenes) from Python: their parameters, the scenes with their
// observables, the rope queries that apply to every rope (forces along a span, energies), and the
// runs of the demos (run_pendulum: examples/pendulum/main.cpp's runCase).

#include <pybind11/pybind11.h>

namespace simbody_reeving_python {

void bindScenes(pybind11::module_& m);

}  // namespace simbody_reeving_python
