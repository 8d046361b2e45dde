// The processes a command runs on: one, or the ranks of an MPI launch (mpirun, Slurm's srun).
// Only the study and validate commands join a launch; every other command runs as one process.
#pragma once

#include <functional>
#include <string>

namespace asperity::cluster {

// Ranks the launcher started and this process's rank, read from the launcher's environment
// (OpenMPI's mpirun: OMPI_COMM_WORLD_*; MPICH/Hydra and PMI: PMI_*; Slurm's srun:
// SLURM_STEP_NUM_TASKS, SLURM_PROCID): 1 and 0 when no launcher started this process. Read
// before MPI starts, so that a build without MPI can refuse a launch instead of letting every
// rank run everything, and so that only rank 0 reports bad input.
int launched_ranks();
int launched_rank();

// True when this build talks MPI (CMake option ASPERITY_MPI).
bool built_with_mpi();

// The ranks of this run. Joins MPI when launched_ranks() > 1 (InputError when the build has no
// MPI: each rank would run the whole job), else a world of one. Leaves MPI on destruction.
class World {
 public:
  World();
  ~World();
  World(const World&) = delete;
  World& operator=(const World&) = delete;

  int rank() const { return rank_; }
  int size() const { return size_; }
  bool root() const { return rank_ == 0; }

  // Text messages between ranks, callable from any thread (MPI calls are serialized inside).
  // Neither spins a core while it waits: they poll every millisecond, so a rank that waits for
  // another's long case leaves the CPU to the workers (mpirun's blocking calls busy-poll).
  void send(int to, int tag, const std::string& text);
  std::string receive(int from, int tag);
  // A message from any rank with this tag, if one is waiting: {from, text}; from = -1: none.
  std::pair<int, std::string> try_receive_any(int tag);

  // Rank 0 runs `work`; every rank learns whether it threw. When it did, rank 0 rethrows its
  // error and every other rank throws InputError with the same message (reported by rank 0 only),
  // so all ranks leave together instead of waiting for one that gave up.
  void on_root(const std::function<void()>& work);

  // Runs the command body `body`; an error on one rank of several stops every rank (MPI_Abort)
  // after printing it with the rank, since the others would wait for that rank forever.
  int guard(const std::function<int()>& body);

 private:
  int rank_ = 0, size_ = 1;
  bool mpi_ = false;
};

}  // namespace asperity::cluster
