#include "dewall/io/input_file.hpp"

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <istream>
#include <vector>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include "dewall/io/point_reader.hpp"
#include "dewall/io/quote.hpp"

namespace dewall::io {
namespace {

/// A forward-only stream buffer over a file descriptor. `fill(n)` reads ahead
/// without consuming, which is all format sniffing needs; seeking is not
/// offered, so no reader can depend on it. A read error is thrown as a
/// Parse_error: the stream (with badbit in its exception mask) passes it on
/// instead of reporting a premature end of file.
class Fd_input_buffer : public std::streambuf {
 public:
  static constexpr std::size_t capacity = std::size_t{1} << 16;
  Fd_input_buffer() : buffer_(capacity) { setg(buffer_.data(), buffer_.data(), buffer_.data()); }
  void attach(int fd, const std::string* name) { fd_ = fd, name_ = name; }

  /// Reads until at least `n` bytes are buffered or the input ends; returns the buffered bytes.
  std::string_view fill(std::size_t n) {
    if (static_cast<std::size_t>(egptr() - gptr()) < n) {
      const auto have = static_cast<std::size_t>(egptr() - gptr());
      std::memmove(buffer_.data(), gptr(), have);
      std::size_t end = have;
      for (std::size_t got = 1; end < n && got > 0; end += got) got = read_some(buffer_.data() + end, capacity - end);
      setg(buffer_.data(), buffer_.data(), buffer_.data() + end);
    }
    return {gptr(), static_cast<std::size_t>(egptr() - gptr())};
  }

 protected:
  int_type underflow() override {
    if (gptr() == egptr()) {
      const std::size_t got = read_some(buffer_.data(), capacity);
      setg(buffer_.data(), buffer_.data(), buffer_.data() + got);
    }
    return gptr() == egptr() ? traits_type::eof() : traits_type::to_int_type(*gptr());
  }
  std::streamsize xsgetn(char* s, std::streamsize n) override {
    // Buffered bytes first, then large blocks straight into the caller's memory.
    auto wanted = static_cast<std::size_t>(n);
    std::size_t done = std::min(wanted, static_cast<std::size_t>(egptr() - gptr()));
    if (done > 0) std::memcpy(s, gptr(), done);  // before the first read gptr() may be null
    gbump(static_cast<int>(done));
    while (done < wanted) {
      if (wanted - done < capacity) {
        if (underflow() == traits_type::eof()) break;
        const std::size_t k = std::min(wanted - done, static_cast<std::size_t>(egptr() - gptr()));
        std::memcpy(s + done, gptr(), k);
        gbump(static_cast<int>(k));
        done += k;
      } else {
        const std::size_t got = read_some(s + done, wanted - done);
        if (got == 0) break;
        done += got;
      }
    }
    return static_cast<std::streamsize>(done);
  }

 private:
  /// One read(2), retried on EINTR; 0 at the end of the input.
  std::size_t read_some(char* to, std::size_t n) {
    for (;;) {
      const ssize_t got = ::read(fd_, to, n);
      if (got >= 0) return static_cast<std::size_t>(got);
      if (errno != EINTR) throw Parse_error(*name_ + ": read error: " + std::strerror(errno));
    }
  }

  int fd_ = -1;
  const std::string* name_ = nullptr;
  std::vector<char> buffer_;
};

constexpr std::string_view utf8_bom = "\xEF\xBB\xBF";

}  // namespace

struct Input_file::Impl {
  std::string name;
  int fd = -1;
  bool owned = true;  // not standard input
  std::uint64_t size = 0;
  Fd_input_buffer buffer;
  std::istream stream{nullptr};
};

Input_file::Input_file(const std::string& path) : impl_(std::make_unique<Impl>()) {
  auto& m = *impl_;
  if (path == "-") {
    m.name = "<stdin>";
    m.fd = STDIN_FILENO;
    m.owned = false;
  } else {
    m.name = file_name(path);
    m.fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NOCTTY);
    if (m.fd < 0) throw Parse_error(m.name + ": cannot open file: " + std::strerror(errno));
  }
  struct stat st {};
  if (::fstat(m.fd, &st) == 0) {
    if (S_ISDIR(st.st_mode)) {
      if (m.owned) ::close(m.fd);
      throw Parse_error(m.name + ": cannot open file: " + std::strerror(EISDIR));
    }
    if (S_ISREG(st.st_mode)) m.size = static_cast<std::uint64_t>(st.st_size);
  }
  m.buffer.attach(m.fd, &m.name);
  m.stream.rdbuf(&m.buffer);
  m.stream.exceptions(std::ios::badbit);
  if (prefix(utf8_bom.size()) == utf8_bom) m.stream.ignore(static_cast<std::streamsize>(utf8_bom.size()));
}

Input_file::~Input_file() {
  if (impl_->owned) ::close(impl_->fd);
}

std::istream& Input_file::stream() { return impl_->stream; }
const std::string& Input_file::name() const { return impl_->name; }
std::uint64_t Input_file::size() const { return impl_->size; }

std::string_view Input_file::prefix(std::size_t n) {
  const auto buffered = impl_->buffer.fill(std::min<std::size_t>(n, 4096));
  return buffered.substr(0, std::min(n, buffered.size()));
}

}  // namespace dewall::io
