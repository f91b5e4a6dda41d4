#include "DemoOutput.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <stdexcept>
#include <system_error>

namespace fs = std::filesystem;

namespace demo_common {

bool prepareOutputFolder(const std::string& program, const std::string& dir) {
    const fs::path out(dir);
    std::error_code ec;
    fs::create_directories(out, ec);
    if (ec || !fs::is_directory(out)) {
        std::cerr << program << ": --out '" << dir << "': cannot create the output folder"
                  << (ec ? ": " + ec.message() : std::string(": it is not a folder")) << "\n";
        return false;
    }
    const fs::path probe = out / ("." + program + "-write-test");
    const bool writable = static_cast<bool>(std::ofstream(probe));
    fs::remove(probe, ec);
    if (!writable) {
        std::cerr << program << ": --out '" << dir << "': the output folder is not writable\n";
        return false;
    }
    return true;
}

OutputFile::OutputFile(fs::path path) : path_(std::move(path)), partial_(path_.string() + ".partial"), out_(partial_) {
    if (!out_) throw std::runtime_error("cannot write " + partial_.string());
}

OutputFile::~OutputFile() {
    if (committed_) return;
    out_.close();
    std::error_code ec;
    fs::remove(partial_, ec);
}

void OutputFile::commit() {
    out_.close();
    if (!out_) throw std::runtime_error("cannot write " + partial_.string() + " (disk full?)");
    fs::rename(partial_, path_);
    committed_ = true;
}

Json jsonNumber(double v) {
    if (!std::isfinite(v)) return nullptr;
    char text[32];
    std::snprintf(text, sizeof text, "%.12g", v);
    // nlohmann::json prints a double in its shortest round-trip form: the 12 digits, no more.
    return std::strtod(text, nullptr);
}

void writeJson(std::ostream& out, const Json& json) { out << json.dump(2) << '\n'; }

}  // namespace demo_common
