// MPI ranks sharing out a sweep's runs (mpi_ranks.hpp).
#include "mpi_ranks.hpp"

#include <algorithm>
#include <cstdlib>
#include <stdexcept>
#include <thread>

#include "adjoin/core/csv_line.hpp"
#include "adjoin/core/errors.hpp"
#include "adjoin/core/parse_number.hpp"

#ifdef ADJOIN_WITH_MPI
#include <mpi.h>
#endif

namespace adjoin::cli {

#ifdef ADJOIN_WITH_MPI
namespace {

bool launched_by_mpi() {
  for (const char* v : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "PMIX_RANK", "MPI_LOCALNRANKS", "SLURM_PROCID"})
    if (std::getenv(v)) return true;
  return false;
}

// The run number of a row (rows come from the ranks' journals, checked there).
std::size_t cell_index(const std::vector<std::string>& cells) {
  std::size_t index = 0;
  parse_count(cells.at(0), &index);
  return index;
}

}  // namespace

MpiSession::MpiSession() {
  if (!launched_by_mpi()) return;
  int initialized = 0;
  MPI_Initialized(&initialized);
  if (!initialized) MPI_Init(nullptr, nullptr);
  active = true;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm_size(MPI_COMM_WORLD, &size);
  MPI_Comm local;
  MPI_Comm_split_type(MPI_COMM_WORLD, MPI_COMM_TYPE_SHARED, rank, MPI_INFO_NULL, &local);
  MPI_Comm_size(local, &local_size);
  MPI_Comm_free(&local);
}

MpiSession::~MpiSession() {
  int finalized = 0;
  if (active && (MPI_Finalized(&finalized), !finalized)) MPI_Finalize();
}

std::vector<std::string> gather_text(const std::string& mine, const MpiSession& mpi) {
  const int length = static_cast<int>(mine.size());
  std::vector<int> lengths(static_cast<std::size_t>(mpi.size)), offsets(static_cast<std::size_t>(mpi.size));
  MPI_Gather(&length, 1, MPI_INT, lengths.data(), 1, MPI_INT, 0, MPI_COMM_WORLD);
  int total = 0;
  for (int r = 0; r < mpi.size; ++r) {
    offsets[static_cast<std::size_t>(r)] = total;
    total += lengths[static_cast<std::size_t>(r)];
  }
  std::string all(mpi.rank == 0 ? static_cast<std::size_t>(total) : 0, '\0');
  MPI_Gatherv(mine.data(), length, MPI_CHAR, all.data(), lengths.data(), offsets.data(), MPI_CHAR, 0, MPI_COMM_WORLD);
  std::vector<std::string> out;
  if (mpi.rank == 0)
    for (int r = 0; r < mpi.size; ++r)
      out.push_back(all.substr(static_cast<std::size_t>(offsets[static_cast<std::size_t>(r)]),
                               static_cast<std::size_t>(lengths[static_cast<std::size_t>(r)])));
  return out;
}

int caught_status(std::string* message) {
  try {
    throw;
  } catch (const InputError& e) {
    *message = e.what();
    return kExitInputError;
  } catch (const std::exception& e) {
    *message = std::string("internal: ") + e.what();
    return kExitNumericalError;
  }
}

int worst_status(int status, const std::string& message, const MpiSession& mpi) {
  int worst = 0;
  MPI_Allreduce(&status, &worst, 1, MPI_INT, MPI_MAX, MPI_COMM_WORLD);
  const auto messages = gather_text(status ? message : std::string(), mpi);
  if (worst == 0 || mpi.rank != 0) return worst;
  for (int r = 0; r < mpi.size; ++r)
    if (!messages[static_cast<std::size_t>(r)].empty()) {
      const std::string text = mpi.size > 1 ? "rank " + std::to_string(r) + ": " + messages[static_cast<std::size_t>(r)] : messages[0];
      if (worst == kExitInputError) throw InputError(text);
      throw std::runtime_error(text);
    }
  return worst;
}

std::vector<std::vector<std::string>> gather_rows(const std::vector<std::vector<std::string>>& mine, const MpiSession& mpi) {
  std::string text;
  for (const auto& r : mine) text += csv_line(r) + "\n";
  std::vector<std::vector<std::string>> rows;
  for (const auto& part : gather_text(text, mpi)) {
    std::size_t pos = 0;
    while (pos < part.size()) {
      const std::size_t end = part.find('\n', pos);
      std::vector<std::string> cells;
      split_csv_line(part.substr(pos, end - pos), &cells);
      rows.push_back(std::move(cells));
      pos = end + 1;
    }
  }
  std::sort(rows.begin(), rows.end(), [](const auto& a, const auto& b) { return cell_index(a) < cell_index(b); });
  return rows;
}

int share_status(int status, const MpiSession&) {
  MPI_Bcast(&status, 1, MPI_INT, 0, MPI_COMM_WORLD);
  return status;
}

unsigned threads_per_rank(unsigned jobs, const MpiSession& mpi) {
  return jobs ? jobs : std::max(1u, std::thread::hardware_concurrency() / static_cast<unsigned>(std::max(1, mpi.local_size)));
}
#else
std::string mpi_launcher_evidence() {
  const auto above = [](const char* name, long limit) -> std::string {
    const char* value = std::getenv(name);
    if (!value) return "";
    char* end = nullptr;
    const long n = std::strtol(value, &end, 10);
    return end != value && n > limit ? std::string(name) + "=" + value : std::string();
  };
  for (const char* size : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "PMIX_SIZE", "MPI_LOCALNRANKS", "MV2_COMM_WORLD_SIZE"})
    if (auto found = above(size, 1); !found.empty()) return found;
  for (const char* rank : {"OMPI_COMM_WORLD_RANK", "PMI_RANK", "PMIX_RANK", "MV2_COMM_WORLD_RANK"})
    if (auto found = above(rank, 0); !found.empty()) return found;
  return "";
}
#endif

void refuse_mpi_launcher_without_mpi([[maybe_unused]] const std::string& command, [[maybe_unused]] const std::string& what,
                                     [[maybe_unused]] const std::string& hint) {
#ifndef ADJOIN_WITH_MPI
  if (const std::string evidence = mpi_launcher_evidence(); !evidence.empty())
    throw InputError(command + ": started by an MPI launcher with several ranks (" + evidence +
                     "), but this adjoin was built without MPI: every rank would run the whole " + what +
                     " and write the same files. Build it with MPI (scripts/setup.sh --with-mpi, then cmake -DADJOIN_WITH_MPI=ON), "
                     "or run it without mpirun (" + hint + ")");
#endif
}

}  // namespace adjoin::cli
