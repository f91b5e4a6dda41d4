#pragma once
// reeving-study under MPI: rank 0 reads the study, checks it, hands out case ids one at a time to
// the other ranks as they become free, collects their result rows and alone writes; the other
// ranks run the cases (the demo in a child process, as serially) and send back each row as text.

namespace study {

/// true if an MPI launcher started this process (mpirun/mpiexec: OMPI_COMM_WORLD_SIZE; PMI or
/// PMIx, as srun sets: PMI_RANK, PMI_SIZE, PMIX_RANK): MPI is initialized only then, so that the
/// program started alone runs serially without any MPI start-up.
bool launchedByMpi();

/// The whole program under MPI (MPI_Init to MPI_Finalize); one rank: the serial path. Returns the
/// exit status (the same on every rank).
int runUnderMpi(int argc, char** argv);

}  // namespace study
