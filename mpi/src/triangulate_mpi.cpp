// dewall::mpi::triangulate (triangulate.hpp): the Delaunay triangulation of
// points distributed over MPI ranks, the same simplices as CGAL's on one
// machine for every number of ranks.
//
// Steps:
//  1. Checks: a non-finite coordinate on any rank is an error on every rank.
//  2. Decomposition by DeWall's top walls (wall.hpp, split.hpp): a node of the
//     recursion is a range of ranks; it is cut on axis depth % D at the k-th
//     smallest coordinate of its points (k = n·R1/R for R ranks split into
//     R1 = ⌊R/2⌋ and R − R1: the median, choose_split's, when R is a power of
//     two), side 1 strictly below the value, or at or below it when nothing is
//     below, and the next axis when all its points share the coordinate. The
//     k-th value is found exactly by a radix selection on the doubles' bits,
//     8 bits per MPI_Allreduce of the histograms of every node of a level.
//     The points then move to their block's rank (MPI_Alltoallv).
//  3. Duplicates: the cuts compare coordinates only, so equal points land in
//     one block; there the smallest global index is kept (the single-machine
//     rule). Then too few distinct points, or points not spanning E^D (each
//     block's affine basis, gathered, ranked exactly over GMP), are errors on
//     every rank.
//  4. Halo rounds. S = the block; first, the points of other blocks within a
//     few spacings of the block's box (a guess, for speed only). Then, until
//     a round brings no rank a new point: build DT(S) with the library's
//     incremental engine (later rounds insert their new points into it); for
//     each cell incident to a block point, not yet verified, that may hold
//     another block's point (found by a walk: verification_queries), ask the
//     ranks whose block may hold a point that decides it:
//     a finite cell: the ranks whose block box may meet the closed ball
//       (Simplex_sphere's box, proven to contain it; Ball_box::may_meet) —
//       they answer with the points of theirs that may lie in the ball not
//       sent before, or, when there are more than a limit (8, doubling each
//       round), with that many nearest the centre, the answer then marked
//       incomplete; a cell is verified once every answer about it was
//       complete (until then it is asked about again while it stands);
//     an infinite cell (a hull facet f of S): the ranks whose block box has a
//       corner strictly beyond f (exact orientation) — they answer with one
//       point strictly beyond f (exact orientation), if they have one.
//     The answers join S (each point sent to a rank once).
//  5. Each rank keeps the finite cells of DT(S) whose smallest global vertex
//     index lies in its block.
// With regions (Options::region_points), steps 4 and 5 run once per region of
// the block, all ranks in step: the block is cut into regions by step 2's
// cuts (on the rank alone), and for region Q, S starts as Q; "other blocks"
// are then the other ranks' blocks and this rank's other regions (asked
// through the same exchange, the rank answering itself). The argument below
// holds with Q for the block: Q is a cell of DeWall's cuts, as a block is.
//
// Why the result is DT(P) of all points P, each simplex on exactly one rank.
// Under CGAL's perturbation (only the lifting is perturbed, lexicographically
// by coordinates — the same decision for a point on every rank, whatever its
// index) the lifted points are in general position, so a full-dimensional
// simplex σ ⊆ X is a cell of DT(X) iff every point of X \ σ lies outside σ's
// perturbed sphere. Hence (a) σ ∈ DT(P), σ ⊆ S ⊆ P ⇒ σ ∈ DT(S), and (b)
// σ ∈ DT(S) and no point of P \ S in σ's closed ball ⇒ σ ∈ DT(P) (a point
// outside the closed ball is outside the perturbed sphere: the perturbation
// decides only ties). At the end, for each block point v:
//  * every finite cell of DT(S) at v is verified, or was never reached by
//    the walk of verification_queries (then no point of P \ S is in conflict
//    with it: see there): a verified cell's closed ball holds no point of
//    P \ S (a rank not asked has none in it — its box misses the ball; each
//    rank asked, in a complete answer, sent all it has there, now in S; S only
//    grows), so by (b) it is a cell of DT(P);
//  * no point of P lies strictly beyond a hull facet of S at v: the walk
//    tests every infinite cell; a rank whose box lies on the closed inner
//    side (exact, at its corners) has none beyond, and a rank asked answers
//    with a point beyond when it has one, which then joins S — and a point
//    of S is never strictly beyond a hull facet of S. So near v,
//    conv(P) lies on the inner side of each hull facet of S at v, and equals
//    conv(S) near v.
// The cells of DT(S) at v cover a neighbourhood of v in conv(S) = conv(P)
// there; they are cells of DT(P), whose cells have disjoint interiors, so DT(P)
// has no other cell at v: the star of v in DT(S) is its star in DT(P).
// Each simplex of DT(P) has one smallest vertex index, in one block: it is
// written by exactly that rank. Duplicates: a later copy lies in its first
// occurrence's block and was dropped there (step 3), so it is in no S.
// Termination: S grows in every round but the last, and P is finite. Floating
// point only chooses whom to ask and what to send (boxes proven to contain the
// balls, exact orientations for the half-spaces); every cell is decided by the
// engine's exact predicates.
#include "dewall/mpi/triangulate.hpp"

#include <algorithm>
#include <bit>
#include <climits>
#include <cmath>
#include <cstring>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string>
#include <unordered_set>
#include <vector>

#include <tbb/task_arena.h>

#include "dewall/detail/incremental/incremental_delaunay.hpp"
#include "dewall/detail/common/input.hpp"
#include "dewall/kernel/point.hpp"
#include "dewall/detail/walls/simplex_sphere.hpp"
#include "dewall/kernel/filtered_predicate.hpp"  // refuses to build under unsafe flags
#include "dewall/kernel/first_occurrence.hpp"
#include "dewall/kernel/orientation.hpp"
#include "dewall/mpi/collective_error.hpp"

