#pragma once
// A child process (fork and exec, POSIX) with its standard output and error in files, in a process
// group of its own, killed with the runner (Linux: the parent-death signal) and by time limits.

#include <filesystem>
#include <string>
#include <sys/types.h>
#include <vector>

namespace study {

class ChildProcess {
public:
    /// Starts `program` with `args` (argv[1...]), stdout and stderr to the given files (created).
    /// @throws std::runtime_error if it cannot be started (fork failed, program not executable).
    ChildProcess(const std::string& program, const std::vector<std::string>& args,
                 const std::filesystem::path& stdoutFile, const std::filesystem::path& stderrFile);
    ChildProcess(const ChildProcess&) = delete;
    ChildProcess& operator=(const ChildProcess&) = delete;
    /// Kills a child still running (SIGKILL to its group) and reaps it.
    ~ChildProcess();

    /// true once the child has ended (reaped); does not block.
    bool poll();
    /// Sends `signal` to the child's process group.
    void signalGroup(int signal);
    /// SIGTERM to the group, then SIGKILL if it has not ended after `graceSeconds`; waits for it.
    void terminate(double graceSeconds);

    bool ended() const { return ended_; }
    pid_t pid() const { return pid_; }
    /// The exit status (0..255), or -1 if a signal ended it.
    int exitStatus() const { return exitStatus_; }
    /// The signal that ended it, 0 if it exited.
    int termSignal() const { return termSignal_; }

private:
    pid_t pid_ = -1;
    bool ended_ = false;
    int exitStatus_ = -1, termSignal_ = 0;
};

/// The last `maxLines` non-empty lines of a text file, joined with " | " (at most maxChars, the
/// end kept); "" if it cannot be read.
std::string fileTail(const std::filesystem::path& file, int maxLines = 6, std::size_t maxChars = 600);

/// Installs SIGINT/SIGTERM handlers that set the flag read by stopRequested().
void installStopHandlers();
/// true once SIGINT or SIGTERM was received.
bool stopRequested();
/// Forgets a SIGINT or SIGTERM received (the Python module runs several studies in one process).
void clearStopRequest();

/// Sleeps for `seconds`.
void sleepFor(double seconds);

}  // namespace study
