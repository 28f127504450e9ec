// The registry of named temporary files and the signal handler that removes them
// (temporary_files.h).
//
// The handler may run on any thread, at any moment, so it only reads atomics and calls
// unlink(), sigaction() and raise(), all async-signal-safe. Paths live in heap strings owned
// by their slot. A path is freed when its slot is released, except once cleaning has begun:
// the handler may then be reading it, so it is leaked (the process is about to end anyway).

#include "core/temporary_files.h"

#include <signal.h>
#include <unistd.h>

#include <array>
#include <atomic>
#include <cstdlib>
#include <cstring>

namespace plantarch::io {

namespace {

constexpr std::size_t kSlots = 4096;
std::array<std::atomic<char*>, kSlots> slots{};
std::atomic<bool> cleaning{false};

void removeAndReraise(int signal) {
    cleaning.store(true);
    for (std::atomic<char*>& slot : slots)
        if (const char* path = slot.load()) ::unlink(path);
    // SA_RESETHAND put the default action back; the signal is blocked while this handler
    // runs and is delivered on return, ending the process as it would have without us.
    ::raise(signal);
}

}  // namespace

int registerTemporary(const char* path) noexcept {
    char* copy = ::strdup(path);
    if (!copy) return -1;
    for (std::size_t i = 0; i < kSlots; ++i) {
        char* expected = nullptr;
        if (slots[i].compare_exchange_strong(expected, copy)) return int(i);
    }
    std::free(copy);
    return -1;
}

void unregisterTemporary(int slot) noexcept {
    if (slot < 0 || std::size_t(slot) >= kSlots) return;
    char* path = slots[std::size_t(slot)].exchange(nullptr);
    if (!cleaning.load()) std::free(path);
}

void installTemporaryFileCleanup() {
    struct sigaction action {};
    action.sa_handler = removeAndReraise;
    ::sigemptyset(&action.sa_mask);
    ::sigaddset(&action.sa_mask, SIGINT);
    ::sigaddset(&action.sa_mask, SIGTERM);
    action.sa_flags = SA_RESETHAND;
    ::sigaction(SIGINT, &action, nullptr);
    ::sigaction(SIGTERM, &action, nullptr);
}

}  // namespace plantarch::io
