#pragma once
// SIGINT / SIGTERM handling shared by the bundled demos: the handlers only set a flag, which the
// simulation loops check at every report; an interrupted demo writes nothing and exits 130.

namespace demo_common {

/// Installs the SIGINT and SIGTERM handlers that set the flag read by interrupted().
void installInterruptHandlers();

/// true once SIGINT or SIGTERM was received (async-signal-safe flag, readable from any thread).
bool interrupted();

/// The exit status of an interrupted demo (128 + SIGINT).
constexpr int kInterruptedExitStatus = 130;

}  // namespace demo_common
