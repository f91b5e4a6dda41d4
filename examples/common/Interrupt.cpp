#include "Interrupt.h"

#include <atomic>
#include <csignal>

namespace demo_common {
namespace {

std::atomic<bool> gInterrupted{false};
extern "C" void onInterrupt(int) { gInterrupted = true; }

}  // namespace

void installInterruptHandlers() {
    std::signal(SIGINT, onInterrupt);
    std::signal(SIGTERM, onInterrupt);
}

bool interrupted() { return gInterrupted; }

}  // namespace demo_common
