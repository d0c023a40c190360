// agree_on_error and its helpers (collective_error.hpp).
#include "dewall/mpi/collective_error.hpp"

#include <stdexcept>
#include <vector>

namespace dewall::mpi {

Rank_error agree_on_error(MPI_Comm comm, const Rank_error& mine) {
  int rank = 0, size = 1;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &size);
  const int candidate = mine.kind == Error_kind::none ? size : rank;
  int first = size;
  MPI_Allreduce(&candidate, &first, 1, MPI_INT, MPI_MIN, comm);
  Rank_error agreed;
  if (first == size) return agreed;
  // The failing rank sends kind, point index and the message's length, then the message.
  std::uint64_t head[3] = {static_cast<std::uint64_t>(mine.kind), mine.point_index, mine.message.size()};
  MPI_Bcast(head, 3, MPI_UINT64_T, first, comm);
  std::vector<char> text(head[2]);
  if (rank == first) text.assign(mine.message.begin(), mine.message.end());
  if (!text.empty()) MPI_Bcast(text.data(), static_cast<int>(text.size()), MPI_CHAR, first, comm);
  agreed.kind = static_cast<Error_kind>(head[0]);
  agreed.point_index = head[1];
  agreed.message.assign(text.begin(), text.end());
  agreed.rank = first;
  return agreed;
}

Rank_error error_of(std::exception_ptr e) {
  Rank_error r;
  try {
    std::rethrow_exception(e);
  } catch (const Invalid_input& x) {
    r.kind = Error_kind::invalid_input;
    r.message = x.reason();  // what() is "point N " + reason() when a point is named
    r.point_index = x.point_index();
  } catch (const std::exception& x) {
    r.kind = Error_kind::other;
    r.message = x.what();
  } catch (...) {
    r.kind = Error_kind::other;
    r.message = "unknown exception";
  }
  return r;
}

void throw_error(const Rank_error& e) {
  if (e.kind == Error_kind::invalid_input) {
    if (e.point_index == Invalid_input::npos) throw Invalid_input(e.message);
    throw Invalid_input(static_cast<std::size_t>(e.point_index), e.message);
  }
  throw std::runtime_error(e.message);
}

}  // namespace dewall::mpi
