// Errors that end every rank alike. A rank that throws alone leaves the others
// waiting in their next collective call (a hang), so each step that may fail
// on some ranks only is followed by one agreement: every rank learns whether
// any failed and, if so, the lowest failing rank's error, and all throw it.
#pragma once

#include <mpi.h>

#include <cstdint>
#include <exception>
#include <string>
#include <utility>

#include "dewall/error.hpp"

namespace dewall::mpi {

/// What went wrong, as every rank reports it.
enum class Error_kind : int {
  none = 0,
  invalid_input = 1,  ///< dewall::Invalid_input (the input cannot be triangulated)
  file = 2,           ///< a file could not be read or written (the tool's)
  other = 3,          ///< anything else (std::bad_alloc, a broken invariant)
};

/// One rank's error.
struct Rank_error {
  Error_kind kind = Error_kind::none;
  std::string message;  ///< what(); for invalid_input the reason (Invalid_input::reason())
  std::uint64_t point_index = Invalid_input::npos;  ///< for invalid_input
  int rank = -1;                                    ///< the rank that met it
};

/// Collective over `comm`: the error of the lowest rank whose `mine` is not
/// none, on every rank; kind none when no rank failed.
Rank_error agree_on_error(MPI_Comm comm, const Rank_error& mine);

/// The error an exception carries (invalid_input for Invalid_input, else other).
Rank_error error_of(std::exception_ptr e);

/// Throws `e` (kind != none): Invalid_input for invalid_input, else std::runtime_error.
[[noreturn]] void throw_error(const Rank_error& e);

/// Collective: runs f() on this rank, then agrees; when f threw on any rank,
/// every rank throws the lowest failing rank's error (throw_error).
template <class F>
void run_collectively(MPI_Comm comm, F&& f) {
  Rank_error mine;
  try {
    std::forward<F>(f)();
  } catch (...) {
    mine = error_of(std::current_exception());
  }
  const Rank_error agreed = agree_on_error(comm, mine);
  if (agreed.kind != Error_kind::none) throw_error(agreed);
}

}  // namespace dewall::mpi
