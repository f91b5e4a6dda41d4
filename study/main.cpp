// reeving-study: parameter studies over the bundled scenes, serial or under MPI. See --help and
// docs/studies.md.
#include "StudyRun.h"

#include <cstdlib>
#include <iostream>

#ifdef SIMBODYREEVING_STUDY_WITH_MPI
#include "StudyMpi.h"
#endif

int main(int argc, char** argv) {
    using namespace study;
#ifdef SIMBODYREEVING_STUDY_WITH_MPI
    if (launchedByMpi()) return runUnderMpi(argc, argv);
#else
    // Started by mpirun with several processes, a build without MPI would run the whole study in
    // each of them, all writing the same files.
    if (const char* size = std::getenv("OMPI_COMM_WORLD_SIZE") ? std::getenv("OMPI_COMM_WORLD_SIZE")
                                                                : std::getenv("PMI_SIZE")) {
        if (std::atoi(size) > 1) {
            const char* rank = std::getenv("OMPI_COMM_WORLD_RANK") ? std::getenv("OMPI_COMM_WORLD_RANK")
                                                                    : std::getenv("PMI_RANK");
            if (!rank || std::atoi(rank) == 0)
                std::cerr << "reeving-study: started as " << size
                          << " MPI processes, but built without MPI: configure with -DSIMBODYREEVING_STUDY_MPI=ON "
                             "(libopenmpi-dev), or run it alone\n";
            return kExitBadInput;
        }
    }
#endif
    CommandLine commandLine;
    const int status = parseCommandLine(argc, argv, commandLine);
    if (status >= 0) return status;
    std::string text;
    try {
        text = readStudyText(commandLine.studyFile);
    } catch (const StudyError& e) {
        std::cerr << "reeving-study: " << e.what() << "\n";
        return kExitBadInput;
    }
    StudyRun run(commandLine, 1, 1);
    const int prepared = run.prepare(text);
    if (prepared >= 0) return prepared;
    return runSerial(run);
}
