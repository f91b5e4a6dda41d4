#pragma once
// Errors crossing into Python: C++ exceptions become Python exceptions with the C++ message
// (std::invalid_argument: ValueError; study::StudyError: simbody_reeving.StudyError, a ValueError;
// any other std::exception: RuntimeError), and a run polls Python's signal handlers so that
// Ctrl-C (KeyboardInterrupt) ends it.

#include <pybind11/pybind11.h>

#include <string>

namespace simbody_reeving_python {

/// Registers the exception translators and simbody_reeving.StudyError in `m`.
void bindErrors(pybind11::module_& m);

/// Called without the GIL (inside a py::gil_scoped_release) between reports: takes the GIL and runs
/// Python's pending signal handlers. Returns true if one raised (KeyboardInterrupt for SIGINT); the
/// Python error is then set, and the caller stops its run, leaves the released region and throws
/// pybind11::error_already_set. Polls at most every 20 ms of wall time (a cheap clock read between).
class InterruptPoll {
public:
    bool operator()();

private:
    double last_ = -1;
};

/// Throws std::invalid_argument(what) unless `ok`.
void require(bool ok, const std::string& what);

}  // namespace simbody_reeving_python
