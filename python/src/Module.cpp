// simbody_reeving._core: the extension module under the simbody_reeving package (docs/python.md).
#include "Errors.h"
#include "Machine.h"
#include "Scenes.h"
#include "Simulation.h"
#include "Study.h"

#include <pybind11/pybind11.h>

PYBIND11_MODULE(_core, m) {
    m.doc() = "SimbodyReeving's bundled scenes, one's own machines, runs and parameter studies (see simbody_reeving and docs/python.md)";
    simbody_reeving_python::bindErrors(m);
    simbody_reeving_python::bindSimulation(m);
    simbody_reeving_python::bindScenes(m);
    simbody_reeving_python::bindStudy(m);
    simbody_reeving_python::bindMachine(m);
}
