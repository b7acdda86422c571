#include "core/temp_files.hpp"

#include <unistd.h>

#include <atomic>
#include <cstring>

namespace rscene {
namespace {

// A slot is free, being filled (invisible to the handler), or live.
enum SlotState : int { kFree = 0, kFilling = 1, kLive = 2 };

struct Slot {
  std::atomic<int> state{kFree};
  char path[kTemporaryPathBytes];
};

static_assert(std::atomic<int>::is_always_lock_free, "signal handlers need lock-free atomics");

Slot gSlots[kTemporaryFileSlots];

}  // namespace

int registerTemporaryFile(std::string_view path) noexcept {
  if (path.empty() || path.size() >= kTemporaryPathBytes || path.find('\0') != std::string_view::npos) return -1;
  for (std::size_t i = 0; i < kTemporaryFileSlots; ++i) {
    int expected = kFree;
    if (!gSlots[i].state.compare_exchange_strong(expected, kFilling, std::memory_order_acquire)) continue;
    std::memcpy(gSlots[i].path, path.data(), path.size());
    gSlots[i].path[path.size()] = '\0';
    gSlots[i].state.store(kLive, std::memory_order_release);
    return static_cast<int>(i);
  }
  return -1;
}

void forgetTemporaryFile(int slot) noexcept {
  if (slot < 0 || static_cast<std::size_t>(slot) >= kTemporaryFileSlots) return;
  gSlots[slot].state.store(kFree, std::memory_order_release);
}

int removeTemporaryFiles() noexcept {
  int removed = 0;
  for (Slot& s : gSlots) {
    if (s.state.load(std::memory_order_acquire) != kLive) continue;
    ::unlink(s.path);
    ++removed;
  }
  return removed;
}

}  // namespace rscene
