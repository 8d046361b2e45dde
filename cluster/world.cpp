// MPI behind a small text-message interface; without ASPERITY_MPI a world of one process.
#include "cluster/world.hpp"

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <mutex>
#include <thread>

#include "solver/core/error.hpp"

#if ASPERITY_HAVE_MPI
#include <mpi.h>
#endif

namespace asperity::cluster {
namespace {

int env_int(const char* name, int fallback) {
  const char* v = std::getenv(name);
  if (v == nullptr || *v == '\0') return fallback;
  char* end = nullptr;
  const long x = std::strtol(v, &end, 10);
  return end != nullptr && *end == '\0' && x >= 0 && x < 1'000'000 ? static_cast<int>(x) : fallback;
}

#if ASPERITY_HAVE_MPI
// One millisecond: short against a case (tens of milliseconds and up), long enough that a
// waiting rank costs no measurable CPU.
void pause() {
  std::this_thread::sleep_for(std::chrono::milliseconds(1));
}

// MPI_THREAD_SERIALIZED: any thread may call MPI, one at a time; this mutex is the "one at a
// time". (MPI_THREAD_MULTIPLE is not needed and not built into every MPI.)
std::mutex& mpi_mutex() {
  static std::mutex m;
  return m;
}
#endif

}  // namespace

int launched_ranks() {
  for (const char* name : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "PMIX_SIZE", "MV2_COMM_WORLD_SIZE",
                           "SLURM_STEP_NUM_TASKS"}) {
    if (const int n = env_int(name, 0); n > 0) return n;
  }
  return 1;
}

int launched_rank() {
  for (const char* name :
       {"OMPI_COMM_WORLD_RANK", "PMI_RANK", "PMIX_RANK", "MV2_COMM_WORLD_RANK", "SLURM_PROCID"}) {
    if (const int r = env_int(name, -1); r >= 0) return r;
  }
  return 0;
}

bool built_with_mpi() {
  return ASPERITY_HAVE_MPI != 0;
}

World::World() {
  if (launched_ranks() <= 1) return;
#if ASPERITY_HAVE_MPI
  int provided = 0;
  MPI_Init_thread(nullptr, nullptr, MPI_THREAD_SERIALIZED, &provided);
  if (provided < MPI_THREAD_SERIALIZED) {
    MPI_Finalize();
    throw InputError("MPI: this MPI library does not let threads take turns (" +
                     std::to_string(provided) +
                     " < MPI_THREAD_SERIALIZED); run one thread per rank: -j 1");
  }
  MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
  MPI_Comm_size(MPI_COMM_WORLD, &size_);
  mpi_ = true;
#else
  throw InputError("launched as " + std::to_string(launched_ranks()) +
                   " ranks (mpirun or srun), but this asperity was built without MPI "
                   "(ASPERITY_MPI=OFF): every rank would run the whole job; rebuild with MPI "
                   "(libopenmpi-dev) or run one process with -j THREADS");
#endif
}

World::~World() {
#if ASPERITY_HAVE_MPI
  if (mpi_) MPI_Finalize();
#endif
}

void World::send(int to, int tag, const std::string& text) {
#if ASPERITY_HAVE_MPI
  MPI_Request request{};
  {
    std::lock_guard<std::mutex> lock(mpi_mutex());
    MPI_Isend(text.data(), static_cast<int>(text.size()), MPI_CHAR, to, tag, MPI_COMM_WORLD,
              &request);
  }
  for (;;) {
    int done = 0;
    {
      std::lock_guard<std::mutex> lock(mpi_mutex());
      MPI_Test(&request, &done, MPI_STATUS_IGNORE);
    }
    if (done != 0) return;
    pause();
  }
#else
  (void)to, (void)tag, (void)text;
  ASPERITY_CHECK(!"send in a world of one");
#endif
}

std::pair<int, std::string> World::try_receive_any(int tag) {
#if ASPERITY_HAVE_MPI
  std::lock_guard<std::mutex> lock(mpi_mutex());
  int flag = 0;
  MPI_Status status{};
  MPI_Iprobe(MPI_ANY_SOURCE, tag, MPI_COMM_WORLD, &flag, &status);
  if (flag == 0) return {-1, {}};
  int count = 0;
  MPI_Get_count(&status, MPI_CHAR, &count);
  std::string text(static_cast<std::size_t>(count), '\0');
  MPI_Recv(text.data(), count, MPI_CHAR, status.MPI_SOURCE, tag, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
  return {status.MPI_SOURCE, text};
#else
  (void)tag;
  return {-1, {}};
#endif
}

std::string World::receive(int from, int tag) {
#if ASPERITY_HAVE_MPI
  for (;;) {
    {
      std::lock_guard<std::mutex> lock(mpi_mutex());
      int flag = 0;
      MPI_Status status{};
      MPI_Iprobe(from, tag, MPI_COMM_WORLD, &flag, &status);
      if (flag != 0) {
        int count = 0;
        MPI_Get_count(&status, MPI_CHAR, &count);
        std::string text(static_cast<std::size_t>(count), '\0');
        MPI_Recv(text.data(), count, MPI_CHAR, from, tag, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
        return text;
      }
    }
    pause();
  }
#else
  (void)from, (void)tag;
  ASPERITY_CHECK(!"receive in a world of one");
  return {};
#endif
}

namespace {
constexpr int kVerdictTag = 7;
}

void World::on_root(const std::function<void()>& work) {
  if (size_ == 1) {
    work();
    return;
  }
  if (root()) {
    std::exception_ptr error;
    std::string message;
    try {
      work();
    } catch (const std::exception& e) {
      error = std::current_exception();
      message = e.what();
    }
    // "" is the all-clear; an error message is never empty.
    for (int r = 1; r < size_; ++r) send(r, kVerdictTag, error ? message + " " : "");
    if (error) std::rethrow_exception(error);
    return;
  }
  const std::string verdict = receive(0, kVerdictTag);
  if (!verdict.empty()) throw InputError(verdict.substr(0, verdict.size() - 1));
}

int World::guard(const std::function<int()>& body) {
  if (size_ == 1) return body();
  try {
    return body();
  } catch (const InputError&) {
    throw;  // every rank met it (input is read by all, or on_root told them): they leave together
  } catch (const std::exception& e) {
    std::fprintf(stderr, "asperity: rank %d of %d: error: %s (stopping every rank)\n", rank_, size_,
                 e.what());
#if ASPERITY_HAVE_MPI
    MPI_Abort(MPI_COMM_WORLD, kExitFailure);
#endif
    return kExitFailure;
  }
}

}  // namespace asperity::cluster