namespace dewall::mpi {
namespace {

using detail::Coords;
using detail::Index;

__extension__ using U128 = unsigned __int128;  // n·r / R without overflow

struct Comm {
  MPI_Comm comm;
  int rank = 0, size = 1;
};

std::uint64_t allreduce_sum(const Comm& c, std::uint64_t x) {
  std::uint64_t r = 0;
  MPI_Allreduce(&x, &r, 1, MPI_UINT64_T, MPI_SUM, c.comm);
  return r;
}

/// A point with its global index, as it travels between ranks.
template <int D>
struct Record {
  std::uint64_t gid;
  Coords<D> x;
};

/// Collective: sends send[displacement q … + count[q]) to rank q (the parts
/// in rank order); returns what each rank sent here, concatenated in rank
/// order. T is trivially copyable. No copy beyond MPI's own.
template <class T>
std::vector<T> alltoall(const Comm& c, const std::vector<T>& send, const std::vector<std::uint64_t>& count) {
  std::vector<int> send_counts(c.size), recv_counts(c.size), send_displs(c.size), recv_displs(c.size);
  std::uint64_t send_total = 0;
  bool too_big = false;
  for (int q = 0; q < c.size; ++q) {
    const std::uint64_t bytes = count[q] * sizeof(T);
    too_big |= bytes > INT_MAX;
    send_counts[q] = static_cast<int>(std::min<std::uint64_t>(bytes, INT_MAX));
    send_total += bytes;
  }
  too_big |= send_total > INT_MAX;
  MPI_Alltoall(send_counts.data(), 1, MPI_INT, recv_counts.data(), 1, MPI_INT, c.comm);
  std::uint64_t recv_total = 0;
  for (int q = 0; q < c.size; ++q) recv_total += static_cast<std::uint64_t>(recv_counts[q]);
  too_big |= recv_total > INT_MAX;
  int any_too_big = too_big ? 1 : 0, flag = 0;
  MPI_Allreduce(&any_too_big, &flag, 1, MPI_INT, MPI_MAX, c.comm);
  if (flag)  // every rank throws alike
    throw std::runtime_error("dewall-mpi: one exchange needs more than 2 GiB per rank (MPI int counts); use more ranks");
  for (int q = 0, at = 0; q < c.size; ++q) {
    send_displs[q] = at;
    at += send_counts[q];
  }
  for (int q = 0, at = 0; q < c.size; ++q) {
    recv_displs[q] = at;
    at += recv_counts[q];
  }
  std::vector<T> result(recv_total / sizeof(T));
  MPI_Alltoallv(send.data(), send_counts.data(), send_displs.data(), MPI_BYTE, result.data(), recv_counts.data(),
                recv_displs.data(), MPI_BYTE, c.comm);
  return result;
}

/// As above, out[q] to rank q (the small exchanges of the halo rounds).
template <class T>
std::vector<T> alltoall(const Comm& c, const std::vector<std::vector<T>>& out) {
  std::vector<T> send;
  std::vector<std::uint64_t> count(c.size);
  for (int q = 0; q < c.size; ++q) {
    send.insert(send.end(), out[q].begin(), out[q].end());
    count[q] = out[q].size();
  }
  return alltoall(c, send, count);
}

/// The doubles' order as unsigned integers (−0 and +0 one key; no NaN).
std::uint64_t order_key(double x) {
  if (x == 0) x = 0.0;
  const auto b = std::bit_cast<std::uint64_t>(x);
  return (b >> 63) ? ~b : b | (std::uint64_t{1} << 63);
}
double from_order_key(std::uint64_t k) {
  return std::bit_cast<double>((k >> 63) ? k & ~(std::uint64_t{1} << 63) : ~k);
}

/// Step 2: the rank each local point goes to.
template <int D>
std::vector<int> decompose(const Comm& c, std::span<const kernel::Point_d<D>> points) {
  struct Node {
    int r0, r1;
    std::uint64_t count;
  };
  const std::size_t n = points.size();
  std::vector<std::uint32_t> node(n, 0);
  std::vector<Node> nodes{{0, c.size, allreduce_sum(c, n)}};
  for (int depth = 0;; ++depth) {
    const std::size_t m = nodes.size();
    bool any_split = false;
    for (const Node& nd : nodes) any_split |= nd.r1 - nd.r0 > 1;
    if (!any_split) break;
    // Per node: the cut, or everything to side 1 (one rank, no points, or all points equal).
    std::vector<char> decided(m, 1), all_side1(m, 1), inclusive(m, 0);
    std::vector<int> axis(m, 0);
    std::vector<double> value(m, 0);
    std::vector<std::uint64_t> k(m, 0), side1(m, 0);
    for (std::size_t j = 0; j < m; ++j) {
      const Node& nd = nodes[j];
      if (nd.r1 - nd.r0 > 1 && nd.count > 0) {
        decided[j] = 0;
        const int r = nd.r1 - nd.r0;
        k[j] = static_cast<std::uint64_t>(static_cast<U128>(nd.count) * static_cast<unsigned>(r / 2) /
                                          static_cast<unsigned>(r));
      }
      side1[j] = nd.count;
    }
    for (int t = 0; t < D; ++t) {
      bool open = false;
      for (std::size_t j = 0; j < m; ++j) open |= !decided[j];
      if (!open) break;  // the same on every rank: decided comes from reduced counts
      const int ax = (depth + t) % D;
      // Radix selection of the k-th smallest key, 8 bits at a time.
      std::vector<std::uint64_t> prefix(m, 0), less(m, 0), equal(m, 0), hist(m * 256), total(m * 256);
      for (int digit = 0; digit < 8; ++digit) {
        const int shift = 56 - 8 * digit;
        std::fill(hist.begin(), hist.end(), 0);
        for (std::size_t i = 0; i < n; ++i) {
          const std::uint32_t j = node[i];
          if (decided[j]) continue;
          const std::uint64_t key = order_key(points[i][ax]);
          if (digit > 0 && ((key ^ prefix[j]) >> (shift + 8)) != 0) continue;
          ++hist[j * 256 + ((key >> shift) & 255)];
        }
        MPI_Allreduce(hist.data(), total.data(), static_cast<int>(hist.size()), MPI_UINT64_T, MPI_SUM, c.comm);
        for (std::size_t j = 0; j < m; ++j) {
          if (decided[j]) continue;
          std::uint64_t cum = less[j];
          for (std::uint64_t b = 0; b < 256; ++b) {
            const std::uint64_t h = total[j * 256 + b];
            if (cum + h > k[j]) {
              prefix[j] |= b << shift;
              less[j] = cum;
              equal[j] = h;
              break;
            }
            cum += h;
          }
        }
      }
      for (std::size_t j = 0; j < m; ++j) {
        if (decided[j]) continue;
        // As choose_split: side 1 below the value, or at or below it when nothing is below.
        const bool incl = less[j] == 0;
        const std::uint64_t s1 = incl ? equal[j] : less[j];
        if (s1 < nodes[j].count) {
          decided[j] = 1;
          all_side1[j] = 0;
          axis[j] = ax;
          value[j] = from_order_key(prefix[j]);
          inclusive[j] = incl;
          side1[j] = s1;
        }
      }
    }
    // Children: side 1 to the first ⌊R/2⌋ ranks, side 2 to the others.
    std::vector<Node> next;
    std::vector<std::uint32_t> first_child(m);
    for (std::size_t j = 0; j < m; ++j) {
      const Node& nd = nodes[j];
      first_child[j] = static_cast<std::uint32_t>(next.size());
      if (nd.r1 - nd.r0 == 1) {
        next.push_back(nd);
        continue;
      }
      const int mid = nd.r0 + (nd.r1 - nd.r0) / 2;
      next.push_back({nd.r0, mid, side1[j]});
      next.push_back({mid, nd.r1, nd.count - side1[j]});
    }
    for (std::size_t i = 0; i < n; ++i) {
      const std::uint32_t j = node[i];
      const Node& nd = nodes[j];
      bool second = false;
      if (nd.r1 - nd.r0 > 1 && !all_side1[j]) {
        const double x = points[i][axis[j]];
        second = !(inclusive[j] ? x <= value[j] : x < value[j]);
      }
      node[i] = first_child[j] + (second ? 1 : 0);
    }
    nodes = std::move(next);
  }
  std::vector<int> rank_of(n);
  for (std::size_t i = 0; i < n; ++i) rank_of[i] = nodes[node[i]].r0;
  return rank_of;
}

/// A box of points; empty when lo > hi.
template <int D>
struct Box {
  Coords<D> lo, hi;
  static Box empty() {
    Box b;
    b.lo.fill(std::numeric_limits<double>::infinity());
    b.hi.fill(-std::numeric_limits<double>::infinity());
    return b;
  }
  bool is_empty() const { return lo[0] > hi[0]; }
  void add(const Coords<D>& x) {
    for (int j = 0; j < D; ++j) {
      lo[j] = std::min(lo[j], x[j]);
      hi[j] = std::max(hi[j], x[j]);
    }
  }
  bool meets(const Box& b) const {
    for (int j = 0; j < D; ++j)
      if (b.hi[j] < lo[j] || hi[j] < b.lo[j]) return false;
    return true;
  }
  bool holds(const Coords<D>& x) const {
    for (int j = 0; j < D; ++j)
      if (!(lo[j] <= x[j] && x[j] <= hi[j])) return false;
    return true;
  }
};

/// Whether some corner of `b` lies strictly beyond the facet of `cell` opposite
/// its slot `slot` (the cell with that vertex replaced by the corner positively
/// oriented: exact). False only when the whole box lies on the closed inner side.
template <int D>
bool box_reaches_beyond(const Box<D>& b, std::array<kernel::Point_d<D>, D + 1> cell, int slot) {
  kernel::Orientation_points<D> refs;
  for (int i = 0; i <= D; ++i) refs[i] = &cell[i];
  for (unsigned corner = 0; corner < (1u << D); ++corner) {
    for (int j = 0; j < D; ++j) cell[slot][j] = (corner >> j & 1u) ? b.hi[j] : b.lo[j];
    if (kernel::orientation_d<D>(refs) == kernel::POSITIVE) return true;
  }
  return false;
}

/// A question to another rank about its block.
template <int D>
struct Query {
  enum Kind : std::int32_t { box = 0, ball = 1, facet = 2 };
  static constexpr int payload = std::max(4 * D + 1, (D + 1) * D);
  std::int32_t kind = box;
  std::int32_t slot = 0;   // facet: the position of the infinite vertex
  std::int32_t limit = 0;  // ball: answer with at most this many points (the nearest the centre)
  std::array<double, payload> d{};
};

/// A kd-tree over a block's points, for answering queries.
template <int D>
class Block_index {
 public:
  /// Indexes points[0, count); `points` may grow afterwards (it is read through the vector).
  void build(const std::vector<kernel::Point_d<D>>& points, std::size_t count) {
    points_ = &points;
    order_.resize(count);
    for (std::size_t i = 0; i < order_.size(); ++i) order_[i] = static_cast<std::uint32_t>(i);
    nodes_.clear();
    if (count > 0) split(0, static_cast<std::uint32_t>(count));
  }
  /// Calls visit(i) for each point i in a node for which node_may(box) holds.
  template <class NodeTest, class Visit>
  void for_each(NodeTest&& node_may, Visit&& visit) const {
    if (nodes_.empty()) return;
    std::vector<std::uint32_t> stack{0};
    while (!stack.empty()) {
      const Node& nd = nodes_[stack.back()];
      stack.pop_back();
      if (!node_may(nd.box)) continue;
      if (nd.left < 0) {
        for (std::uint32_t k = nd.begin; k < nd.end; ++k) visit(order_[k]);
      } else {
        stack.push_back(static_cast<std::uint32_t>(nd.left));
        stack.push_back(static_cast<std::uint32_t>(nd.right));
      }
    }
  }

