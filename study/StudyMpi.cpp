#include "StudyMpi.h"

#include "ChildProcess.h"
#include "StudyRun.h"

#include <mpi.h>

#include <cstdlib>
#include <iostream>
#include <memory>
#include <string>
#include <unistd.h>

namespace study {
namespace {

// Messages between rank 0 and the others.
constexpr int kTagResult = 1;       // worker -> 0: a result row as text ("" : ready for the first case)
constexpr int kTagWork = 2;         // 0 -> worker: a case id (long)
constexpr int kTagStop = 3;         // 0 -> worker: no more cases
constexpr int kTagInterrupted = 4;  // worker -> 0: its case was stopped by SIGINT/SIGTERM (not done)

// Waits for a message without spinning a core (MPI_Recv polls busily in most implementations, and
// the cases need the cores): probes every millisecond.
MPI_Status waitForMessage(int source, int tag) {
    MPI_Status status;
    for (;;) {
        int flag = 0;
        MPI_Iprobe(source, tag, MPI_COMM_WORLD, &flag, &status);
        if (flag) return status;
        sleepFor(0.001);
    }
}

std::string receiveText(const MPI_Status& probed) {
    int length = 0;
    MPI_Get_count(&probed, MPI_CHAR, &length);
    std::string text(static_cast<std::size_t>(length), '\0');
    MPI_Recv(text.data(), length, MPI_CHAR, probed.MPI_SOURCE, probed.MPI_TAG, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
    return text;
}

void sendText(const std::string& text, int destination, int tag) {
    MPI_Send(text.data(), static_cast<int>(text.size()), MPI_CHAR, destination, tag, MPI_COMM_WORLD);
}

// Broadcast from rank 0 (a non-blocking broadcast waited for by polling, see waitForMessage).
void broadcast(void* data, int count, MPI_Datatype type) {
    MPI_Request request;
    MPI_Ibcast(data, count, type, 0, MPI_COMM_WORLD, &request);
    for (;;) {
        int done = 0;
        MPI_Test(&request, &done, MPI_STATUS_IGNORE);
        if (done) return;
        sleepFor(0.001);
    }
}

int broadcastStatus(int status) {
    broadcast(&status, 1, MPI_INT);
    return status;
}

std::string broadcastText(std::string text) {
    long long length = static_cast<long long>(text.size());
    broadcast(&length, 1, MPI_LONG_LONG);
    text.resize(static_cast<std::size_t>(length));
    if (length > 0) broadcast(text.data(), static_cast<int>(length), MPI_CHAR);
    return text;
}

int master(StudyRun& run, int ranks) {
    const std::vector<long>& pending = run.pending();
    std::size_t next = 0;
    int active = ranks - 1;
    bool interrupted = false, writeFailed = false;
    const std::size_t parameters = parameterColumns(run.study()).size(), metrics = run.study().metrics.size();
    while (active > 0) {
        const MPI_Status probed = waitForMessage(MPI_ANY_SOURCE, MPI_ANY_TAG);
        const std::string text = receiveText(probed);
        if (probed.MPI_TAG == kTagInterrupted) interrupted = true;
        if (probed.MPI_TAG == kTagResult && !text.empty()) {
            ResultRow row;
            std::string why;
            if (!parseRow(text, parameters, metrics, row, why)) {
                std::cerr << "reeving-study: rank " << probed.MPI_SOURCE << " sent a row that is not one (" << why
                          << "): " << text << "\n";
                writeFailed = true;
            } else {
                try {
                    run.record(row);
                } catch (const std::exception& e) {
                    std::cerr << "reeving-study: " << e.what() << "\n";
                    writeFailed = true;
                }
            }
        }
        interrupted = interrupted || stopRequested();
        if (!interrupted && !writeFailed && next < pending.size()) {
            const long id = pending[next++];
            MPI_Send(&id, 1, MPI_LONG, probed.MPI_SOURCE, kTagWork, MPI_COMM_WORLD);
        } else {
            MPI_Send(nullptr, 0, MPI_CHAR, probed.MPI_SOURCE, kTagStop, MPI_COMM_WORLD);
            --active;
        }
    }
    if (writeFailed) return kExitCaseFailed;
    return run.finish(interrupted);
}

void worker(const CommandLine& commandLine, const std::string& text) {
    // The study as rank 0 read it; the demo next to this rank's own executable.
    const Study study = parseStudy(text, commandLine.studyFile);
    const std::vector<Case> cases = makeCases(study);
    std::unique_ptr<ScratchFolder> scratch;
    RunSettings settings;
    std::string setupError;
    try {
        settings.program = locateDemo(study, commandLine.demoDir);
        scratch = std::make_unique<ScratchFolder>();
        settings.scratch = scratch->path();
    } catch (const std::exception& e) {
        char host[256] = "?";
        gethostname(host, sizeof host - 1);
        setupError = std::string("on ") + host + ": " + e.what();
    }
    installStopHandlers();
    sendText("", 0, kTagResult);
    for (;;) {
        const MPI_Status probed = waitForMessage(0, MPI_ANY_TAG);
        if (probed.MPI_TAG == kTagStop) {
            MPI_Recv(nullptr, 0, MPI_CHAR, 0, kTagStop, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
            return;
        }
        long id = 0;
        MPI_Recv(&id, 1, MPI_LONG, 0, kTagWork, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
        const Case& c = cases.at(static_cast<std::size_t>(id));
        ResultRow row;
        bool interrupted = false;
        if (setupError.empty()) {
            row = runCase(study, c, settings, interrupted);
        } else {
            row.id = c.id;
            row.parameters = c.values;
            row.metrics.assign(study.metrics.size(), "");
            row.status = "failed";
            row.message = setupError;
        }
        if (interrupted)
            sendText("", 0, kTagInterrupted);
        else
            sendText(formatRow(row), 0, kTagResult);
    }
}

}  // namespace

bool launchedByMpi() {
    for (const char* variable : {"OMPI_COMM_WORLD_SIZE", "PMI_RANK", "PMI_SIZE", "PMIX_RANK"})
        if (std::getenv(variable)) return true;
    return false;
}

int runUnderMpi(int argc, char** argv) {
    MPI_Init(&argc, &argv);
    int rank = 0, ranks = 1;
    MPI_Comm_rank(MPI_COMM_WORLD, &rank);
    MPI_Comm_size(MPI_COMM_WORLD, &ranks);
    int status = -1;
    CommandLine commandLine;
    if (ranks == 1) {
        status = parseCommandLine(argc, argv, commandLine);
        if (status < 0) {
            try {
                const std::string text = readStudyText(commandLine.studyFile);
                StudyRun run(commandLine, 1, 1);
                status = run.prepare(text);
                if (status < 0) status = runSerial(run);
            } catch (const StudyError& e) {
                std::cerr << "reeving-study: " << e.what() << "\n";
                status = kExitBadInput;
            }
        }
        MPI_Finalize();
        return status;
    }
    // Every rank reads the command line (rank 0 alone says what is wrong with it); rank 0 alone reads
    // the study file and sends its text, so that no shared file system is needed.
    status = broadcastStatus(parseCommandLine(argc, argv, commandLine, rank == 0));
    if (status >= 0) {
        MPI_Finalize();
        return status;
    }
    std::string text;
    if (rank == 0) {
        try {
            text = readStudyText(commandLine.studyFile);
        } catch (const StudyError& e) {
            std::cerr << "reeving-study: " << e.what() << "\n";
            status = kExitBadInput;
        }
    }
    if (broadcastStatus(status) >= 0) {
        MPI_Finalize();
        return kExitBadInput;
    }
    std::unique_ptr<StudyRun> run;
    if (rank == 0) {
        run = std::make_unique<StudyRun>(commandLine, ranks, ranks - 1);
        status = run->prepare(text);
    }
    status = broadcastStatus(status);
    if (status >= 0) {
        MPI_Finalize();
        return status;
    }
    text = broadcastText(text);
    if (rank == 0) {
        status = master(*run, ranks);
    } else {
        try {
            worker(commandLine, text);
        } catch (const std::exception& e) {
            std::cerr << "reeving-study: rank " << rank << ": " << e.what() << "\n";
            MPI_Abort(MPI_COMM_WORLD, kExitCaseFailed);
        }
    }
    status = broadcastStatus(status);
    MPI_Finalize();
    return status;
}

}  // namespace study
