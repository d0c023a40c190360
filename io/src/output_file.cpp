#include "dewall/io/output_file.hpp"

#include <array>
#include <atomic>
#include <cerrno>
#include <climits>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <mutex>
#include <random>
#include <ostream>
#include <vector>

#include <fcntl.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/un.h>
#include <unistd.h>

#include "dewall/io/quote.hpp"

namespace dewall::io {
namespace {

Write_error failure(const std::string& name, const std::string& what, int error) {
  // EFBIG: the process's file size limit (the CLI ignores SIGXFSZ to get here).
  return Write_error(name + ": " + what + ": " + std::strerror(error) + (error == EFBIG ? " (a file size limit: ulimit -f)" : ""));
}

/// A stream buffer writing to a file descriptor with write(2). The first error
/// is kept (and every later write refused) for Output_file::commit to report:
/// std::ostream only remembers that something failed, not what.
class Fd_output_buffer : public std::streambuf {
 public:
  Fd_output_buffer() : buffer_(std::size_t{1} << 16) { reset(); }
  void attach(int fd) { fd_ = fd; }
  int error() const { return error_; }

 protected:
  int_type overflow(int_type c) override {
    if (!drain()) return traits_type::eof();
    if (!traits_type::eq_int_type(c, traits_type::eof())) {
      *pptr() = traits_type::to_char_type(c);
      pbump(1);
    }
    return traits_type::not_eof(c);
  }
  int sync() override { return drain() ? 0 : -1; }
  std::streamsize xsputn(const char* s, std::streamsize n) override {
    const auto count = static_cast<std::size_t>(n);
    if (count <= static_cast<std::size_t>(epptr() - pptr())) {
      std::memcpy(pptr(), s, count);
      pbump(static_cast<int>(n));
      return n;
    }
    // Larger than the room left: drain, then write large blocks straight through.
    if (!drain()) return 0;
    if (count >= buffer_.size()) return write_all(s, count) ? n : 0;
    std::memcpy(pptr(), s, count);
    pbump(static_cast<int>(n));
    return n;
  }

 private:
  void reset() { setp(buffer_.data(), buffer_.data() + buffer_.size()); }
  bool drain() {
    const bool ok = write_all(pbase(), static_cast<std::size_t>(pptr() - pbase()));
    reset();
    return ok;
  }
  bool write_all(const char* p, std::size_t n) {
    while (n > 0 && error_ == 0) {
      const ssize_t written = ::write(fd_, p, n);
      if (written < 0) {
        if (errno != EINTR) error_ = errno;
        continue;
      }
      p += written;
      n -= static_cast<std::size_t>(written);
    }
    return error_ == 0;
  }