 private:
  static constexpr std::uint32_t leaf_size = 16;
  struct Node {
    Box<D> box;
    std::uint32_t begin, end;
    std::int32_t left = -1, right = -1;
  };
  std::int32_t split(std::uint32_t begin, std::uint32_t end) {
    const auto id = static_cast<std::int32_t>(nodes_.size());
    nodes_.push_back({Box<D>::empty(), begin, end});
    Box<D> box = Box<D>::empty();
    for (std::uint32_t k = begin; k < end; ++k) box.add((*points_)[order_[k]].x);
    nodes_[id].box = box;
    if (end - begin > leaf_size) {
      int axis = 0;
      for (int j = 1; j < D; ++j)
        if (box.hi[j] - box.lo[j] > box.hi[axis] - box.lo[axis]) axis = j;
      const std::uint32_t mid = begin + (end - begin) / 2;
      std::nth_element(order_.begin() + begin, order_.begin() + mid, order_.begin() + end,
                       [&](std::uint32_t a, std::uint32_t b) { return (*points_)[a][axis] < (*points_)[b][axis]; });
      const std::int32_t l = split(begin, mid);
      const std::int32_t r = split(mid, end);
      nodes_[id].left = l;
      nodes_[id].right = r;
    }
    return id;
  }
  const std::vector<kernel::Point_d<D>>* points_ = nullptr;
  std::vector<std::uint32_t> order_;
  std::vector<Node> nodes_;
};

/// The cells already verified, by their sorted global vertex indices (a hull
/// facet: its D indices and the largest value for the infinite vertex).
template <int D>
struct Key_hash {
  std::size_t operator()(const Global_simplex<D>& k) const {
    std::uint64_t h = 0;
    for (const std::uint64_t x : k) h = (h ^ x) * 0x9e3779b97f4a7c15ull;
    return static_cast<std::size_t>(h ^ (h >> 29));
  }
};

template <int D>
class Rank_triangulation {
 public:
  Rank_triangulation(const Comm& c, std::vector<Record<D>> block, const Options& options, Statistics& stats)
      : c_(c), options_(options), stats_(stats) {
    nb_ = block.size();
    points_.reserve(nb_);
    gid_.reserve(nb_);
    for (const Record<D>& r : block) {
      points_.push_back(kernel::Point_d<D>{r.x});
      gid_.push_back(r.gid);
    }
    std::vector<Record<D>>().swap(block);
    Box<D> mine = Box<D>::empty();
    for (const auto& p : points_) mine.add(p.x);
    boxes_.resize(c.size);
    MPI_Allgather(&mine, sizeof(Box<D>), MPI_BYTE, boxes_.data(), sizeof(Box<D>), MPI_BYTE, c.comm);
    sent_.resize(c.size);
    pending_.resize(c.size);
    others_.resize(c.size);
    all_blocks_ = detail::Box<D>{Box<D>::empty().lo, Box<D>::empty().hi};
    for (const Box<D>& b : boxes_)
      for (int j = 0; j < D && !b.is_empty(); ++j) {
        all_blocks_.lo[j] = std::min(all_blocks_.lo[j], b.lo[j]);
        all_blocks_.hi[j] = std::max(all_blocks_.hi[j], b.hi[j]);
      }
    make_regions();
  }

