#include "Errors.h"

#include "StudyFile.h"

#include <chrono>
#include <stdexcept>

namespace py = pybind11;

namespace simbody_reeving_python {

void bindErrors(py::module_& m) {
    // A bad study (file, dict, or a case the demo's --check rejects): a ValueError subclass, so
    // `except ValueError` catches every bad input.
    static py::exception<study::StudyError> studyError(m, "StudyError", PyExc_ValueError);
    py::register_exception_translator([](std::exception_ptr p) {
        try {
            if (p) std::rethrow_exception(p);
        } catch (const study::StudyError& e) {
            studyError(e.what());
        } catch (const std::invalid_argument& e) {
            PyErr_SetString(PyExc_ValueError, e.what());
        } catch (const std::out_of_range& e) {
            PyErr_SetString(PyExc_IndexError, e.what());
        }
        // Anything else goes on to pybind11's own translators: std::exception -> RuntimeError.
    });
}

bool InterruptPoll::operator()() {
    using Clock = std::chrono::steady_clock;
    const double now = std::chrono::duration<double>(Clock::now().time_since_epoch()).count();
    if (last_ >= 0 && now - last_ < 0.02) return false;
    last_ = now;
    py::gil_scoped_acquire gil;
    return PyErr_CheckSignals() != 0;
}

void require(bool ok, const std::string& what) {
    if (!ok) throw std::invalid_argument(what);
}

}  // namespace simbody_reeving_python