  int fd_ = -1;
  std::vector<char> buffer_;
  int error_ = 0;
};

// Temporaries to remove when a signal ends the process. The handler may only
// call async-signal-safe functions, so each path is copied into a fixed
// buffer before its file is created, and the handler does no more than
// unlink(2) the armed ones and re-raise the signal with its default action.
struct Pending_temporary {
  std::array<char, PATH_MAX> path{};
  volatile std::sig_atomic_t armed = 0;
};
std::array<Pending_temporary, 8> pending;
std::mutex pending_mutex;  // claiming a slot; the handler only reads
// Every signal whose default action ends the process and that comes from
// outside (kill, a terminal, a timer or a limit), not from a fault of ours.
constexpr int cleanup_signals[] = {SIGINT,  SIGTERM,   SIGHUP,  SIGQUIT, SIGALRM, SIGUSR1,
                                   SIGUSR2, SIGVTALRM, SIGPROF, SIGXCPU, SIGPIPE};

extern "C" void remove_temporaries_and_reraise(int signal_number) {
  for (auto& p : pending)
    if (p.armed) ::unlink(p.path.data());
  ::signal(signal_number, SIG_DFL);
  ::raise(signal_number);  // delivered when the handler returns: the default action ends the process
}

/// Installs the handler for each signal still at its default action (a signal
/// the caller ignores, as under nohup, or handles itself, is left alone).
void install_cleanup_handlers() {
  static std::once_flag once;
  std::call_once(once, [] {
    for (int s : cleanup_signals) {
      struct sigaction old {};
      if (::sigaction(s, nullptr, &old) != 0 || old.sa_handler != SIG_DFL || (old.sa_flags & SA_SIGINFO)) continue;
      struct sigaction action {};
      action.sa_handler = remove_temporaries_and_reraise;
      sigemptyset(&action.sa_mask);
      ::sigaction(s, &action, nullptr);
    }
  });
}

/// Arms a slot for `path`; -1 when none is free (the file is then still
/// removed on errors, only not on a signal).
int arm_temporary(const std::string& path) {
  std::lock_guard lock(pending_mutex);
  if (path.size() >= PATH_MAX) return -1;
  for (std::size_t i = 0; i < pending.size(); ++i) {
    if (pending[i].armed) continue;
    std::memcpy(pending[i].path.data(), path.c_str(), path.size() + 1);
    std::atomic_signal_fence(std::memory_order_seq_cst);  // the path is complete before it is armed
    pending[i].armed = 1;
    return static_cast<int>(i);
  }
  return -1;
}

void disarm_temporary(int slot) {
  if (slot >= 0) pending[static_cast<std::size_t>(slot)].armed = 0;
}

/// The directory part of `path`, with its trailing '/' ("" for the current directory).
std::string directory_of(const std::string& path) {
  const auto slash = path.rfind('/');
  return slash == std::string::npos ? std::string() : path.substr(0, slash + 1);
}

/// True when `path` lies in /proc (/proc/self/fd/N, and /dev/stdout and
/// /dev/fd/N once followed): its links name open files, not paths to rename into.
bool in_proc(const std::string& path) {
  const std::string directory = directory_of(path);
  char resolved[PATH_MAX];
  if (!::realpath(directory.empty() ? "." : directory.c_str(), resolved)) return false;
  return std::strncmp(resolved, "/proc/", 6) == 0 || std::strcmp(resolved, "/proc") == 0;
}

/// Where to write: `path` with every symbolic link of its last component
/// followed, and whether it is written in place.
struct Target {
  std::string path;
  bool direct = false;
  bool exists = false;
  struct stat status {};
};

Target resolve(const std::string& path, const std::string& name) {
  Target t{path};
  for (int hops = 0;; ++hops) {
    if (in_proc(t.path)) {
      t.direct = true;
      t.exists = ::stat(t.path.c_str(), &t.status) == 0;
      return t;
    }
    if (::lstat(t.path.c_str(), &t.status) != 0) {
      if (errno != ENOENT) throw failure(name, "cannot open", errno);
      t.exists = false;  // a new file (perhaps a dangling link's target)
      return t;
    }
    t.exists = true;
    if (!S_ISLNK(t.status.st_mode)) {
      t.direct = !S_ISREG(t.status.st_mode);
      return t;
    }
    if (hops == 40) throw failure(name, "cannot open", ELOOP);
    std::vector<char> link(PATH_MAX + 1);
    const ssize_t n = ::readlink(t.path.c_str(), link.data(), link.size() - 1);
    if (n < 0) throw failure(name, "cannot open", errno);
    const std::string to(link.data(), static_cast<std::size_t>(n));
    t.path = to.front() == '/' ? to : directory_of(t.path) + to;
  }
}

int connect_socket(const std::string& path, const std::string& name) {
  sockaddr_un address{};
  address.sun_family = AF_UNIX;
  if (path.size() >= sizeof address.sun_path) throw failure(name, "cannot connect", ENAMETOOLONG);
  std::memcpy(address.sun_path, path.c_str(), path.size() + 1);
  const int fd = ::socket(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0);
  if (fd < 0) throw failure(name, "cannot connect", errno);
  if (::connect(fd, reinterpret_cast<const sockaddr*>(&address), sizeof address) != 0) {
    const int error = errno;
    ::close(fd);
    throw failure(name, "cannot connect", error);
  }
  return fd;
}

mode_t current_umask() {
  const mode_t mask = ::umask(0);
  ::umask(mask);
  return mask;
}

}  // namespace

struct Output_file::Impl {
  std::string name;
  int fd = -1;
  bool owned = true;           // fd is ours to close (not standard output)
  bool direct = true;
  std::string target, temporary;  // for a temporary: the final path and the temporary's
  int slot = -1;
  bool committed = false;
  Fd_output_buffer buffer;
  std::ostream stream{nullptr};