  /// Step 4 and 5, region after region (one region: the block).
  void run(const Simplex_sink<D>& sink) {
    const double t_index = MPI_Wtime();
    index_.build(points_, nb_);
    stats_.index_seconds = MPI_Wtime() - t_index;
    stats_.regions = region_start_.size() - 1;
    for (std::size_t r = 0; r + 1 < region_start_.size(); ++r) run_region(r, sink);
  }

 private:
  /// With Options::region_points: the block cut into regions by the cuts of
  /// step 2 (decompose, on this rank alone), the points reordered region by
  /// region. Regions are cells of DeWall's cuts, so what verification_queries'
  /// walk relies on (a cell with all its vertices in the region holds no
  /// point outside it) holds for them as for blocks. Every rank makes the same
  /// number of regions (the rounds are collective), some maybe empty.
  void make_regions() {
    std::uint64_t largest = 0, mine = nb_;
    MPI_Allreduce(&mine, &largest, 1, MPI_UINT64_T, MPI_MAX, c_.comm);
    std::uint64_t regions = 1;
    if (options_.region_points > 0)
      regions = std::max<std::uint64_t>(1, (largest + options_.region_points - 1) / options_.region_points);
    if (regions > static_cast<std::uint64_t>(INT_MAX)) throw std::length_error("dewall::mpi: too many regions");
    region_start_.assign(regions + 1, 0);
    region_box_.assign(regions, Box<D>::empty());
    if (regions == 1) {
      region_start_[1] = nb_;
      region_box_[0] = boxes_[c_.rank];
      return;
    }
    std::vector<int> region_of;
    run_collectively(c_.comm, [&] {
      region_of = decompose<D>(Comm{MPI_COMM_SELF, 0, static_cast<int>(regions)}, points_);
    });
    for (const int r : region_of) ++region_start_[static_cast<std::size_t>(r) + 1];
    for (std::size_t r = 1; r <= regions; ++r) region_start_[r] += region_start_[r - 1];
    std::vector<std::uint64_t> at(region_start_.begin(), region_start_.end() - 1);
    {
      std::vector<kernel::Point_d<D>> p(nb_);
      for (std::size_t i = 0; i < nb_; ++i) p[at[region_of[i]]++] = points_[i];
      points_.swap(p);
    }
    std::copy(region_start_.begin(), region_start_.end() - 1, at.begin());
    {
      std::vector<std::uint64_t> g(nb_);
      for (std::size_t i = 0; i < nb_; ++i) g[at[region_of[i]]++] = gid_[i];
      gid_.swap(g);
    }
    for (std::size_t r = 0; r < regions; ++r)
      for (std::size_t i = region_start_[r]; i < region_start_[r + 1]; ++i) region_box_[r].add(points_[i].x);
  }

