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
constexpr std::size_t kFolderSlots = 256;
std::array<std::atomic<char*>, kFolderSlots> folderSlots{};
std::atomic<bool> cleaning{false};

void removeAndReraise(int signal) {
    cleaning.store(true);
    for (std::atomic<char*>& slot : slots)
        if (const char* path = slot.load()) ::unlink(path);
    // Folders after the files that were in them; a folder taken from the end of the array
    // first, since one is registered after its parent (rmdir fails harmlessly on a folder
    // that is not empty).
    for (std::size_t i = kFolderSlots; i-- > 0;)
        if (const char* path = folderSlots[i].load()) ::rmdir(path);
    // SA_RESETHAND put the default action back; the signal is blocked while this handler
    // runs and is delivered on return, ending the process as it would have without us.
    ::raise(signal);
}

// The first free slot, or with `ordered` the first after the last one taken, so that a folder
// registered after its parent lies after it even when an earlier slot was freed meanwhile.
template <std::size_t N>
int takeSlot(std::array<std::atomic<char*>, N>& table, const char* path, bool ordered) noexcept {
    char* copy = ::strdup(path);
    if (!copy) return -1;
    std::size_t first = ordered ? N : 0;
    while (first > 0 && table[first - 1].load() == nullptr) --first;
    for (std::size_t i = first; i < N; ++i) {
        char* expected = nullptr;
        if (table[i].compare_exchange_strong(expected, copy)) return int(i);
    }
    std::free(copy);
    return -1;
}

template <std::size_t N>
void releaseSlot(std::array<std::atomic<char*>, N>& table, int slot) noexcept {
    if (slot < 0 || std::size_t(slot) >= N) return;
    char* path = table[std::size_t(slot)].exchange(nullptr);
    if (!cleaning.load()) std::free(path);
}

}  // namespace

int registerTemporary(const char* path) noexcept {
    return takeSlot(slots, path, false);
}

void unregisterTemporary(int slot) noexcept {
    releaseSlot(slots, slot);
}

int registerTemporaryFolder(const char* path) noexcept {
    return takeSlot(folderSlots, path, true);
}

void unregisterTemporaryFolder(int slot) noexcept {
    releaseSlot(folderSlots, slot);
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
