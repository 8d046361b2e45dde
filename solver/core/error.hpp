// Errors that cross the program's edge, and the exit codes the contract gives them.
#pragma once

#include <sstream>
#include <stdexcept>
#include <string>

namespace asperity {

// Exit codes (docs/contract.md): 0 done, 1 anything else, 2 bad input or usage, 3 unstable.
inline constexpr int kExitOk = 0;
inline constexpr int kExitFailure = 1;
inline constexpr int kExitBadInput = 2;
inline constexpr int kExitUnstable = 3;

// Bad input or usage. The message is one line naming the file, the key (or line) and the problem.
struct InputError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// A broken invariant inside the solver: always on, never for user input.
[[noreturn]] inline void invariant_failed(const char* what, const char* file, int line) {
  std::ostringstream s;
  s << "internal error: " << what << " (" << file << ":" << line << ")";
  throw std::logic_error(s.str());
}

}  // namespace asperity

// Two tiers (as MFEM's MFEM_VERIFY / MFEM_ASSERT): ASPERITY_CHECK is always on, for what must never
// happen whatever the input; ASPERITY_ASSERT is compiled only without NDEBUG (Debug builds), for
// checks too costly for the hot paths of a Release build.
#define ASPERITY_CHECK(cond) \
  ((cond) ? static_cast<void>(0) : ::asperity::invariant_failed(#cond, __FILE__, __LINE__))
#ifdef NDEBUG
#define ASPERITY_ASSERT(cond) static_cast<void>(0)
#else
#define ASPERITY_ASSERT(cond) ASPERITY_CHECK(cond)
#endif