  /// Region r: S = its points (points_[lo_, hi_)) and the halo (points_[nb_,
  /// …)); the rounds until no rank receives a point, then the owned cells to
  /// the sink and the region's state freed. "Other blocks" below are, for
  /// this rank, its other regions: it asks itself about them as it asks the
  /// other ranks (through the same exchange), its region's own points
  /// counting as sent.
  void run_region(std::size_t region, const Simplex_sink<D>& sink) {
    lo_ = region_start_[region];
    hi_ = region_start_[region + 1];
    const bool last = region + 2 == region_start_.size();
    for (int r = 0; r < c_.size; ++r) {
      others_[r].clear();
      if (r != c_.rank && !boxes_[r].is_empty()) others_[r].push_back(boxes_[r]);
      if (!sent_[r].empty()) std::fill(sent_[r].begin(), sent_[r].end(), 0);
    }
    for (std::size_t j = 0; j + 1 < region_start_.size(); ++j)
      if (j != region && !region_box_[j].is_empty()) others_[c_.rank].push_back(region_box_[j]);
    if (!others_[c_.rank].empty()) {
      sent_[c_.rank].assign(nb_, 0);
      std::fill(sent_[c_.rank].begin() + static_cast<std::ptrdiff_t>(lo_), sent_[c_.rank].begin() + static_cast<std::ptrdiff_t>(hi_), 1);
    }
    spanning_ = false;
    in_dt_ = 0;
    std::vector<std::vector<Query<D>>> queries(c_.size);
    run_collectively(c_.comm, [&] { seed_queries(region, queries); });
    bool verifying = false;
    detail::Incremental_delaunay<D> dt;
    std::size_t rounds = 0;
    for (;;) {
      const double t0 = MPI_Wtime();
      const std::uint64_t fresh = allreduce_sum(c_, halo_round(queries));
      stats_.halo_seconds += MPI_Wtime() - t0;
      ++stats_.rounds;
      ++rounds;
      if (verifying && fresh == 0) break;
      verifying = true;
      const double t1 = MPI_Wtime();
      run_collectively(c_.comm, [&] {
        for (auto& q : queries) q.clear();
        if (lo_ == hi_) return;
        // S's point k: the region's points, then the halo; the engine keeps
        // the position in points_ as the point's id.
        const auto slot = [&](std::size_t k) { return k < hi_ - lo_ ? lo_ + k : nb_ + (k - (hi_ - lo_)); };
        // The first triangulation of S is built; the points of later rounds
        // are inserted into it (the static filter made for the box of all
        // blocks, which holds every point a round can bring).
        bool built = spanning_;
        // One thread per rank: the engine's parallel parts (zoned insertion,
        // the order's keys) would start threads beside the other ranks' and,
        // on one thread, zones only cost.
        tbb::task_arena one_thread(1);
        one_thread.execute([&] {
          if (spanning_) {
            dt.insert_more(
                points_.size() - in_dt_, [&](std::size_t k) -> const Coords<D>& { return points_[in_dt_ + k].x; },
                [&](std::size_t k) { return in_dt_ + k; });
          } else {
            const std::size_t count = (hi_ - lo_) + (points_.size() - nb_);
            // Zones off: this rank runs on one thread, where zones only cost.
            detail::Incremental_tuning no_zones;
            no_zones.zoned_insertion_threshold = std::numeric_limits<std::size_t>::max();
            dt = detail::Incremental_delaunay<D>(no_zones);
            dt.reserve(detail::Incremental_delaunay<D>::expected_cells(count + count / 8));
            built = dt.build(count, [&](std::size_t k) -> const Coords<D>& { return points_[slot(k)].x; }, slot,
                             &all_blocks_);
          }
        });
        ++stats_.builds;
        in_dt_ = points_.size();
        stats_.build_seconds += MPI_Wtime() - t1;
        if (!built) {
          // S does not span E^D (a flat region): ask for everything; P spans E^D.
          Query<D> all;
          for (int j = 0; j < D; ++j) {
            all.d[j] = -std::numeric_limits<double>::infinity();
            all.d[D + j] = std::numeric_limits<double>::infinity();
          }
          for (int q = 0; q < c_.size; ++q)
            if (!others_[q].empty()) queries[q].push_back(all);
          return;
        }
        spanning_ = true;
        const double t2 = MPI_Wtime();
        verification_queries(dt, queries, rounds);
        stats_.verify_seconds += MPI_Wtime() - t2;
      });
    }
    // Step 5, outside dewall::mpi's collective calls (the sink may make its
    // own): the owned cells, counted, then handed over in batches, in slot
    // order (the same on every run with R ranks).
    const double t3 = MPI_Wtime();
    decltype(verified_)().swap(verified_);
    for (auto& p : pending_) {
      p.clear();
      p.shrink_to_fit();
    }
    if (last) {
      // What answered questions is done with: freed before the keys and the
      // sink's buffers are made (the rank's memory peak without regions).
      index_ = Block_index<D>();
      decltype(sent_)().swap(sent_);
      decltype(points_)().swap(points_);
    } else {
      points_.resize(nb_);  // the region's halo
      points_.shrink_to_fit();
    }
    run_collectively(c_.comm, [&] { hand_over(dt, sink); });
    gid_.resize(nb_);
    if (!last) gid_.shrink_to_fit();
    stats_.finish_seconds += MPI_Wtime() - t3;
  }

  /// The cells of dt owned by the region (those whose smallest global index
  /// is one of its points) to the sink.
  void hand_over(const detail::Incremental_delaunay<D>& dt, const Simplex_sink<D>& sink) {
    // By vertex id (the engine's insertion order, which its cells follow):
    // 2·global index + 1 for a halo point, so that the smallest key of a
    // cell is its smallest global index, and its low bit says whether that
    // vertex lies outside the region.
    const bool any = lo_ < hi_ && spanning_;
    std::vector<std::uint64_t> key(any ? dt.vertices() : 0);
    for (std::size_t v = 0; v < key.size(); ++v) {
      const Index local = dt.input_index(static_cast<Index>(v));
      key[v] = gid_[local] << 1 | (local < nb_ ? 0 : 1);
    }
    const auto owned = [&](std::size_t c) {
      if (dt.is_free(c) || dt.is_infinite(c)) return false;
      std::uint64_t smallest = std::numeric_limits<std::uint64_t>::max();
      for (const Index v : dt.cell(c)) smallest = std::min(smallest, key[v]);
      return (smallest & 1) == 0;  // owned by the region of its smallest vertex
    };
    std::uint64_t count = 0;
    if (any)
      for (std::size_t c = 0; c < dt.slots(); ++c) count += owned(c) ? 1 : 0;
    if (sink.start) sink.start(count);
    constexpr std::size_t batch_size = 4096;
    std::vector<Global_simplex<D>> batch;
    batch.reserve(batch_size);
    for (std::size_t c = 0; any && c < dt.slots(); ++c) {
      if (!owned(c)) continue;
      const auto& cell = dt.cell(c);
      Global_simplex<D> s;
      for (int i = 0; i <= D; ++i) s[i] = key[cell[i]] >> 1;
      // Canonical form: the indices sorted, then the last two swapped when the
      // sort was an odd permutation (the orientation is kept).
      bool odd = false;
      for (int i = 0; i <= D; ++i)
        for (int j = i + 1; j <= D; ++j) odd ^= s[j] < s[i];
      std::sort(s.begin(), s.end());
      if (odd) std::swap(s[D - 1], s[D]);
      batch.push_back(s);
      if (batch.size() == batch_size) {
        sink.take(batch);
        batch.clear();
      }
    }
    if (!batch.empty()) sink.take(batch);
    stats_.simplices += count;
  }

  /// Whether one of the boxes that hold rank r's points outside S passes `test`.
  template <class Test>
  bool may_have(int r, Test&& test) const {
    for (const Box<D>& b : others_[r])
      if (test(b)) return true;
    return false;
  }

  /// The first halo guess: the points within seed_spacings mean spacings of the region's box.
  void seed_queries(std::size_t region, std::vector<std::vector<Query<D>>>& queries) {
    if (lo_ == hi_ || !(options_.seed_spacings > 0)) return;
    const Box<D>& mine = region_box_[region];
    double extent = 0;
    for (int j = 0; j < D; ++j) extent = std::max(extent, mine.hi[j] - mine.lo[j]);
    const double margin = options_.seed_spacings * extent / std::pow(static_cast<double>(hi_ - lo_), 1.0 / D);
    Box<D> grown = mine;
    for (int j = 0; j < D; ++j) {
      grown.lo[j] -= margin;
      grown.hi[j] += margin;
    }
    Query<D> q;
    q.kind = Query<D>::box;
    for (int j = 0; j < D; ++j) {
      q.d[j] = grown.lo[j];
      q.d[D + j] = grown.hi[j];
    }
    for (int r = 0; r < c_.size; ++r)
      if (may_have(r, [&](const Box<D>& b) { return b.meets(grown); })) queries[r].push_back(q);
  }

