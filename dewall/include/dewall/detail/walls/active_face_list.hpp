// Active_face_list: the paper's AFL, a set of oriented faces keyed by their
// sorted vertex indices, with the Update rule (insert if absent, delete if
// present). Open addressing with linear probing and tombstones; a pending
// stack gives the faces in insertion order without scanning the table.
#pragma once

#include <cstdint>
#include <vector>

#include "dewall/detail/walls/face.hpp"

namespace dewall::detail {

template <int D>
class Active_face_list {
 public:
  bool empty() const { return live_ == 0; }

  /// The paper's Update: a face seen for the second time is closed (it has a
  /// simplex on each side) and leaves the list; otherwise it joins it.
  void update(const Face<D>& f) {
    const Face<D> key = face_key<D>(f);
    std::uint32_t order = 0;  // f[i] = key[(order >> (3i)) & 7]: the orientation, kept in 3 bits per vertex
    for (int i = 0; i < D; ++i)
      for (int j = 0; j < D; ++j)
        if (key[j] == f[i]) order |= static_cast<std::uint32_t>(j) << (3 * i);
    if (slots_.empty() || 2 * (used_ + 1) > slots_.size()) rehash();
    std::size_t i = face_hash<D>(key) & mask_;
    std::size_t tomb = npos;
    for (;; i = (i + 1) & mask_) {
      Slot& s = slots_[i];
      if (s.state == EMPTY) break;
      if (s.state == TOMB) {
        if (tomb == npos) tomb = i;
      } else if (same(s.key, key)) {
        s.state = TOMB;
        --live_;
        return;
      }
    }
    if (tomb == npos) {
      tomb = i;
      ++used_;
    }
    slots_[tomb] = Slot{key, order, FULL};
    ++live_;
    pending_.push_back(key);
  }

  /// Removes and returns some active face (oriented as inserted). \pre !empty().
  Face<D> pop() {
    for (;;) {
      const Face<D> key = pending_.back();
      pending_.pop_back();
      std::size_t i = face_hash<D>(key) & mask_;
      for (;; i = (i + 1) & mask_) {
        Slot& s = slots_[i];
        if (s.state == EMPTY) break;  // closed since it was pushed
        if (s.state == FULL && same(s.key, key)) {
          s.state = TOMB;
          --live_;
          Face<D> f;
          for (int v = 0; v < D; ++v) f[v] = key[(s.order >> (3 * v)) & 7];
          return f;
        }
      }
    }
  }

 private:
  enum State : std::uint8_t { EMPTY, TOMB, FULL };
  // 16 bytes in 3D (the table is probed at random: its size is its cost).
  struct Slot {
    Face<D> key{};
    std::uint32_t order : 24 = 0;
    State state : 8 = EMPTY;
  };
  static_assert(3 * D <= 24);
  // Element by element: std::array's == calls memcmp here.
  static bool same(const Face<D>& a, const Face<D>& b) {
    for (int i = 0; i < D; ++i)
      if (a[i] != b[i]) return false;
    return true;
  }
  static constexpr std::size_t npos = ~std::size_t{0};

  void rehash() {
    std::vector<Slot> old;
    old.swap(slots_);
    std::size_t capacity = 64;
    while (capacity < 4 * (live_ + 1)) capacity *= 2;
    slots_.assign(capacity, Slot{});
    mask_ = capacity - 1;
    used_ = live_;
    for (const Slot& s : old) {
      if (s.state != FULL) continue;
      std::size_t i = face_hash<D>(s.key) & mask_;
      while (slots_[i].state != EMPTY) i = (i + 1) & mask_;
      slots_[i] = s;
    }
  }

  std::vector<Slot> slots_;
  std::vector<Face<D>> pending_;  // keys; may hold closed faces, skipped by pop()
  std::size_t mask_ = 0, used_ = 0, live_ = 0;
};

}  // namespace dewall::detail
