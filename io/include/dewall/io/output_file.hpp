// The one way every command writes a file (triangulate, generate, draw) or
// standard output (certify, demo, help): what happens depends on the kind of
// target, and every failure is an exception naming it.
//
//  * "-": standard output, written directly (C stdio's buffer is flushed
//    first, so what was printf'ed before comes first).
//  * An existing target that is not a regular file — a character device, a
//    FIFO, a socket — or any path through /proc (/dev/stdout,
//    /proc/self/fd/N): opened and written directly, in place. There is
//    nothing to be atomic about; a failed run may have written part of its output.
//  * A regular file or a new name: written to a temporary file created
//    exclusively (O_EXCL, a random 64-bit name, as mkstemp) in the target's
//    directory, fsync'ed, renamed over the target, and the directory fsync'ed.
//    A reader sees the old file or the complete new one, never a part, even
//    after a crash. The old file's permission bits are kept (and its owner and
//    group where the process may set them); hard links to the old file keep
//    the old contents, since the name now points to a new file. A read-only
//    target is refused, as the shell would. The temporary is removed on every
//    error, on an exception, and on a signal that ends the process from
//    outside (SIGINT, SIGTERM, SIGHUP, SIGQUIT, SIGALRM, SIGUSR1, SIGUSR2,
//    SIGVTALRM, SIGPROF, SIGXCPU, SIGPIPE).
//  * A symbolic link: followed to its final target (the temporary goes in that
//    target's directory), so the link stays a link and the file it points to is
//    replaced; a dangling link creates its target.
#pragma once

#include <functional>
#include <iosfwd>
#include <memory>
#include <stdexcept>
#include <string>

namespace dewall::io {

/// A file or standard output could not be written; what() names it and says why.
class Write_error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// An output in progress. Write to stream(), then commit(); destroying an
/// uncommitted Output_file discards it (the temporary is removed; a direct
/// target keeps what was written).
class Output_file {
 public:
  /// Opens `path` ("-" = standard output) as described above.
  /// \throws Write_error when it cannot be opened or the temporary cannot be created.
  explicit Output_file(const std::string& path);
  ~Output_file();
  Output_file(const Output_file&) = delete;
  Output_file& operator=(const Output_file&) = delete;

  /// The stream to write to (binary: no newline translation). A failed write
  /// sets its badbit; commit() reports the error.
  std::ostream& stream();
  /// \throws Write_error when a write to stream() has failed so far.
  void check() const;
  /// Makes the output final: flushes, and for a temporary fsyncs, renames it
  /// over the target and fsyncs the directory.
  /// \throws Write_error on any failure (nothing is left behind for a temporary).
  void commit();
  /// Overwrites `size` bytes already written at `offset` (a header field known
  /// only at the end) and returns true; returns false, writing nothing, for a
  /// direct target (a pipe or a device cannot seek).
  /// \throws Write_error when the write fails.
  bool patch(std::size_t offset, const void* data, std::size_t size);
  /// Checks, before a long computation, that `path` can be written as the
  /// constructor would write it, and leaves nothing behind: for a regular file
  /// or a new name the temporary is created beside the target and removed (a
  /// missing directory, a read-only file or directory, a directory as the
  /// target, the empty name fail here); a target written in place is not
  /// opened (a FIFO's reader would see its end), only checked to be writable
  /// and not a directory. Standard output ("-") is not checked.
  /// \throws Write_error, as the constructor would.
  static void probe(const std::string& path);
  /// The target as messages name it ("<stdout>", or the path made printable).
  const std::string& name() const;
  /// The temporary's path (empty for a target written in place): where other
  /// processes may write the output before commit() (dewall-mpi's ranks write
  /// their parts of it through MPI-IO, then rank 0 commits).
  const std::string& temporary_path() const;
  /// True when the target is written in place (standard output, devices,
  /// FIFOs, sockets, /proc), false for a temporary renamed into place.
  bool direct() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// Opens `path` as an Output_file, runs `write(stream)` and commits.
/// \throws Write_error; an exception from `write` discards the output and is rethrown.
void write_output_file(const std::string& path, const std::function<void(std::ostream&)>& write);

/// Flushes C stdio's standard output (what printf wrote) and checks it.
/// \throws Write_error ("<stdout>: write error: …") when anything written to
/// it was lost, e.g. on a full device.
void finish_standard_output();

}  // namespace dewall::io
