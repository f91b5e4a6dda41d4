#pragma once
// What the end-to-end study tests share: running a program with its output captured, scratch
// folders, reading results.csv.

#include "Results.h"

#include <gtest/gtest.h>

#include <algorithm>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <sys/wait.h>
#include <unistd.h>
#include <vector>

namespace study_test {

namespace fs = std::filesystem;

struct ProgramRun {
    int status = -1;  ///< the exit status (-1: did not exit normally)
    std::string out, err;
};

inline std::string readFile(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    std::ostringstream ss;
    ss << in.rdbuf();
    return ss.str();
}

/// This test process's folder under the system's temporary folder.
inline fs::path scratchRoot() {
    return fs::temp_directory_path() / ("simbodyreeving_study_tests_" + std::to_string(getpid()));
}

/// Removes scratchRoot() after the tests if they all passed (kept for a look otherwise).
class ScratchCleanup : public ::testing::Environment {
public:
    void TearDown() override {
        if (::testing::UnitTest::GetInstance()->Passed()) {
            std::error_code ignored;
            fs::remove_all(scratchRoot(), ignored);
        }
    }
};
inline ::testing::Environment* const scratchCleanup = ::testing::AddGlobalTestEnvironment(new ScratchCleanup);

/// A fresh folder for one test, under scratchRoot().
inline fs::path scratch(const std::string& name) {
    const fs::path dir = scratchRoot() / name;
    fs::remove_all(dir);
    fs::create_directories(dir);
    return dir;
}

/// Runs a shell command line (`cd`, quoting: the caller's) with stdout and stderr captured.
inline ProgramRun run(const std::string& commandLine, const fs::path& dir) {
    const fs::path out = dir / "run.out", err = dir / "run.err";
    const std::string cmd = commandLine + " > '" + out.string() + "' 2> '" + err.string() + "'";
    const int raw = std::system(cmd.c_str());
    ProgramRun r;
    r.status = raw != -1 && WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
    r.out = readFile(out);
    r.err = readFile(err);
    fs::remove(out);
    fs::remove(err);
    return r;
}

inline std::string quote(const fs::path& p) { return "'" + p.string() + "'"; }

inline void writeFile(const fs::path& path, const std::string& text) {
    std::ofstream out(path, std::ios::binary);
    out << text;
}

/// The lines of a file.
inline std::vector<std::string> lines(const fs::path& path) {
    std::ifstream in(path);
    std::vector<std::string> all;
    std::string line;
    while (std::getline(in, line)) all.push_back(line);
    return all;
}

/// A results.csv without its column `drop` (wall_seconds: the one column that differs between
/// runs), the fields of each row joined by '|'.
inline std::string withoutColumn(const fs::path& csv, const std::string& drop) {
    std::string text;
    std::size_t skip = static_cast<std::size_t>(-1);
    for (const std::string& line : lines(csv)) {
        std::vector<std::string> fields;
        EXPECT_TRUE(study::splitCsv(line, fields)) << line;
        if (skip == static_cast<std::size_t>(-1))
            skip = static_cast<std::size_t>(std::find(fields.begin(), fields.end(), drop) - fields.begin());
        for (std::size_t i = 0; i < fields.size(); ++i)
            if (i != skip) text += fields[i] + "|";
        text += "\n";
    }
    return text;
}

/// The rows of a results.csv as fields (the header first).
inline std::vector<std::vector<std::string>> csvRows(const fs::path& csv) {
    std::vector<std::vector<std::string>> rows;
    for (const std::string& line : lines(csv)) {
        std::vector<std::string> fields;
        EXPECT_TRUE(study::splitCsv(line, fields)) << line;
        rows.push_back(fields);
    }
    return rows;
}

}  // namespace study_test
