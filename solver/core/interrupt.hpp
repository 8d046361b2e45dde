// SIGINT/SIGTERM (and SIGABRT): stop at once, but first remove what would mislead (a half-written
// file, a study's lock). The handler only unlinks registered paths and re-raises the signal with
// its default action, so the exit status says "killed by SIGINT" (130 in a shell). Only
// async-signal-safe calls run in the handler (unlink, signal, raise); the paths live in fixed
// slots of atomic pointers, so a worker thread may register one while the handler runs.
// Header-only so that geometry and io (siblings in the layering) can both guard their writes.
#pragma once

#include <signal.h>
#include <unistd.h>

#include <array>
#include <atomic>
#include <cstdlib>
#include <cstring>
#include <filesystem>

namespace asperity {

inline constexpr std::size_t kCleanupSlots = 256;  // writing threads plus a lock; more go unguarded

namespace detail {
inline std::array<std::atomic<char*>, kCleanupSlots> g_cleanup_slots{};

inline void on_interrupt(int sig) {
  for (auto& s : g_cleanup_slots) {
    if (char* p = s.load()) ::unlink(p);
  }
  ::signal(sig, SIG_DFL);
  ::raise(sig);
}
}  // namespace detail

// Installs the handler for SIGINT and SIGTERM (once, from main), and for SIGABRT: an abort
// (std::terminate, a failed assert in a library) must not leave a lock or a temporary either.
inline void install_interrupt_cleanup() {
  struct sigaction sa {};
  sa.sa_handler = detail::on_interrupt;
  sigemptyset(&sa.sa_mask);
  ::sigaction(SIGINT, &sa, nullptr);
  ::sigaction(SIGTERM, &sa, nullptr);
  ::sigaction(SIGABRT, &sa, nullptr);
}

// While alive, `path` is removed if the process is interrupted.
class RemoveOnInterrupt {
 public:
  explicit RemoveOnInterrupt(const std::filesystem::path& path) {
    char* copy = ::strdup(path.c_str());
    if (!copy) return;
    for (std::size_t i = 0; i < kCleanupSlots; ++i) {
      char* expected = nullptr;
      if (detail::g_cleanup_slots[i].compare_exchange_strong(expected, copy)) {
        slot_ = static_cast<int>(i);
        return;
      }
    }
    std::free(copy);
  }
  ~RemoveOnInterrupt() {
    if (slot_ < 0) return;
    std::free(detail::g_cleanup_slots[static_cast<std::size_t>(slot_)].exchange(nullptr));
  }
  RemoveOnInterrupt(const RemoveOnInterrupt&) = delete;
  RemoveOnInterrupt& operator=(const RemoveOnInterrupt&) = delete;

 private:
  int slot_ = -1;
};

}  // namespace asperity