  void open_direct(const Target& t) {
    if (t.exists && S_ISSOCK(t.status.st_mode)) {
      fd = connect_socket(t.path, name);
    } else {
      // O_TRUNC for a regular file reached through /proc (/dev/stdout redirected to a file).
      const int truncate = t.exists && S_ISREG(t.status.st_mode) ? O_TRUNC : 0;
      fd = ::open(t.path.c_str(), O_WRONLY | O_NOCTTY | O_CLOEXEC | truncate);
      if (fd < 0) throw failure(name, "cannot open", errno);
    }
  }

  void open_temporary(const Target& t) {
    direct = false;
    target = t.path;
    if (t.exists && ::faccessat(AT_FDCWD, t.path.c_str(), W_OK, AT_EACCESS) != 0)
      throw failure(name, "cannot write", errno);
    // Created exclusively (O_EXCL: never through a planted link) under an
    // unpredictable name, like mkstemp; the slot is armed before the file
    // exists, so no signal can come between the two and leave it behind.
    // The basename is shortened so that the temporary's name fits NAME_MAX.
    const std::string directory = directory_of(t.path);
    const std::string stem = directory + "." + t.path.substr(directory.size(), 200) + ".tmp.";
    install_cleanup_handlers();
    std::random_device random;
    for (int attempt = 0; fd < 0; ++attempt) {
      char suffix[20];
      std::snprintf(suffix, sizeof suffix, "%08x%08x", random(), random());
      temporary = stem + suffix;
      slot = arm_temporary(temporary);
      fd = ::open(temporary.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0600);
      if (fd >= 0) break;
      const int error = errno;
      disarm_temporary(slot);
      slot = -1;
      temporary.clear();
      if (error != EEXIST || attempt == 100)
        throw failure(name, "cannot create a temporary file in " + file_name(directory.empty() ? "." : directory), error);
    }
    // Created with mode 0600: give the file the old file's mode (and owner
    // where permitted), or what a new file gets under the umask.
    mode_t mode = 0666 & ~current_umask();
    if (t.exists) {
      mode = t.status.st_mode & 07777;
      if ((t.status.st_uid != ::geteuid() || t.status.st_gid != ::getegid()) &&
          ::fchown(fd, t.status.st_uid, t.status.st_gid) != 0)
        mode &= ~mode_t{S_ISUID | S_ISGID};  // never a set-id file of another owner
    }
    if (::fchmod(fd, mode) != 0) throw failure(name, "cannot set the mode of the temporary file", errno);
  }

  // An uncommitted output is discarded however it ends: destroyed, or its
  // constructor failing after the temporary was created (fchmod), or a probe.
  ~Impl() {
    if (!committed) discard();
  }

  void discard() {
    if (owned && fd >= 0) ::close(fd);
    fd = -1;
    if (!temporary.empty()) ::unlink(temporary.c_str());
    temporary.clear();
    disarm_temporary(slot);
    slot = -1;
  }