  /// Step 4's questions for the cells at the block not yet verified.
  ///
  /// Which cells can hold a point q of another block in their perturbed
  /// sphere (be in conflict with q)? Those cells form q's cavity, which is
  /// connected (Bowyer–Watson; the engine's breadth-first search relies on
  /// it), and it holds the cells whose closure holds q (strictly inside their
  /// balls: q is not a vertex) or, for q outside conv(S), infinite cells. No
  /// cell whose vertices are all block points holds q: the block lies on the
  /// other side of a cut from q. So every cavity has a cell with a halo or
  /// infinite vertex, and a walk from those cells that crosses only cells
  /// which may hold another block's point reaches every cell in conflict with
  /// one. The cells it does not reach are cells of DT(P) untested; on 10^6
  /// points it tests the cells near the block's boundary only.
  void verification_queries(const detail::Incremental_delaunay<D>& dt, std::vector<std::vector<Query<D>>>& queries,
                            std::size_t round) {
    constexpr Index infinite = detail::Incremental_delaunay<D>::infinite;
    for (auto& p : pending_) p.clear();
    enum : std::uint8_t { untested = 0, closed = 1, open = 2 };
    std::vector<std::uint8_t> state(dt.slots(), untested);
    std::vector<std::size_t> stack;
    for (std::size_t c = 0; c < dt.slots(); ++c) {
      if (dt.is_free(c)) continue;
      for (const Index v : dt.cell(c))
        if (v == infinite || dt.input_index(v) >= nb_) {
          stack.push_back(c);
          break;
        }
    }
    std::vector<int> ranks;
    while (!stack.empty()) {
      const std::size_t c = stack.back();
      stack.pop_back();
      if (state[c] != untested) continue;
      ranks.clear();
      const auto& cell = dt.cell(c);
      const int slot = dt.infinite_position(c);
      Query<D> q;
      if (slot > D) {
        std::array<const Coords<D>*, D + 1> s;
        for (int i = 0; i <= D; ++i) s[i] = &points_[dt.input_index(cell[i])].x;
        const detail::Simplex_sphere<D> sphere(s);
        const detail::Ball_box<D>& b = sphere.enclosing_box();
        for (int r = 0; r < c_.size; ++r)
          if (may_have(r, [&](const Box<D>& x) { return b.may_meet(x.lo, x.hi); })) ranks.push_back(r);
        q.kind = Query<D>::ball;
        for (int j = 0; j < D; ++j) {
          q.d[j] = b.centre_lo[j];
          q.d[D + j] = b.centre_hi[j];
          q.d[2 * D + j] = b.lo[j];
          q.d[3 * D + j] = b.hi[j];
        }
        q.d[4 * D] = b.bounded ? b.radius2_limit : -1.0;  // negative: not bounded, the ball may be anywhere
      } else {
        std::array<kernel::Point_d<D>, D + 1> f{};
        q.kind = Query<D>::facet;
        q.slot = slot;
        for (int i = 0; i <= D; ++i) {
          if (i == slot) continue;
          f[i] = points_[dt.input_index(cell[i])];
          for (int j = 0; j < D; ++j) q.d[i * D + j] = f[i][j];
        }
        for (int r = 0; r < c_.size; ++r)
          if (may_have(r, [&](const Box<D>& x) { return box_reaches_beyond<D>(x, f, slot); })) ranks.push_back(r);
      }
      if (ranks.empty()) {
        state[c] = closed;  // no other block's point can be in conflict with it
        continue;
      }
      state[c] = open;
      for (int i = 0; i <= D; ++i) stack.push_back(dt.neighbor(c, i));
      // Ask about it when it is at the block and was not asked about before.
      bool at_block = false;
      Global_simplex<D> key;
      for (int i = 0; i <= D; ++i) {
        if (cell[i] == infinite) {
          key[i] = std::numeric_limits<std::uint64_t>::max();
          continue;
        }
        const Index local = dt.input_index(cell[i]);
        at_block |= local < nb_;
        key[i] = gid_[local];
      }
      if (!at_block) continue;
      std::sort(key.begin(), key.end());
      if (verified_.count(key)) continue;
      q.limit = answer_limit(round);
      for (const int r : ranks) {
        queries[r].push_back(q);
        pending_[r].push_back(key);
      }
      stats_.queries_sent += ranks.size();
    }
  }

  /// How many points a ball question asks for: 8 in the first verifying
  /// round, doubling with each round (few rounds even where every ball holds
  /// every point, as on a sphere).
  static std::int32_t answer_limit(std::size_t round) {
    return std::int32_t{8} << std::min<std::size_t>(round, 26);
  }

  /// One exchange of questions and answers; the points received join S, and
  /// the cells asked about whose every answer was complete are verified.
  /// Returns how many points arrived here.
  std::uint64_t halo_round(const std::vector<std::vector<Query<D>>>& queries) {
    const std::vector<Query<D>> asked_flat = alltoall(c_, queries);
    // Who asked what: exchange keeps rank order; recover the sources from the counts.
    std::vector<int> per_source(c_.size), counts(c_.size);
    for (int q = 0; q < c_.size; ++q) counts[q] = static_cast<int>(queries[q].size());
    MPI_Alltoall(counts.data(), 1, MPI_INT, per_source.data(), 1, MPI_INT, c_.comm);
    std::vector<std::vector<Record<D>>> answers(c_.size);
    std::vector<std::vector<std::uint8_t>> complete(c_.size);
    run_collectively(c_.comm, [&] {
      std::size_t at = 0;
      for (int source = 0; source < c_.size; ++source)
        for (int k = 0; k < per_source[source]; ++k)
          complete[source].push_back(answer(source, asked_flat[at++], answers[source]) ? 1 : 0);
    });
    const std::vector<Record<D>> got = alltoall(c_, answers);
    const std::vector<std::uint8_t> done = alltoall(c_, complete);
    // A cell is verified when every rank asked about it sent all it may hold in its ball.
    std::unordered_set<Global_simplex<D>, Key_hash<D>> incomplete;
    std::size_t at = 0;
    for (int r = 0; r < c_.size; ++r) {
      const bool verifying = pending_[r].size() == queries[r].size();
      for (std::size_t k = 0; k < queries[r].size(); ++k, ++at)
        if (verifying && !done[at]) incomplete.insert(pending_[r][k]);
    }
    for (int r = 0; r < c_.size; ++r) {
      if (pending_[r].size() != queries[r].size()) continue;
      for (const Global_simplex<D>& key : pending_[r])
        if (!incomplete.count(key)) verified_.insert(key);
    }
    for (auto& p : pending_) p.clear();
    for (const Record<D>& r : got) {
      points_.push_back(kernel::Point_d<D>{r.x});
      gid_.push_back(r.gid);
    }
    stats_.halo_points += got.size();
    return got.size();
  }

