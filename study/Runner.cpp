#include "Runner.h"

#include "ChildProcess.h"

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <map>
#include <memory>
#include <sstream>
#include <stdexcept>
#include <unistd.h>

namespace fs = std::filesystem;

namespace study {
namespace {

using Clock = std::chrono::steady_clock;

constexpr int kUsageStatus = 2;  // the demos' exit status for a bad command line
constexpr int kLate = -1000;     // a --check that did not end (negative statuses: -signal)

double secondsSince(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

// The demo's stderr without CLI11's pointer to --help.
std::string demoMessage(const fs::path& stderrFile) {
    std::ifstream in(stderrFile);
    std::string line, text;
    while (std::getline(in, line)) {
        if (line.rfind("Try '", 0) == 0) continue;
        while (!line.empty() && (line.back() == '\r' || line.back() == ' ')) line.pop_back();
        const auto cr = line.rfind('\r');
        if (cr != std::string::npos) line = line.substr(cr + 1);
        if (!line.empty()) text += (text.empty() ? "" : " | ") + line;
    }
    if (text.size() > 600) text = "..." + text.substr(text.size() - 600);
    return text;
}

std::string signalText(int signal) {
    const char* name = strsignal(signal);
    return "killed by signal " + std::to_string(signal) + (name ? std::string(" (") + name + ")" : std::string());
}

bool isWordChar(char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '_'; }

// `needle` in `text` as a whole word (not inside a longer option name).
bool containsWord(const std::string& text, const std::string& needle) {
    for (std::size_t at = text.find(needle); at != std::string::npos; at = text.find(needle, at + 1)) {
        const bool before = at == 0 || !isWordChar(text[at - 1]) || needle.front() == '-' || needle.front() == '\'';
        const std::size_t end = at + needle.size();
        const bool after = end >= text.size() || !isWordChar(text[end]) || needle.back() == '=';
        if (before && after) return true;
    }
    return false;
}

// "car-position" -> "carPosition" (the scenes' parameter names).
std::string camelCase(const std::string& name) {
    std::string out;
    bool up = false;
    for (char c : name) {
        if (c == '-') {
            up = true;
            continue;
        }
        out += up ? static_cast<char>(std::toupper(static_cast<unsigned char>(c))) : c;
        up = false;
    }
    return out;
}

bool mentions(const std::string& message, const std::string& parameter) {
    if (parameter.rfind("set.", 0) == 0) {
        const std::string key = parameter.substr(4);
        return message.find("'" + key + "=") != std::string::npos || message.find("--set=" + key + "=") != std::string::npos;
    }
    if (containsWord(message, "--" + parameter)) return true;
    const std::string camel = camelCase(parameter);
    return camel != parameter && containsWord(message, camel);
}

struct Located {
    Place place;      // of the value
    std::string parameter;
    Place namePlace;  // of the parameter's name
};

// The place in the study file of the parameter a demo's message names: a varied parameter's value
// of this case, a fixed parameter's value, a sampled parameter's name; else the vary: or fixed: key.
Located locate(const Study& study, const Case& c, const std::string& message) {
    for (const FixedParameter& f : study.fixed)
        if (mentions(message, f.name)) return {f.place, f.name, f.namePlace};
    for (std::size_t k = 0; k < study.vary.size(); ++k) {
        const VariedParameter& v = study.vary[k];
        if (!mentions(message, v.name)) continue;
        const auto it = std::find(v.values.begin(), v.values.end(), c.values[k]);
        const auto index = static_cast<std::size_t>(it - v.values.begin());
        return {index < v.valuePlaces.size() ? v.valuePlaces[index] : v.place, v.name, v.place};
    }
    if (study.sample)
        for (const SampledParameter& p : study.sample->parameters)
            if (mentions(message, p.name)) return {p.place, p.name, p.place};
    if (study.varyPlace.line) return {study.varyPlace, "", study.varyPlace};
    if (study.fixedPlace.line) return {study.fixedPlace, "", study.fixedPlace};
    return {study.scenePlace, "", study.scenePlace};
}

fs::path caseFolder(const RunSettings& settings, const std::string& kind, long id) {
    return settings.scratch / (kind + "-" + std::to_string(id));
}

}  // namespace

ScratchFolder::ScratchFolder() {
    const char* tmp = std::getenv("TMPDIR");
    std::string pattern = std::string(tmp && *tmp ? tmp : "/tmp") + "/reeving-study.XXXXXX";
    if (!mkdtemp(pattern.data()))
        throw std::runtime_error("cannot create a scratch folder " + pattern + ": " + std::strerror(errno));
    path_ = pattern;
}

ScratchFolder::~ScratchFolder() {
    std::error_code ignored;
    fs::remove_all(path_, ignored);
}

std::string locateDemo(const Study& study, const std::string& demoDir) {
    fs::path dir = demoDir;
    if (dir.empty()) {
        std::error_code ec;
        dir = fs::read_symlink("/proc/self/exe", ec).parent_path();
    }
    const fs::path program = dir / study.scene->program;
    if (access(program.c_str(), X_OK) != 0)
        throw StudyError(placed(study.file, study.scenePlace,
                                "scene " + study.scene->name + ": its demo " + program.string() +
                                    " is not there (build the target " + study.scene->program +
                                    ", or give its folder with --demo-dir)"));
    return program.string();
}

ResultRow runCase(const Study& study, const Case& c, const RunSettings& settings, bool& interrupted) {
    interrupted = false;
    ResultRow row;
    row.id = c.id;
    row.parameters = c.values;
    row.metrics.assign(study.metrics.size(), "");
    const fs::path dir = caseFolder(settings, "case", c.id), out = dir / "out";
    std::error_code ec;
    fs::remove_all(dir, ec);
    fs::create_directories(dir, ec);
    const auto start = Clock::now();
    bool timedOut = false;
    int exitStatus = -1, termSignal = 0;
    try {
        ChildProcess child(settings.program, demoArguments(study, c, out.string()), dir / "stdout.txt",
                           dir / "stderr.txt");
        // Short polls first: most cases of a study take well under a second.
        for (double pause = 0.0005; !child.poll(); pause = std::min(2 * pause, 0.005)) {
            if (stopRequested()) {
                child.terminate(settings.terminateGrace);
                interrupted = true;
                fs::remove_all(dir, ec);
                return {};
            }
            if (study.limits.wallSeconds > 0 && secondsSince(start) > study.limits.wallSeconds) {
                child.terminate(settings.terminateGrace);
                timedOut = true;
                break;
            }
            sleepFor(pause);
        }
        exitStatus = child.exitStatus();
        termSignal = child.termSignal();
    } catch (const std::exception& e) {
        row.wallSeconds = secondsSince(start);
        row.status = "failed";
        row.message = e.what();
        fs::remove_all(dir, ec);
        return row;
    }
    row.wallSeconds = secondsSince(start);
    const std::string tail = demoMessage(dir / "stderr.txt");
    if (timedOut) {
        row.status = "timeout";
        row.message = "passed the wall-clock limit of " + numberText(study.limits.wallSeconds) + " s: stopped";
    } else if (termSignal != 0) {
        row.status = "failed";
        row.message = signalText(termSignal) + (tail.empty() ? "" : ": " + tail);
    } else if (exitStatus != 0) {
        row.status = "failed";
        row.message = "exit status " + std::to_string(exitStatus) + (tail.empty() ? "" : ": " + tail);
    } else {
        row.status = "ok";
    }
    // The metrics of a summary.json, if the demo wrote one (the crane's rope-limit exit does).
    if (!timedOut && fs::exists(out / "summary.json")) {
        try {
            std::ifstream in(out / "summary.json");
            const nlohmann::json summary = nlohmann::json::parse(in);
            for (std::size_t k = 0; k < study.metrics.size(); ++k) {
                std::string why;
                if (!metricValue(summary, study.metrics[k].path, row.metrics[k], why) && row.status == "ok") {
                    row.status = "failed";
                    row.message = why;
                }
            }
        } catch (const std::exception& e) {
            if (row.status == "ok") {
                row.status = "failed";
                row.message = std::string("summary.json unreadable: ") + e.what();
            }
        }
    } else if (row.status == "ok") {
        row.status = "failed";
        row.message = "exit status 0 but no summary.json" + (tail.empty() ? "" : ": " + tail);
    }
    fs::remove_all(dir, ec);
    return row;
}

void checkCases(const Study& study, const std::vector<Case>& cases, const RunSettings& settings, int parallel) {
    struct Running {
        std::size_t index;
        std::unique_ptr<ChildProcess> child;
        Clock::time_point start;
    };
    const double checkLimit = 120.0;  // [s] a --check builds scenes only: far less
    std::vector<Running> running;
    std::map<std::size_t, std::pair<int, std::string>> rejected;  // index -> (exit status, message)
    std::size_t next = 0;
    parallel = std::max(1, parallel);
    while ((next < cases.size() && rejected.empty()) || !running.empty()) {
        if (stopRequested()) throw StudyError("interrupted while checking the cases");
        while (next < cases.size() && rejected.empty() && static_cast<int>(running.size()) < parallel) {
            const Case& c = cases[next];
            const fs::path dir = caseFolder(settings, "check", c.id);
            std::error_code ec;
            fs::create_directories(dir, ec);
            std::vector<std::string> args = demoArguments(study, c, (dir / "out").string());
            args.push_back("--check");
            try {
                running.push_back({next, std::make_unique<ChildProcess>(settings.program, args, dir / "stdout.txt",
                                                                        dir / "stderr.txt"),
                                   Clock::now()});
            } catch (const std::exception& e) {
                throw StudyError(placed(study.file, study.scenePlace, e.what()));
            }
            ++next;
        }
        bool progressed = false;
        for (std::size_t k = 0; k < running.size();) {
            Running& r = running[k];
            const bool late = secondsSince(r.start) > checkLimit;
            if (!r.child->poll() && !late) {
                ++k;
                continue;
            }
            if (late) r.child->terminate(1.0);
            const Case& c = cases[r.index];
            const fs::path dir = caseFolder(settings, "check", c.id);
            if (late) {
                rejected[r.index] = {kLate, "its --check did not finish in " + numberText(checkLimit) + " s"};
            } else if (r.child->exitStatus() != 0) {
                const int status = r.child->termSignal() ? -r.child->termSignal() : r.child->exitStatus();
                rejected[r.index] = {status, demoMessage(dir / "stderr.txt")};
            }
            std::error_code ec;
            fs::remove_all(dir, ec);
            running.erase(running.begin() + static_cast<long>(k));
            progressed = true;
        }
        if (!progressed) sleepFor(0.001);
    }
    if (rejected.empty()) return;
    const auto& [index, failure] = *rejected.begin();
    const Case& c = cases[index];
    const int status = failure.first;
    std::string message = failure.second;
    if (message.rfind(study.scene->program + ": ", 0) == 0) message.erase(0, study.scene->program.size() + 2);
    const Located at = locate(study, c, failure.second);
    const std::string& program = study.scene->program;
    std::string text;
    Place place = at.place;
    if (status == kUsageStatus && message.find("not expected") != std::string::npos && !at.parameter.empty()) {
        place = at.namePlace;
        text = "unknown parameter '" + at.parameter + "' for scene " + study.scene->name + " (" + program + ": " +
               message + "; see " + program + " --help)";
    } else if (status == kUsageStatus && at.parameter == "scenario" && message.find("must be one of") != std::string::npos) {
        std::string value;
        for (const FixedParameter& f : study.fixed)
            if (f.name == "scenario") value = f.value;
        for (std::size_t k = 0; k < study.vary.size(); ++k)
            if (study.vary[k].name == "scenario") value = c.values[k];
        text = "unknown scenario '" + value + "' for scene " + study.scene->name + " (" + program + ": " + message + ")";
    } else if (status == kUsageStatus) {
        text = "case " + std::to_string(c.id) + " (" + describeCase(study, c) + ") is rejected by " + program + ": " +
               message;
    } else {
        const std::string how = status == kLate ? std::string()
                                : status < 0    ? program + " --check was " + signalText(-status) + ": "
                                                : program + " --check ended with exit status " + std::to_string(status) + ": ";
        text = "case " + std::to_string(c.id) + " (" + describeCase(study, c) + "): " + how + message;
    }
    throw StudyError(placed(study.file, place, text));
}

}  // namespace study
