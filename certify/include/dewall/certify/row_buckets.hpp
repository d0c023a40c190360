// Streaming certification's store of rows: temporary files, one per range of
// vertices, each holding every row that files a facet under one of its
// vertices (the row's smallest vertex and, when it lies in another range, its
// second smallest: the smallest vertex of the facet opposite the first). A
// range's facets are then matched from its file alone. Topology only.
#pragma once

#include <algorithm>
#include <array>
#include <cerrno>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

#include <unistd.h>

namespace dewall::certify::detail {

template <std::size_t K>
class Row_buckets {
 public:
  /// A stored row: its number in the input and its vertices (encode_row).
  struct Entry {
    std::uint64_t row;
    std::array<std::uint32_t, K> cell;
  };

  /// `buckets` files (at least one) over the vertices [0, vertex_count), in
  /// `directory` (empty: $TMPDIR, else /tmp), each unlinked as soon as it is
  /// open, so that nothing is left behind whatever happens. Each file buffers
  /// `buffer_entries` entries. \throws std::runtime_error when a file cannot be made.
  Row_buckets(std::size_t vertex_count, std::size_t buckets, std::string directory, std::size_t buffer_entries)
      : width_(std::max<std::size_t>(1, (vertex_count + std::max<std::size_t>(buckets, 1) - 1) / std::max<std::size_t>(buckets, 1))),
        n_(vertex_count),
        buffer_entries_(std::max<std::size_t>(buffer_entries, 1)) {
    if (directory.empty()) {
      const char* t = std::getenv("TMPDIR");
      directory = t && *t ? t : "/tmp";
    }
    directory_ = directory;
    const std::size_t count = std::max<std::size_t>(1, (vertex_count + width_ - 1) / width_);
    for (std::size_t b = 0; b < count; ++b) {
      std::string name = directory + "/dewall-certify-XXXXXX";
      const int fd = ::mkstemp(name.data());
      if (fd < 0) fail("cannot create a temporary file");
      ::unlink(name.c_str());
      std::FILE* f = ::fdopen(fd, "w+b");
      if (!f) {
        ::close(fd);
        fail("cannot open a temporary file");
      }
      files_.emplace_back(f);
      buffers_.emplace_back();
    }
    counts_.assign(files_.size(), 0);
  }

  std::size_t size() const { return files_.size(); }
  std::size_t first_vertex(std::size_t b) const { return std::min(b * width_, n_); }
  std::size_t bucket_of(std::uint32_t v) const { return v / width_; }
  std::size_t entries(std::size_t b) const { return counts_[b]; }
  /// Bytes written to the files.
  std::uint64_t bytes() const { return bytes_; }

  /// Stores a valid row whose vertices in increasing order are `sorted`.
  void add(std::uint64_t row, const std::array<std::uint32_t, K>& encoded, const std::array<std::uint32_t, K>& sorted) {
    const std::size_t b0 = bucket_of(sorted[0]), b1 = bucket_of(sorted[1]);
    put(b0, {row, encoded});
    if (b1 != b0) put(b1, {row, encoded});
  }

  /// Writes what is buffered; the files are then read with for_each.
  void finish() {
    for (std::size_t b = 0; b < files_.size(); ++b) flush(b);
    std::vector<std::vector<Entry>>().swap(buffers_);
  }

  /// Calls f(std::span<const Entry>) over bucket b's entries, `chunk` at a time.
  template <class F>
  void for_each(std::size_t b, std::vector<Entry>& chunk, F&& f) const {
    std::FILE* file = files_[b].get();
    if (std::fseek(file, 0, SEEK_SET) != 0) fail("cannot rewind a temporary file");
    for (std::uint64_t left = counts_[b]; left > 0;) {
      const std::size_t k = static_cast<std::size_t>(std::min<std::uint64_t>(left, chunk.size()));
      if (std::fread(chunk.data(), sizeof(Entry), k, file) != k) fail("cannot read back a temporary file");
      f(std::span<const Entry>(chunk.data(), k));
      left -= k;
    }
  }

 private:
  struct Closer {
    void operator()(std::FILE* f) const { std::fclose(f); }
  };

  [[noreturn]] void fail(const std::string& what) const {
    throw std::runtime_error("certify: " + what + " in " + directory_ + ": " + std::strerror(errno));
  }
  void put(std::size_t b, const Entry& e) {
    auto& buffer = buffers_[b];
    if (buffer.capacity() == 0) buffer.reserve(buffer_entries_);
    buffer.push_back(e);
    if (buffer.size() == buffer_entries_) flush(b);
  }
  void flush(std::size_t b) {
    auto& buffer = buffers_[b];
    if (buffer.empty()) return;
    if (std::fwrite(buffer.data(), sizeof(Entry), buffer.size(), files_[b].get()) != buffer.size() ||
        std::fflush(files_[b].get()) != 0)
      fail("cannot write a temporary file (is the disk full? TMPDIR chooses the directory)");
    counts_[b] += buffer.size();
    bytes_ += buffer.size() * sizeof(Entry);
    buffer.clear();
  }

  std::size_t width_, n_, buffer_entries_;
  std::string directory_;
  std::vector<std::unique_ptr<std::FILE, Closer>> files_;
  std::vector<std::vector<Entry>> buffers_;
  std::vector<std::uint64_t> counts_;
  std::uint64_t bytes_ = 0;
};

}  // namespace dewall::certify::detail