  void finish_temporary() {
    if (::fsync(fd) != 0) throw failure(name, "write error", errno);
    const int closing = fd;
    fd = -1;
    if (::close(closing) != 0) throw failure(name, "write error", errno);
    if (::rename(temporary.c_str(), target.c_str()) != 0) throw failure(name, "cannot rename the temporary file", errno);
    temporary.clear();  // nothing to remove any more
    disarm_temporary(slot);
    slot = -1;
    // The rename is durable once the directory is: some file systems cannot
    // fsync a directory (EINVAL), which then is the best one can do.
    const std::string directory = directory_of(target).empty() ? "." : directory_of(target);
    const int d = ::open(directory.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    if (d >= 0) {
      const int error = ::fsync(d) == 0 ? 0 : errno;
      ::close(d);
      if (error != 0 && error != EINVAL && error != EROFS) throw failure(name, "write error", error);
    }
  }
};

namespace {

/// How messages name an output path; the empty name as ''.
std::string output_name(const std::string& path) { return path.empty() ? std::string("''") : file_name(path); }

/// resolve(), and the empty name refused as the shell refuses `> ''`.
Target resolve_output(const std::string& path, const std::string& name) {
  if (path.empty()) throw failure(name, "cannot open", ENOENT);
  return resolve(path, name);
}

}  // namespace

Output_file::Output_file(const std::string& path) : impl_(std::make_unique<Impl>()) {
  auto& m = *impl_;
  if (path == "-") {
    m.name = "<stdout>";
    finish_standard_output();  // what printf wrote so far comes first
    m.fd = STDOUT_FILENO;
    m.owned = false;
  } else {
    m.name = output_name(path);
    const Target t = resolve_output(path, m.name);
    if (t.direct) m.open_direct(t);
    else m.open_temporary(t);
  }
  m.buffer.attach(m.fd);
  m.stream.rdbuf(&m.buffer);
}

void Output_file::probe(const std::string& path) {
  if (path == "-") return;
  const std::string name = output_name(path);
  const Target t = resolve_output(path, name);
  if (!t.direct) {
    Impl m;  // its destructor removes the temporary
    m.name = name;
    m.open_temporary(t);
    return;
  }
  // Written in place, and not opened now: a FIFO's reader would take the
  // probe's close for the end of the output. What can be told without opening:
  if (!t.exists) return;
  if (S_ISDIR(t.status.st_mode)) throw failure(name, "cannot open", EISDIR);
  if (!S_ISSOCK(t.status.st_mode) && ::faccessat(AT_FDCWD, t.path.c_str(), W_OK, AT_EACCESS) != 0)
    throw failure(name, "cannot open", errno);
}

Output_file::~Output_file() = default;

std::ostream& Output_file::stream() { return impl_->stream; }
const std::string& Output_file::name() const { return impl_->name; }

bool Output_file::patch(std::size_t offset, const void* data, std::size_t size) {
  auto& m = *impl_;
  if (m.direct) return false;
  m.stream.flush();
  check();
  const char* p = static_cast<const char*>(data);
  while (size > 0) {
    const ssize_t written = ::pwrite(m.fd, p, size, static_cast<off_t>(offset));
    if (written < 0) {
      if (errno == EINTR) continue;
      throw failure(m.name, "write error", errno);
    }
    p += written;
    offset += static_cast<std::size_t>(written);
    size -= static_cast<std::size_t>(written);
  }
  return true;
}
bool Output_file::direct() const { return impl_->direct; }

const std::string& Output_file::temporary_path() const { return impl_->temporary; }

void Output_file::check() const {
  const auto& m = *impl_;
  if (m.buffer.error() != 0) throw failure(m.name, "write error", m.buffer.error());
  if (!m.stream) throw Write_error(m.name + ": write error");
}

void Output_file::commit() {
  auto& m = *impl_;
  m.stream.flush();
  check();
  if (!m.direct) {
    m.finish_temporary();
  } else if (m.owned) {
    const int closing = m.fd;
    m.fd = -1;
    if (::close(closing) != 0) throw failure(m.name, "write error", errno);
  }
  m.committed = true;
}

void write_output_file(const std::string& path, const std::function<void(std::ostream&)>& write) {
  Output_file file(path);
  write(file.stream());
  file.commit();
}

void finish_standard_output() {
  errno = 0;
  const bool flushed = std::fflush(stdout) == 0;
  const int error = errno;
  if (flushed && !std::ferror(stdout)) return;
  std::clearerr(stdout);
  throw Write_error(std::string("<stdout>: write error") + (!flushed && error ? std::string(": ") + std::strerror(error) : ""));
}

}  // namespace dewall::io
