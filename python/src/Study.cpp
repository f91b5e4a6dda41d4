#include "Study.h"

#include "Errors.h"

#include "ChildProcess.h"
#include "Results.h"
#include "StudyFile.h"
#include "StudyRun.h"

#include <pybind11/stl.h>

#include <csignal>
#include <filesystem>
#include <iostream>
#include <optional>
#include <regex>
#include <sstream>
#include <string>

namespace py = pybind11;
namespace fs = std::filesystem;

namespace simbody_reeving_python {
namespace {

// Redirects a C++ stream into a buffer for its lifetime.
class Capture {
public:
    explicit Capture(std::ostream& stream) : stream_(stream), old_(stream.rdbuf(buffer_.rdbuf())) {}
    Capture(const Capture&) = delete;
    Capture& operator=(const Capture&) = delete;
    ~Capture() { stream_.rdbuf(old_); }
    std::string text() const { return buffer_.str(); }

private:
    std::ostream& stream_;
    std::ostringstream buffer_;
    std::streambuf* old_;
};

// Python's SIGINT and SIGTERM handlers, put back when the study ends (the runner installs its own:
// a signal stops the study, its finished cases kept in results.csv.partial).
class SavedSignalHandlers {
public:
    SavedSignalHandlers() {
        sigaction(SIGINT, nullptr, &int_);
        sigaction(SIGTERM, nullptr, &term_);
    }
    SavedSignalHandlers(const SavedSignalHandlers&) = delete;
    SavedSignalHandlers& operator=(const SavedSignalHandlers&) = delete;
    ~SavedSignalHandlers() {
        sigaction(SIGINT, &int_, nullptr);
        sigaction(SIGTERM, &term_, nullptr);
    }

private:
    struct sigaction int_ {}, term_ {};
};

// "reeving-study: MESSAGE\n" -> "MESSAGE".
std::string message(std::string text) {
    while (!text.empty() && (text.back() == '\n' || text.back() == ' ')) text.pop_back();
    const std::string prefix = "reeving-study: ";
    if (text.rfind(prefix, 0) == 0) text.erase(0, prefix.size());
    return text;
}

// A results.csv cell as Python: integers (plain digits) as int, other numbers as float (the same
// double: the cells hold every digit), "" as None, the rest as str.
py::object cell(const std::string& text) {
    static const std::regex integer("-?[0-9]+");
    if (text.empty()) return py::none();
    if (std::regex_match(text, integer) && text.size() < 18) return py::int_(std::stoll(text));
    double v = 0;
    if (study::toFiniteNumber(text, v)) return py::float_(v);
    return py::str(text);
}

py::list runStudy(const py::object& studyArgument, const std::optional<std::string>& out, const std::string& demoDir,
                  bool quiet, bool resume) {
    std::string text, fileName;
    if (py::isinstance<py::dict>(studyArgument)) {
        // A dict is written as JSON, which YAML reads: numbers in Python's shortest round-trip form.
        text = py::str(py::module_::import("json").attr("dumps")(studyArgument, py::arg("indent") = 2));
        fileName = "<study dict>";
    } else {
        const std::string path = py::str(py::module_::import("os").attr("fspath")(studyArgument));
        std::error_code ec;
        fileName = fs::is_directory(path, ec) ? (fs::path(path) / "study.yaml").string() : path;
        text = study::readStudyText(fileName);
    }
    study::CommandLine cl;
    cl.studyFile = fileName;
    cl.demoDir = demoDir;
    cl.quiet = quiet;
    cl.resume = resume;
    std::optional<py::object> temporary;
    if (out) {
        cl.outDir = *out;
    } else {
        temporary = py::module_::import("tempfile").attr("TemporaryDirectory")(py::arg("prefix") = "simbody-reeving-study.");
        cl.outDir = py::str(temporary->attr("name"));
    }

    int status = -1;
    std::string errors;
    std::optional<study::StudyRun> run;
    std::map<long, study::ResultRow> rows;
    {
        SavedSignalHandlers saved;
        py::gil_scoped_release release;
        study::clearStopRequest();
        run.emplace(cl, 1, 1);
        {
            Capture err(std::cerr);
            status = run->prepare(text);
            errors = err.text();
        }
        if (status < 0) {
            if (quiet) {
                Capture outText(std::cout);
                Capture err(std::cerr);
                status = study::runSerial(*run);
            } else {
                status = study::runSerial(*run);
            }
        }
        if (status != study::kExitInterrupted && status != study::kExitBadInput && status != study::kExitOk + 0 &&
            status != study::kExitCaseFailed)
            status = study::kExitCaseFailed;
        if (status == study::kExitOk || status == study::kExitCaseFailed) {
            const fs::path results = fs::path(cl.outDir) / "results.csv";
            std::error_code ec;
            if (fs::exists(results, ec)) rows = study::readResults(results, run->study(), run->cases());
        }
    }
    if (status == study::kExitInterrupted || study::stopRequested()) {
        study::clearStopRequest();
        PyErr_SetNone(PyExc_KeyboardInterrupt);
        throw py::error_already_set();
    }
    if (status == study::kExitBadInput) throw study::StudyError(message(errors));
    if (rows.empty() && !run->cases().empty())
        throw std::runtime_error("the study wrote no results.csv in " + cl.outDir + (errors.empty() ? "" : ": " + message(errors)));

    const std::vector<std::string> columns = study::resultColumns(run->study());
    py::list list;
    for (const auto& [id, row] : rows) {
        py::dict d;
        std::size_t c = 0;
        d[py::str(columns[c++])] = py::int_(row.id);
        for (const std::string& v : row.parameters) d[py::str(columns[c++])] = cell(v);
        for (const std::string& v : row.metrics) d[py::str(columns[c++])] = cell(v);
        d[py::str(columns[c++])] = py::float_(row.wallSeconds);
        d[py::str(columns[c++])] = py::str(row.status);
        d[py::str(columns[c++])] = py::str(row.message);
        list.append(d);
    }
    if (temporary) temporary->attr("cleanup")();
    return list;
}

}  // namespace

void bindStudy(py::module_& m) {
    m.def("_run_study", &runStudy, py::arg("study"), py::arg("out"), py::arg("demo_dir"), py::arg("quiet"),
          py::arg("resume"));
    m.attr("_installed_demo_dir") = SIMBODYREEVING_PYTHON_INSTALLED_DEMO_DIR;
    m.attr("_build_demo_dir") = SIMBODYREEVING_PYTHON_DEMO_DIR;
}

}  // namespace simbody_reeving_python