  /// Answers one question of rank `source` about this block; says whether
  /// the answer is complete (every point the question may concern is sent
  /// now or was before).
  bool answer(int source, const Query<D>& q, std::vector<Record<D>>& out) {
    std::vector<char>& sent = sent_[source];
    if (sent.empty()) sent.assign(nb_, 0);
    auto send = [&](std::uint32_t i) {
      sent[i] = 1;
      out.push_back({gid_[i], points_[i].x});
    };
    if (q.kind == Query<D>::box) {
      Box<D> b;
      for (int j = 0; j < D; ++j) {
        b.lo[j] = q.d[j];
        b.hi[j] = q.d[D + j];
      }
      index_.for_each([&](const Box<D>& node) { return node.meets(b); },
                      [&](std::uint32_t i) {
                        if (!sent[i] && b.holds(points_[i].x)) send(i);
                      });
      return true;
    } else if (q.kind == Query<D>::ball) {
      detail::Ball_box<D> b;
      for (int j = 0; j < D; ++j) {
        b.centre_lo[j] = q.d[j];
        b.centre_hi[j] = q.d[D + j];
        b.lo[j] = q.d[2 * D + j];
        b.hi[j] = q.d[3 * D + j];
      }
      b.radius2_limit = q.d[4 * D];
      b.bounded = b.radius2_limit >= 0;
      std::vector<std::pair<double, std::uint32_t>> candidates;  // (squared distance to the centre, point)
      Coords<D> centre;
      for (int j = 0; j < D; ++j) centre[j] = 0.5 * b.centre_lo[j] + 0.5 * b.centre_hi[j];
      index_.for_each([&](const Box<D>& node) { return b.may_meet(node.lo, node.hi); },
                      [&](std::uint32_t i) {
                        if (sent[i] || !b.may_meet(points_[i].x, points_[i].x)) return;
                        double d2 = 0;
                        for (int j = 0; j < D; ++j) d2 += (points_[i][j] - centre[j]) * (points_[i][j] - centre[j]);
                        candidates.push_back({d2, i});
                      });
      // Too many: the nearest the centre only (a ranking; the asker asks again
      // while the cell stands). Ties by point number: the same answer on every run.
      const auto limit = static_cast<std::size_t>(std::max(q.limit, 1));
      const bool all = !b.bounded || candidates.size() <= limit;
      if (!all) {
        std::nth_element(candidates.begin(), candidates.begin() + static_cast<std::ptrdiff_t>(limit), candidates.end());
        candidates.resize(limit);
      }
      std::sort(candidates.begin(), candidates.end());
      for (const auto& [d2, i] : candidates) send(i);
      return all;
    } else {
      std::array<kernel::Point_d<D>, D + 1> f{};
      Coords<D> centroid{};
      for (int i = 0; i <= D; ++i) {
        if (i == q.slot) continue;
        for (int j = 0; j < D; ++j) {
          f[i][j] = q.d[i * D + j];
          centroid[j] += f[i][j] / D;
        }
      }
      kernel::Orientation_points<D> refs;
      for (int i = 0; i <= D; ++i) refs[i] = &f[i];
      std::uint32_t best = std::numeric_limits<std::uint32_t>::max();
      double best_d2 = std::numeric_limits<double>::infinity();
      index_.for_each([&](const Box<D>& node) { return box_reaches_beyond<D>(node, f, q.slot); },
                      [&](std::uint32_t i) {
                        if (sent[i]) return;  // in the asker's S: never strictly beyond its hull
                        double d2 = 0;
                        for (int j = 0; j < D; ++j) d2 += (points_[i][j] - centroid[j]) * (points_[i][j] - centroid[j]);
                        if (best != std::numeric_limits<std::uint32_t>::max() &&
                            (d2 > best_d2 || (d2 == best_d2 && gid_[i] > gid_[best])))
                          return;  // ranks the candidates only: any point beyond is a right answer
                        refs[q.slot] = &points_[i];
                        if (kernel::orientation_d<D>(refs) == kernel::POSITIVE) {
                          best = i;
                          best_d2 = d2;
                        }
                      });
      if (best == std::numeric_limits<std::uint32_t>::max()) return true;
      send(best);
      return false;
    }
  }

