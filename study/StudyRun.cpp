#include "StudyRun.h"

#include "ChildProcess.h"

#include <CLI/CLI.hpp>

#include <algorithm>
#include <cstdio>
#include <iostream>
#include <sstream>
#include <thread>
#include <unistd.h>

namespace fs = std::filesystem;

namespace study {
namespace {

constexpr const char* kProgram = "reeving-study";

const char* kDescription =
    "reeving-study: a parameter study over a bundled scene. Each case of STUDY (a YAML file, or a\n"
    "folder with a study.yaml; see docs/studies.md) runs the scene's demo (reeving-pendulum,\n"
    "reeving-crane or reeving-elevator, next to this program) with the case's options; the metrics of\n"
    "its summary.json go to DIR/results.csv, one row per case. Every case's options are checked\n"
    "with the demo's --check before any case runs.\n"
    "Serial, or under MPI (mpirun -n N reeving-study STUDY): rank 0 hands out the cases one at a\n"
    "time to the other ranks and alone writes.\n";

const char* kFooter =
    "Outputs in DIR: results.csv (sorted by case id; results.csv.partial while the study runs, a row\n"
    "per finished case), summary.json (counts, failures, wall time, speedup) and figures/ (the study\n"
    "file's figures, with gnuplot).\n"
    "Exit status: 0 every case ok; 1 the study ran, some cases failed or passed their limits (see\n"
    "summary.json); 2 bad study file or command line (nothing run, nothing written); 130\n"
    "interrupted (SIGINT/SIGTERM: --resume continues).";

std::string clock(double seconds) {
    const long s = std::max(0L, std::lround(seconds));
    char buffer[32];
    if (s >= 3600)
        std::snprintf(buffer, sizeof buffer, "%ld:%02ld:%02ld", s / 3600, s / 60 % 60, s % 60);
    else
        std::snprintf(buffer, sizeof buffer, "%ld:%02ld", s / 60, s % 60);
    return buffer;
}

std::string joinArgs(const std::string& program, const std::vector<std::string>& args) {
    std::string s = program;
    for (const std::string& a : args) {
        const bool plain = a.find_first_of(" '\"\\$`") == std::string::npos;
        s += " " + (plain ? a : "'" + a + "'");
    }
    return s;
}

}  // namespace

int parseCommandLine(int argc, char** argv, CommandLine& cl, bool speak) {
    CLI::App app(kDescription, kProgram);
    app.set_help_flag("-h,--help", "this text");
    app.footer(kFooter);
    app.get_formatter()->column_width(27);
    std::string study;
    app.add_option("STUDY", study, "the study file (or a folder holding study.yaml)")->required();
    app.add_option("--out", cl.outDir, "output folder (default out/<the study's name>)")->type_name("DIR");
    app.add_flag("--dry-run", cl.dryRun, "check the study and list its cases with their command lines; run and write nothing");
    app.add_flag("--resume", cl.resume,
                 "continue the study in DIR: run only the cases that DIR/results.csv.partial\n"
                 "(or results.csv) does not have");
    app.add_flag("--quiet", cl.quiet, "no progress line");
    app.add_option("--demo-dir", cl.demoDir, "the folder of the demo programs (default: this program's folder)")
        ->type_name("DIR");
    try {
        app.parse(argc, argv);
    } catch (const CLI::CallForHelp&) {
        if (speak) std::cout << app.help();
        return kExitOk;
    } catch (const CLI::ParseError& e) {
        if (speak) std::cerr << kProgram << ": " << e.what() << "\nTry '" << kProgram << " --help'.\n";
        return kExitBadInput;
    }
    std::error_code ec;
    const fs::path path(study);
    cl.studyFile = fs::is_directory(path, ec) ? (path / "study.yaml").string() : study;
    if (cl.outDir.empty()) {
        const fs::path file(cl.studyFile);
        std::string name = file.filename() == "study.yaml" ? file.parent_path().filename().string() : file.stem().string();
        if (name.empty() || name == "." || name == "..") name = "study";
        cl.outDir = (fs::path("out") / name).string();
    }
    return -1;
}

StudyRun::StudyRun(CommandLine commandLine, int ranks, int workers)
    : commandLine_(std::move(commandLine)), ranks_(ranks), workers_(workers) {}

StudyRun::~StudyRun() = default;

int StudyRun::prepare(const std::string& studyText) {
    start_ = lastProgress_ = std::chrono::steady_clock::now();
    out_ = commandLine_.outDir;
    const fs::path partialFile = out_ / "results.csv.partial", finalFile = out_ / "results.csv";
    try {
        study_ = parseStudy(studyText, commandLine_.studyFile);
        cases_ = makeCases(study_);
        settings_.program = locateDemo(study_, commandLine_.demoDir);
        std::map<long, ResultRow> done;
        std::error_code ec;
        if (commandLine_.resume) {
            if (fs::exists(partialFile, ec))
                done = readResults(partialFile, study_, cases_);
            else if (fs::exists(finalFile, ec))
                done = readResults(finalFile, study_, cases_);
            else
                throw StudyError("--resume: " + out_.string() + " has no results.csv.partial or results.csv to continue");
        } else if (fs::exists(partialFile, ec)) {
            throw StudyError(partialFile.string() +
                             " exists: a study stopped there. --resume continues it; remove the file to start again");
        }
        for (auto& [id, row] : done) rows_.push_back(std::move(row));
        resumed_ = static_cast<long>(rows_.size());
        for (const Case& c : cases_)
            if (!done.count(c.id)) pending_.push_back(c.id);
        scratch_ = std::make_unique<ScratchFolder>();
        settings_.scratch = scratch_->path();
        std::vector<Case> toCheck;
        for (long id : pending_) toCheck.push_back(cases_[static_cast<std::size_t>(id)]);
        installStopHandlers();
        const int parallel = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
        checkCases(study_, toCheck, settings_, parallel);
    } catch (const StudyError& e) {
        std::cerr << kProgram << ": " << e.what() << "\n";
        return stopRequested() ? kExitInterrupted : kExitBadInput;
    } catch (const std::exception& e) {
        std::cerr << kProgram << ": " << e.what() << "\n";
        return kExitBadInput;
    }
    if (commandLine_.dryRun) {
        std::cout << kProgram << ": " << study_.file << ": scene " << study_.scene->name << " ("
                  << settings_.program << "), " << cases_.size() << " cases (" << gridSize(study_) << " grid point"
                  << (gridSize(study_) == 1 ? "" : "s") << " x " << sampleSize(study_) << " sample point"
                  << (sampleSize(study_) == 1 ? "" : "s") << ")";
        if (resumed_) std::cout << ", " << resumed_ << " done in " << out_.string();
        std::cout << "; every case passed " << study_.scene->program << " --check\n";
        for (long id : pending_) {
            const Case& c = cases_[static_cast<std::size_t>(id)];
            std::cout << "case " << id << ": " << describeCase(study_, c) << "\n    "
                      << joinArgs(study_.scene->program, demoArguments(study_, c, "CASE_DIR")) << "\n";
        }
        return kExitOk;
    }
    try {
        fs::create_directories(out_);
        std::error_code ec;
        if (!commandLine_.resume) {  // a finished study's outputs there are replaced at the end
            fs::remove(finalFile, ec);
            fs::remove(out_ / "summary.json", ec);
        }
        partial_ = std::make_unique<PartialResults>(partialFile, study_, rows_);
    } catch (const std::exception& e) {
        std::cerr << kProgram << ": --out '" << out_.string() << "': cannot write the results there: " << e.what()
                  << "\n";
        return kExitBadInput;
    }
    start_ = lastProgress_ = std::chrono::steady_clock::now();
    return -1;
}

void StudyRun::record(const ResultRow& row) {
    partial_->append(row);
    rows_.push_back(row);
    ++runNow_;
    caseWall_ += row.wallSeconds;
    if (row.status != "ok") ++failedNow_;
    progress(false);
}

void StudyRun::progress(bool last) {
    if (commandLine_.quiet) return;
    const auto now = std::chrono::steady_clock::now();
    const double elapsed = std::chrono::duration<double>(now - start_).count();
    const bool tty = isatty(STDERR_FILENO) != 0;
    const double every = tty ? 0.2 : 10.0;
    if (!last && std::chrono::duration<double>(now - lastProgress_).count() < every) return;
    lastProgress_ = now;
    long failed = 0;
    for (const ResultRow& r : rows_) failed += r.status != "ok";
    const long left = static_cast<long>(pending_.size()) - runNow_;
    std::ostringstream line;
    line << kProgram << ": " << rows_.size() << "/" << cases_.size() << " done, " << failed << " failed, elapsed "
         << clock(elapsed);
    if (left > 0 && runNow_ > 0) line << ", about " << clock(elapsed / static_cast<double>(runNow_) * static_cast<double>(left)) << " left";
    if (tty) {
        std::string text = line.str();
        text.resize(std::max<std::size_t>(text.size(), 72), ' ');
        std::cerr << "\r" << text << (last ? "\n" : "") << std::flush;
    } else {
        std::cerr << line.str() << "\n" << std::flush;
    }
    progressShown_ = true;
}

int StudyRun::finish(bool interrupted) {
    const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    if (progressShown_ || (!commandLine_.quiet && runNow_ > 0)) progress(true);
    if (interrupted) {
        std::cerr << kProgram << ": interrupted: " << rows_.size() << " of " << cases_.size() << " cases done, in "
                  << (out_ / "results.csv.partial").string() << " (--resume continues)\n";
        return kExitInterrupted;
    }
    RunInfo info;
    info.demo = settings_.program;
    info.wallSeconds = wall;
    info.casesRun = runNow_;
    info.caseWallSeconds = caseWall_;
    info.ranks = ranks_;
    info.workers = workers_;
    try {
        std::sort(rows_.begin(), rows_.end(), [](const ResultRow& a, const ResultRow& b) { return a.id < b.id; });
        writeResults(out_ / "results.csv", study_, rows_);
        partial_.reset();
        std::error_code ec;
        fs::remove(out_ / "results.csv.partial", ec);
        std::string note;
        std::vector<std::string> figures;
        try {
            figures = makeFigures(out_ / "figures", study_, rows_, note);
        } catch (const std::exception& e) {
            note = std::string("figures failed: ") + e.what();
        }
        if (!note.empty()) std::cerr << kProgram << ": " << note << "\n";
        writeSummary(out_ / "summary.json", study_, rows_, info, figures, note);
        std::cout << summaryText(study_, rows_, info);
        std::cout << kProgram << ": results in " << (out_ / "results.csv").string() << ", summary in "
                  << (out_ / "summary.json").string();
        if (!figures.empty()) std::cout << ", " << figures.size() << " figure(s) in " << (out_ / "figures").string();
        std::cout << "\n";
    } catch (const std::exception& e) {
        std::cerr << kProgram << ": writing the outputs failed: " << e.what() << "\n";
        return kExitCaseFailed;
    }
    for (const ResultRow& r : rows_)
        if (r.status != "ok") return kExitCaseFailed;
    return kExitOk;
}

int runSerial(StudyRun& run) {
    try {
        for (long id : run.pending()) {
            bool interrupted = false;
            const ResultRow row = runCase(run.study(), run.cases()[static_cast<std::size_t>(id)],
                                          run.settings(), interrupted);
            if (interrupted) return run.finish(true);
            run.record(row);
            if (stopRequested()) return run.finish(true);
        }
    } catch (const std::exception& e) {
        std::cerr << kProgram << ": " << e.what() << "\n";
        return kExitCaseFailed;
    }
    return run.finish(false);
}

}  // namespace study
