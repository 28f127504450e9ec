#pragma once
// Named temporary files that SIGINT and SIGTERM remove.
//
// Most temporaries of AtomicFile have no name (O_TMPFILE) and vanish with the process. A
// named one exists where the filesystem offers no unnamed files, when a job holds back more
// files than it may keep open, and for the moment between naming a finished file and
// renaming it over its target. Each is registered here while it exists; the handler that
// installTemporaryFileCleanup() puts on SIGINT and SIGTERM unlinks every registered path,
// then lets the signal end the process as it would have. SIGKILL cannot be caught: a named
// temporary alive at that moment stays behind.

namespace plantarch::io {

/// Registers `path` (copied) for removal on SIGINT/SIGTERM; returns its slot, or -1 when all
/// slots are taken (the file then stays unregistered). Not for use inside a signal handler.
int registerTemporary(const char* path) noexcept;
/// Forgets a registration (after the file was renamed or removed). -1 is ignored.
void unregisterTemporary(int slot) noexcept;
/// Registers a folder made for outputs (copied) for removal on SIGINT/SIGTERM, after every
/// registered file: the handler removes it if it is empty by then, folders registered later
/// (deeper ones, made after their parents) first. Returns its slot, or -1 when all are taken.
int registerTemporaryFolder(const char* path) noexcept;
/// Forgets a folder's registration (it was kept or removed). -1 is ignored.
void unregisterTemporaryFolder(int slot) noexcept;
/// Installs the handler on SIGINT and SIGTERM (idempotent). A program that has its own
/// handlers for them should not call this.
void installTemporaryFileCleanup();

}  // namespace plantarch::io
