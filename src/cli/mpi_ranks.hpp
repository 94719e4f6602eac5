#pragma once
// MPI ranks for the commands that share out a sweep's runs (cli-internal): `adjoin sweep` and
// `adjoin ida`. Built with -DADJOIN_WITH_MPI=ON, MPI is started only when a launcher (mpirun,
// srun) says so, and each of `size` ranks runs shard rank/size of the sweep (study/sweep.hpp
// SweepShard: the runs i with i mod size == rank, with its own journal); rank 0 gathers the
// rows and writes the files. Without MPI, a launcher with several ranks is refused (each rank
// would run everything and write the same files).
#include <cstddef>
#include <string>
#include <vector>

namespace adjoin::cli {

#ifdef ADJOIN_WITH_MPI
struct MpiSession {
  bool active = false;
  int rank = 0, size = 1, local_size = 1;  // local_size: the ranks on this machine
  MpiSession();  // MPI_Init when a launcher started this process; otherwise one rank
  ~MpiSession();
  MpiSession(const MpiSession&) = delete;
  MpiSession& operator=(const MpiSession&) = delete;
};

// Rank 0 receives every rank's text (by rank); the others get nothing.
std::vector<std::string> gather_text(const std::string& mine, const MpiSession& mpi);

// After a step every rank took part in (`status` 0 or an exit status, `message` its error):
// every rank learns the worst status. When it is not 0, rank 0 throws the first failing rank's
// message (InputError for exit 2, else std::runtime_error), named by rank; the others return
// the status. Returns 0 when every rank succeeded.
int worst_status(int status, const std::string& message, const MpiSession& mpi);

// Inside a catch block: the exception being handled as worst_status takes it, its exit status
// (2 for an InputError, else 3, the contract's status for the unforeseen, as in main.cpp) and
// its message in `message`.
int caught_status(std::string* message);

// Rank 0 gets every rank's sweep-table rows (cell 0 the run's index) ordered by index; the
// others get none.
std::vector<std::vector<std::string>> gather_rows(const std::vector<std::vector<std::string>>& mine, const MpiSession& mpi);

// Rank 0's status (0, or an exit status) told to every rank.
int share_status(int status, const MpiSession& mpi);

// Threads per rank: `jobs` if given, else the local cores shared among the local ranks.
unsigned threads_per_rank(unsigned jobs, const MpiSession& mpi);
#else
// Under mpirun/srun with several ranks: "NAME=VALUE" of the launcher's variable that says so
// (a size above 1 or a rank above 0), or "".
std::string mpi_launcher_evidence();
#endif

// InputError for `command` started by a launcher with several ranks in a build without MPI
// (every rank would run the whole `what` and write the same files; `hint`: what to do
// instead); nothing otherwise, and nothing in a build with MPI.
void refuse_mpi_launcher_without_mpi(const std::string& command, const std::string& what, const std::string& hint);

}  // namespace adjoin::cli
