#include "ChildProcess.h"

#include <cerrno>
#include <csignal>
#include <cstring>
#include <fcntl.h>
#include <fstream>
#include <stdexcept>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>
#ifdef __linux__
#include <sys/prctl.h>
#endif

namespace study {
namespace {

volatile std::sig_atomic_t stopFlag = 0;

extern "C" void onStopSignal(int) { stopFlag = 1; }

}  // namespace

void installStopHandlers() {
    struct sigaction sa {};
    sa.sa_handler = onStopSignal;
    sigemptyset(&sa.sa_mask);
    sigaction(SIGINT, &sa, nullptr);
    sigaction(SIGTERM, &sa, nullptr);
}

bool stopRequested() { return stopFlag != 0; }

void clearStopRequest() { stopFlag = 0; }

void sleepFor(double seconds) {
    timespec ts{};
    ts.tv_sec = static_cast<time_t>(seconds);
    ts.tv_nsec = static_cast<long>((seconds - static_cast<double>(ts.tv_sec)) * 1e9);
    while (nanosleep(&ts, &ts) != 0 && errno == EINTR && !stopRequested()) {
    }
}

ChildProcess::ChildProcess(const std::string& program, const std::vector<std::string>& args,
                           const std::filesystem::path& stdoutFile, const std::filesystem::path& stderrFile) {
    // Everything the child needs is prepared before fork: between fork and exec it only makes
    // async-signal-safe calls.
    std::vector<std::string> all{program};
    all.insert(all.end(), args.begin(), args.end());
    std::vector<char*> argv;
    for (std::string& a : all) argv.push_back(a.data());
    argv.push_back(nullptr);
    const std::string out = stdoutFile.string(), err = stderrFile.string();
    int pipeFds[2];  // reports a failed exec (errno) to the parent; closed by a successful exec
    if (pipe2(pipeFds, O_CLOEXEC) != 0) throw std::runtime_error(std::string("pipe: ") + std::strerror(errno));
    const pid_t parent = getpid();
    const pid_t pid = fork();
    if (pid < 0) {
        const int e = errno;
        close(pipeFds[0]);
        close(pipeFds[1]);
        throw std::runtime_error(std::string("fork: ") + std::strerror(e));
    }
    if (pid == 0) {
        setpgid(0, 0);
#ifdef __linux__
        prctl(PR_SET_PDEATHSIG, SIGKILL);  // the runner killed: its cases die with it
        if (getppid() != parent) _exit(127);
#endif
        struct sigaction sa {};
        sa.sa_handler = SIG_DFL;
        sigemptyset(&sa.sa_mask);
        sigaction(SIGINT, &sa, nullptr);
        sigaction(SIGTERM, &sa, nullptr);
        const int o = open(out.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
        const int e = open(err.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
        const int in = open("/dev/null", O_RDONLY);
        if (o < 0 || e < 0 || in < 0 || dup2(in, 0) < 0 || dup2(o, 1) < 0 || dup2(e, 2) < 0) {
            const int code = errno;
            ssize_t ignored = write(pipeFds[1], &code, sizeof code);
            (void)ignored;
            _exit(127);
        }
        execv(program.c_str(), argv.data());
        const int code = errno;
        ssize_t ignored = write(pipeFds[1], &code, sizeof code);
        (void)ignored;
        _exit(127);
    }
    pid_ = pid;
    setpgid(pid, pid);  // also from the parent: signalGroup may come before the child ran setpgid
    close(pipeFds[1]);
    int code = 0;
    ssize_t n;
    do n = read(pipeFds[0], &code, sizeof code);
    while (n < 0 && errno == EINTR);
    close(pipeFds[0]);
    if (n == static_cast<ssize_t>(sizeof code)) {
        int status;
        while (waitpid(pid_, &status, 0) < 0 && errno == EINTR) {
        }
        ended_ = true;
        throw std::runtime_error("cannot run " + program + ": " + std::strerror(code));
    }
}

ChildProcess::~ChildProcess() {
    if (!ended_ && pid_ > 0) {
        signalGroup(SIGKILL);
        int status;
        while (waitpid(pid_, &status, 0) < 0 && errno == EINTR) {
        }
    }
}

bool ChildProcess::poll() {
    if (ended_) return true;
    int status = 0;
    const pid_t r = waitpid(pid_, &status, WNOHANG);
    if (r == 0 || (r < 0 && errno == EINTR)) return false;
    ended_ = true;
    if (r < 0) return true;  // not ours any more (cannot happen): treated as ended, status -1
    if (WIFEXITED(status)) {
        exitStatus_ = WEXITSTATUS(status);
    } else if (WIFSIGNALED(status)) {
        termSignal_ = WTERMSIG(status);
    }
    return true;
}

void ChildProcess::signalGroup(int signal) {
    if (pid_ > 0 && !ended_) {
        if (kill(-pid_, signal) != 0) kill(pid_, signal);
    }
}

void ChildProcess::terminate(double graceSeconds) {
    if (poll()) return;
    signalGroup(SIGTERM);
    for (double waited = 0; waited < graceSeconds; waited += 0.005) {
        if (poll()) return;
        sleepFor(0.005);
    }
    signalGroup(SIGKILL);
    int status = 0;
    while (waitpid(pid_, &status, 0) < 0 && errno == EINTR) {
    }
    ended_ = true;
    termSignal_ = WIFSIGNALED(status) ? WTERMSIG(status) : 0;
    exitStatus_ = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

std::string fileTail(const std::filesystem::path& file, int maxLines, std::size_t maxChars) {
    std::ifstream in(file);
    if (!in) return "";
    std::vector<std::string> lines;
    std::string line;
    while (std::getline(in, line)) {
        while (!line.empty() && (line.back() == '\r' || line.back() == ' ')) line.pop_back();
        // A progress line rewritten with \r: its last state.
        const auto cr = line.rfind('\r');
        if (cr != std::string::npos) line = line.substr(cr + 1);
        const auto first = line.find_first_not_of(" \t");
        if (first != std::string::npos && line.substr(first) != "^") lines.push_back(line.substr(first));
    }
    std::string tail;
    const auto keep = static_cast<std::size_t>(maxLines);
    const std::size_t first = lines.size() > keep ? lines.size() - keep : 0;
    for (std::size_t i = first; i < lines.size(); ++i) tail += (tail.empty() ? "" : " | ") + lines[i];
    if (tail.size() > maxChars) tail = "..." + tail.substr(tail.size() - maxChars);
    return tail;
}

}  // namespace study