  const Comm& c_;
  const Options& options_;
  Statistics& stats_;
  std::size_t nb_ = 0;                        // points_[0, nb_): the block (region by region); then the halo
  std::size_t lo_ = 0, hi_ = 0;               // the region: S = points_[lo_, hi_) and the halo
  std::vector<std::uint64_t> region_start_;   // region r: points_[region_start_[r], region_start_[r + 1])
  std::vector<Box<D>> region_box_;
  std::vector<std::vector<Box<D>>> others_;   // by rank: boxes holding its points outside S (this rank: its other regions)
  std::vector<kernel::Point_d<D>> points_;
  std::vector<std::uint64_t> gid_;
  std::vector<Box<D>> boxes_;                 // every rank's block box
  std::vector<std::vector<char>> sent_;       // by asking rank: the block points sent there
  Block_index<D> index_;
  std::unordered_set<Global_simplex<D>, Key_hash<D>> verified_;
  std::vector<std::vector<Global_simplex<D>>> pending_;  // by rank: the cells asked about this round
  bool spanning_ = false;                     // dt holds DT(points_[0, in_dt_))
  std::size_t in_dt_ = 0;
  detail::Box<D> all_blocks_;                 // the box of every block
};

/// Step 3: the block's distinct points (of equal points, the smallest global
/// index), in global index order. The records arrive in rank order, each
/// rank's in its order: sorted by global index already when the ranks'
/// offsets grow with the rank (the tool's shares); then duplicates are found
/// by the hash table the one-machine path uses (kernel::first_occurrences,
/// O(n), no sort).
template <int D>
std::vector<Record<D>> distinct_block(std::vector<Record<D>> got) {
  const auto by_gid = [](const Record<D>& a, const Record<D>& b) { return a.gid < b.gid; };
  if (!std::is_sorted(got.begin(), got.end(), by_gid)) std::sort(got.begin(), got.end(), by_gid);
  const std::vector<std::uint32_t> first = kernel::first_occurrences(
      std::span<const Record<D>>(got),
      [](const Record<D>& a, const Record<D>& b) { return a.x == b.x ? kernel::EQUAL : kernel::SMALLER; },
      [](const Record<D>& r) -> const Coords<D>& { return r.x; });
  std::size_t kept = 0;
  for (std::size_t i = 0; i < got.size(); ++i)
    if (first[i] == i) got[kept++] = got[i];
  got.resize(kept);
  got.shrink_to_fit();
  return got;
}

/// Step 3's checks on the distinct points of all blocks (every rank decides alike).
template <int D>
void check_distinct_points(const Comm& c, const std::vector<Record<D>>& block) {
  const std::uint64_t distinct = allreduce_sum(c, block.size());
  if (distinct < static_cast<std::uint64_t>(D + 1))
    throw Invalid_input("need at least " + std::to_string(D + 1) + " distinct points in dimension " +
                        std::to_string(D) + ", got " + std::to_string(distinct));
  // Each block's affine basis (at most D + 1 points), gathered; their union spans what all points span.
  std::vector<Coords<D>> basis_points;
  if (!block.empty()) {
    detail::Affine_basis<D> basis(block[0].x);
    basis_points.push_back(block[0].x);
    for (std::size_t i = 1; i < block.size() && basis.rank() < D; ++i)
      if (basis.add(block[i].x)) basis_points.push_back(block[i].x);
  }
  const int mine_used = static_cast<int>(basis_points.size());
  basis_points.resize(D + 1, Coords<D>{});  // padding, not read
  std::vector<int> used(c.size);
  MPI_Allgather(&mine_used, 1, MPI_INT, used.data(), 1, MPI_INT, c.comm);
  std::vector<Coords<D>> all(static_cast<std::size_t>(c.size) * (D + 1));
  MPI_Allgather(basis_points.data(), static_cast<int>(sizeof(Coords<D>) * (D + 1)), MPI_BYTE, all.data(),
                static_cast<int>(sizeof(Coords<D>) * (D + 1)), MPI_BYTE, c.comm);
  std::optional<detail::Affine_basis<D>> basis;
  for (int r = 0; r < c.size; ++r)
    for (int i = 0; i < used[r]; ++i) {
      const Coords<D>& x = all[static_cast<std::size_t>(r) * (D + 1) + static_cast<std::size_t>(i)];
      if (!basis) basis.emplace(x);
      else basis->add(x);
    }
  if (basis->rank() < D) {
    static const char* const names[] = {"a point", "collinear", "coplanar", "in one 3-flat", "in one 4-flat",
                                        "in one 5-flat"};
    throw Invalid_input("the points do not span E^" + std::to_string(D) + ": all " + std::to_string(distinct) +
                        " distinct points are " + names[basis->rank()] + " (affine dimension " +
                        std::to_string(basis->rank()) + ")");
  }
}

/// triangulate_into's two forms; `owned`, when given, holds `local` and is
/// freed once the points are packed for their blocks.
template <int D>
Statistics run(MPI_Comm comm, std::span<const kernel::Point_d<D>> local, std::uint64_t global_offset,
               const Simplex_sink<D>& sink, const Options& options, std::vector<kernel::Point_d<D>>* owned) {
  const kernel::Fp_environment_guard guard;
  Comm c{comm};
  MPI_Comm_rank(comm, &c.rank);
  MPI_Comm_size(comm, &c.size);
  Statistics st;
  st.local_points = local.size();

  // 1. Non-finite coordinates: the smallest such global index, on every rank.
  std::uint64_t bad = std::numeric_limits<std::uint64_t>::max(), first_bad = bad;
  for (std::size_t i = 0; i < local.size() && bad == std::numeric_limits<std::uint64_t>::max(); ++i)
    for (int j = 0; j < D; ++j)
      if (!kernel::is_finite(local[i][j])) bad = global_offset + i;
  MPI_Allreduce(&bad, &first_bad, 1, MPI_UINT64_T, MPI_MIN, comm);
  if (first_bad != std::numeric_limits<std::uint64_t>::max())
    throw Invalid_input(first_bad, "has a non-finite coordinate (NaN or infinity)");

  // 2. The blocks: the records packed by destination rank (a counting sort),
  // sent in one exchange.
  const double t0 = MPI_Wtime();
  std::vector<Record<D>> block;
  {
    std::vector<Record<D>> send;
    std::vector<std::uint64_t> count(c.size, 0);
    run_collectively(comm, [&] {
      const std::vector<int> rank_of = decompose<D>(c, local);
      for (const int q : rank_of) ++count[q];
      std::vector<std::uint64_t> at(c.size, 0);
      for (int q = 1; q < c.size; ++q) at[q] = at[q - 1] + count[q - 1];
      send.resize(local.size());
      for (std::size_t i = 0; i < local.size(); ++i) send[at[rank_of[i]]++] = {global_offset + i, local[i].x};
      if (owned) std::vector<kernel::Point_d<D>>().swap(*owned);  // `local` is not read again
    });
    run_collectively(comm, [&] {
      std::vector<Record<D>> got = alltoall(c, send, count);
      std::vector<Record<D>>().swap(send);
      block = distinct_block<D>(std::move(got));
    });
  }
  st.decompose_seconds = MPI_Wtime() - t0;
  st.block_points = block.size();

  // 3. The checks on distinct points (collective, the same outcome on every rank).
  check_distinct_points<D>(c, block);

  // 4 and 5.
  Rank_triangulation<D> rt(c, std::move(block), options, st);
  rt.run(sink);
  return st;
}

}  // namespace

template <int D>
Statistics triangulate_into(MPI_Comm comm, std::span<const kernel::Point_d<D>> local, std::uint64_t global_offset,
                            const Simplex_sink<D>& sink, const Options& options) {
  return run<D>(comm, local, global_offset, sink, options, nullptr);
}

template <int D>
Statistics triangulate_into(MPI_Comm comm, std::vector<kernel::Point_d<D>>&& local, std::uint64_t global_offset,
                            const Simplex_sink<D>& sink, const Options& options) {
  return run<D>(comm, std::span<const kernel::Point_d<D>>(local), global_offset, sink, options, &local);
}

#define DEWALL_INSTANTIATE_MPI(D)                                                                   \
  template Statistics triangulate_into<D>(MPI_Comm, std::span<const kernel::Point_d<D>>, std::uint64_t, \
                                          const Simplex_sink<D>&, const Options&);                 \
  template Statistics triangulate_into<D>(MPI_Comm, std::vector<kernel::Point_d<D>>&&, std::uint64_t,  \
                                          const Simplex_sink<D>&, const Options&);
DEWALL_FOR_EACH_DIMENSION(DEWALL_INSTANTIATE_MPI)

}  // namespace dewall::mpi
