// The temporary files that writes in progress own, kept where a signal
// handler can find them.  The library installs no handler (no process-wide
// side effects from lib/); a program that wants interrupted writes to leave
// nothing behind calls removeTemporaryFiles() from its own SIGINT/SIGTERM
// handler (cmd/common does, for every tool).
#pragma once
#include <cstddef>
#include <string_view>

namespace rscene {

// Fixed capacity: a handler can neither allocate nor take a lock.
constexpr std::size_t kTemporaryFileSlots = 16;
constexpr std::size_t kTemporaryPathBytes = 4096;

// Records `path` until forgetTemporaryFile(slot).  Returns the slot, or -1
// when all slots are taken or the path does not fit; the caller goes on
// without the safety net then (a process writes one output at a time, so
// this needs 17 concurrent writes).
int registerTemporaryFile(std::string_view path) noexcept;
void forgetTemporaryFile(int slot) noexcept;

// Unlinks every registered path and returns how many there were.
// Async-signal-safe: lock-free atomics and unlink(2) only.  Relative paths
// are relative to the working directory, which no tool changes.
int removeTemporaryFiles() noexcept;

}  // namespace rscene
