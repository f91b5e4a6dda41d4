#pragma once
// The study runner (study/, docs/studies.md) from Python: a study file or a dict, run by the same
// code as reeving-study (StudyRun: the demos as child processes, --check of every case first), the
// rows of its results.csv returned as a list of dicts.

#include <pybind11/pybind11.h>

namespace simbody_reeving_python {

void bindStudy(pybind11::module_& m);

}  // namespace simbody_reeving_python
