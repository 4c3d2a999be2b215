#include <ellipsect/broad_phase.hpp>

#include "detail/axes.hpp"
#include "detail/instantiate.hpp"
#include "detail/shape_access.hpp"
#include "detail/math.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <numeric>
#include <optional>
#include <stdexcept>
#include <string>
#include <type_traits>

namespace ellipsect {

namespace {

template <int N>
struct Aabb {
  double lo[N], hi[N];
};

// One box of the sweep: body `body`, translated by shift * size in a periodic box.
template <int N>
struct Entry {
  Aabb<N> box;
  std::uint32_t body;
  std::array<std::int32_t, N> shift;
};

// Position of one coordinate at time t, with 0 * inf taken as 0 (a body at rest stays put).
double at_time(double c, double v, double t) { return v == 0.0 ? c : c + v * t; }

template <class T, int N>
bool spins(const RigidMotion<T, N>& m) {
  if constexpr (N == 2)
    return m.angular_velocity != T(0);
  else
    return !m.angular_velocity.isZero(0);
}

// The largest factor (1 + g t) of a body's radii over [t0, t1] (t0, t1 >= 0): infinite for
// a growing body over an unbounded window.
double grown_by(double growth, double t1) { return growth == 0.0 ? 1.0 : 1.0 + growth * t1; }

// The box of `body` moving with `velocity` over [t0, t1], its radii times `scale` at most:
// exact for a body that does not turn or grow (with the axes the queries compute with: float
// axes orthonormalized), the box of its bounding ball for one that turns.
template <class T, int N>
Aabb<N> box_of(const Ellipsoid<T, N>& body, const Vec<T, N>& velocity, bool turning, double t0, double t1,
               double scale = 1.0) {
  const Mat<double, N> A = detail::work_axes<double>(body);
  const auto r = body.radii();
  const auto c = body.center();
  const double r_max = double(r.maxCoeff()) * scale;
  Aabb<N> box;
  for (int k = 0; k < N; ++k) {
    double h = r_max;
    if (!turning) {  // r_max |row k of A diag(r / r_max)|: no underflow or overflow
      double h2 = 0.0;
      for (int j = 0; j < N; ++j) {
        const double e = A(k, j) * (double(r[j]) * scale / r_max);
        h2 += e * e;
      }
      h = std::min(r_max, r_max * sqrt(h2));
    }
    const double start = at_time(double(c[k]), double(velocity[k]), t0);
    const double end = at_time(double(c[k]), double(velocity[k]), t1);
    const double lo = std::min(start, end), hi = std::max(start, end);
    const double pad = 1e-9 * r_max +
                       1e-14 * (abs(double(c[k])) + (isfinite(lo) ? abs(lo) : 0.0) +
                                (isfinite(hi) ? abs(hi) : 0.0)) +
                       8 * std::numeric_limits<double>::denorm_min();  // subnormal coordinates and radii
    box.lo[k] = lo - h - pad;
    box.hi[k] = hi + h + pad;
  }
  return box;
}

template <class T, int N>
std::vector<Aabb<N>> boxes_of(std::span<const Ellipsoid<T, N>> bodies, std::span<const RigidMotion<T, N>> motions,
                              double t0, double t1) {
  if (motions.size() != bodies.size())
    throw std::invalid_argument("ellipsect: motions and bodies must have equal sizes");
  std::vector<Aabb<N>> boxes;
  boxes.reserve(bodies.size());
  for (std::size_t i = 0; i < bodies.size(); ++i)
    if (!(motions[i].growth >= T(0)) || !isfinite(motions[i].growth) || (motions[i].growth > T(0) && !(t0 >= 0.0)))
      throw InputError("motions[" + std::to_string(i) + "].growth",
                       "must be finite and >= 0, and the window must start at t0 >= 0 where it is not 0");
  for (std::size_t i = 0; i < bodies.size(); ++i)
    boxes.push_back(
        box_of(bodies[i], motions[i].velocity, spins(motions[i]), t0, t1, grown_by(double(motions[i].growth), t1)));
  return boxes;
}

// Sweep and prune along x: calls meet(p, q) for every two entries p, q whose boxes meet
// (the fallback of find_meeting for boxes a grid cannot hold).
template <int N, class Meet>
void sweep(const std::vector<Entry<N>>& entries, Meet&& meet) {
  std::vector<std::uint32_t> order(entries.size());
  std::iota(order.begin(), order.end(), 0u);
  std::sort(order.begin(), order.end(), [&](std::uint32_t p, std::uint32_t q) {
    return entries[p].box.lo[0] < entries[q].box.lo[0] || (entries[p].box.lo[0] == entries[q].box.lo[0] && p < q);
  });
  std::vector<std::uint32_t> active;
  for (const std::uint32_t p : order) {
    const Aabb<N>& bp = entries[p].box;
    // Drop boxes that end before this one starts.
    std::size_t keep = 0;
    for (const std::uint32_t q : active)
      if (entries[q].box.hi[0] >= bp.lo[0]) active[keep++] = q;
    active.resize(keep);
    for (const std::uint32_t q : active) {
      const Aabb<N>& bq = entries[q].box;
      bool meets = true;
      for (int k = 1; k < N && meets; ++k) meets = bp.lo[k] <= bq.hi[k] && bq.lo[k] <= bp.hi[k];
      if (meets) meet(entries[p], entries[q]);
    }
    active.push_back(p);
  }
}

// Uniform grid: calls meet(p, q) once for every two entries whose boxes meet. The cell is
// a little more than the largest extent of any box on any axis (by 1e-5 of it and 1e-12 of
// the largest coordinate, far above the rounding of the cell numbers), so two boxes that
// meet have their lower corners in the same or adjacent cells: each entry is filed under
// the cell of its lower corner (cells numbered x fastest) and looks at its 3^N neighbors,
// as 3^(N-1) runs of 3 cells along x. Unbounded boxes, or scenes wider than 2^31 cells on
// an axis, go to the sweep.
template <int N, class Meet>
void find_meeting(const std::vector<Entry<N>>& entries, Meet&& meet) {
  double extent = 0.0, largest = 0.0, origin[N], top[N];
  for (int k = 0; k < N; ++k) origin[k] = std::numeric_limits<double>::infinity(), top[k] = -origin[k];
  for (const Entry<N>& e : entries)
    for (int k = 0; k < N; ++k) {
      extent = std::max(extent, e.box.hi[k] - e.box.lo[k]);
      largest = std::max({largest, abs(e.box.lo[k]), abs(e.box.hi[k])});
      origin[k] = std::min(origin[k], e.box.lo[k]);
      top[k] = std::max(top[k], e.box.lo[k]);
    }
  const double cell = extent * (1.0 + 1e-5) + 1e-12 * largest;
  std::int64_t cells[N];
  double total = 1.0;
  for (int k = 0; k < N; ++k) {
    const double n = floor((top[k] - origin[k]) / cell) + 1.0;
    const bool fits = n <= 0x1p31;  // false for NaN and infinity too
    cells[k] = fits ? std::int64_t(n) : 0;
    total *= fits ? n : std::numeric_limits<double>::infinity();
  }
  if (entries.size() < 2 || !(isfinite(largest) && cell > 0.0 && total < 0x1p62))
    return sweep(entries, meet);

  auto key_of = [&](const std::int64_t (&c)[N]) {
    std::int64_t key = 0;
    for (int k = N - 1; k >= 0; --k) key = key * cells[k] + c[k];
    return key;
  };
  // Entries in the order of their cells (and of their index within a cell): by counting
  // where the cells are few (at most 4 per entry), else by sorting; start(key) is the
  // position of the first entry in a cell >= key.
  const std::size_t n = entries.size();
  std::vector<std::int64_t> keys(n);
  for (std::size_t i = 0; i < n; ++i) {
    std::int64_t c[N];
    for (int k = 0; k < N; ++k) c[k] = std::min(cells[k] - 1, std::int64_t((entries[i].box.lo[k] - origin[k]) / cell));
    keys[i] = key_of(c);
  }
  std::vector<std::uint32_t> order(n);
  std::vector<std::size_t> starts;
  const bool dense = total <= 4.0 * double(n) + 4096.0;
  if (dense) {
    starts.assign(std::size_t(total) + 1, 0);
    for (const std::int64_t key : keys) ++starts[std::size_t(key) + 1];
    std::partial_sum(starts.begin(), starts.end(), starts.begin());
    std::vector<std::size_t> next(starts.begin(), starts.end() - 1);
    for (std::size_t i = 0; i < n; ++i) order[next[std::size_t(keys[i])]++] = std::uint32_t(i);
  } else {
    std::iota(order.begin(), order.end(), 0u);
    std::sort(order.begin(), order.end(),
              [&](std::uint32_t a, std::uint32_t b) { return keys[a] < keys[b] || (keys[a] == keys[b] && a < b); });
  }
  std::vector<Entry<N>> sorted(n);
  std::vector<std::int64_t> sorted_keys(n);
  for (std::size_t a = 0; a < n; ++a) sorted[a] = entries[order[a]], sorted_keys[a] = keys[order[a]];
  auto start = [&](std::int64_t key) {
    return dense ? starts[std::size_t(key)]
                 : std::size_t(std::lower_bound(sorted_keys.begin(), sorted_keys.end(), key) - sorted_keys.begin());
  };
  for (std::size_t a = 0; a < n; ++a) {
    const Entry<N>& p = sorted[a];
    std::int64_t c[N];
    std::int64_t rest = sorted_keys[a];
    for (int k = 0; k < N; ++k) c[k] = rest % cells[k], rest /= cells[k];
    // Neighbor rows along x: offsets in {-1, 0, 1} on the axes after x.
    for (int row = 0; row < (N == 2 ? 3 : 9); ++row) {
      std::int64_t lo[N], hi[N];
      bool inside = true;
      for (int k = 1, code = row; k < N; ++k, code /= 3) {
        lo[k] = hi[k] = c[k] + code % 3 - 1;
        inside = inside && lo[k] >= 0 && lo[k] < cells[k];
      }
      if (!inside) continue;
      lo[0] = std::max<std::int64_t>(c[0] - 1, 0);
      hi[0] = std::min(c[0] + 1, cells[0] - 1);
      for (std::size_t b = start(key_of(lo)), end = start(key_of(hi) + 1); b < end; ++b) {
        if (order[b] <= order[a]) continue;  // each pair once, from its lower entry
        const Entry<N>& q = sorted[b];
        bool meets = true;
        for (int k = 0; k < N && meets; ++k) meets = p.box.lo[k] <= q.box.hi[k] && q.box.lo[k] <= p.box.hi[k];
        if (meets) meet(p, q);
      }
    }
  }
}

template <int N>
std::vector<IndexPair> open_pairs(const std::vector<Aabb<N>>& boxes) {
  std::vector<Entry<N>> entries;
  entries.reserve(boxes.size());
  for (std::size_t i = 0; i < boxes.size(); ++i) entries.push_back({boxes[i], std::uint32_t(i), {}});
  std::vector<IndexPair> pairs;
  find_meeting(entries, [&](const Entry<N>& p, const Entry<N>& q) {
    pairs.emplace_back(std::min(p.body, q.body), std::max(p.body, q.body));
  });
  std::sort(pairs.begin(), pairs.end());
  return pairs;
}

template <int N>
void check_box(const PeriodicBox<N>& box) {
  for (int k = 0; k < N; ++k)
    if (!(isfinite(box.size[k]) && box.size[k] > 0.0))
      throw InputError("box.size", "must be finite and > 0 (got " + std::to_string(box.size[k]) + ")");
}

// Periodic sweep: each box is moved into the periodic cell by whole sides (by the cell of
// its start, `wrap`), and copied by one side along every axis on which it crosses the
// cell's faces; two copies that meet give the pair and the image of j that meets i.
template <int N>
std::vector<ImagePair<N>> periodic_pairs(const std::vector<Aabb<N>>& boxes,
                                         const std::vector<std::array<double, N>>& anchors, const PeriodicBox<N>& box) {
  check_box(box);
  const double limit = ldexp(1.0, 30);
  std::vector<std::array<std::int32_t, N>> wrap(boxes.size());
  std::vector<Entry<N>> entries;
  entries.reserve(boxes.size() * 2);
  for (std::size_t i = 0; i < boxes.size(); ++i) {
    Aabb<N> b = boxes[i];
    int crossing[N];
    for (int k = 0; k < N; ++k) {
      const double L = box.size[k];
      const double cells = floor(anchors[i][k] / L);
      if (!(abs(cells) < limit))
        throw InputError("bodies[" + std::to_string(i) + "].center",
                         "must lie within 2^30 box sides of the periodic box");
      if (!(b.hi[k] - b.lo[k] < 0.5 * L))
        throw InputError("box", "body " + std::to_string(i) +
                                    "'s bounding box must be shorter than half the box side on every axis");
      wrap[i][k] = std::int32_t(cells);
      // Moving the box by whole sides, and its copies by one more, rounds at the scale of
      // the sides: widen it by that much (a side far larger than the bodies then makes
      // boxes near the faces candidates of every body there, never misses one).
      const double rounding = 0x1p-50 * ((abs(cells) + 2.0) * L + std::max(abs(b.lo[k]), abs(b.hi[k])));
      b.lo[k] = b.lo[k] - cells * L - rounding;
      b.hi[k] = b.hi[k] - cells * L + rounding;
      crossing[k] = b.lo[k] <= 0.0 ? 1 : b.hi[k] >= L ? -1 : 0;
    }
    for (unsigned mask = 0; mask < (1u << N); ++mask) {
      Entry<N> e{b, std::uint32_t(i), {}};
      bool skip = false;
      for (int k = 0; k < N && !skip; ++k) {
        if (!(mask >> k & 1u)) continue;
        skip = crossing[k] == 0;
        e.shift[k] = crossing[k];
        e.box.lo[k] += crossing[k] * box.size[k];
        e.box.hi[k] += crossing[k] * box.size[k];
      }
      if (!skip) entries.push_back(e);
    }
  }
  std::vector<ImagePair<N>> pairs;
  find_meeting(entries, [&](const Entry<N>& p, const Entry<N>& q) {
    if (p.body == q.body) return;
    const Entry<N>& a = p.body < q.body ? p : q;
    const Entry<N>& b = p.body < q.body ? q : p;
    ImagePair<N> pair{a.body, b.body, {}};
    // b's copy (cell wrap[b] moved by shift_b) meets a's: b translated by the image meets a.
    for (int k = 0; k < N; ++k)
      pair.image[k] = (b.shift[k] - a.shift[k]) + (wrap[a.body][k] - wrap[b.body][k]);
    pairs.push_back(pair);
  });
  std::sort(pairs.begin(), pairs.end());
  pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());
  return pairs;
}

template <class T, int N>
std::vector<std::array<double, N>> anchors_at(std::span<const Ellipsoid<T, N>> bodies,
                                              std::span<const RigidMotion<T, N>> motions, double t) {
  std::vector<std::array<double, N>> anchors(bodies.size());
  for (std::size_t i = 0; i < bodies.size(); ++i)
    for (int k = 0; k < N; ++k)
      anchors[i][k] = at_time(double(bodies[i].center()[k]), motions.empty() ? 0.0 : double(motions[i].velocity[k]), t);
  return anchors;
}

// Body j's image, translated by image * size (the center summed in double and rounded to T
// once); nothing where that center lies beyond the range of T: such an image cannot meet a
// body of T.
template <class T, int N>
std::optional<Ellipsoid<T, N>> image_of(const Ellipsoid<T, N>& body, const std::array<std::int32_t, N>& image,
                                        const PeriodicBox<N>* box) {
  if (box == nullptr || std::all_of(image.begin(), image.end(), [](std::int32_t m) { return m == 0; })) return body;
  Vec<T, N> center;
  for (int k = 0; k < N; ++k) center[k] = T(double(body.center()[k]) + double(image[k]) * box->size[k]);
  if (!center.allFinite()) return std::nullopt;
  return detail::ShapeAccess::unchecked<T, N>(center, body.axes(), body.radii());
}

template <class T, int N>
void check_motions(std::span<const Ellipsoid<T, N>> bodies, std::span<const RigidMotion<T, N>> motions) {
  if (motions.size() != bodies.size())
    throw std::invalid_argument("ellipsect: motions and bodies must have equal sizes");
  for (std::size_t i = 0; i < motions.size(); ++i) {
    if (!motions[i].velocity.allFinite())
      throw InputError("motions[" + std::to_string(i) + "].velocity", "must be finite");
    bool finite;
    if constexpr (N == 2)
      finite = isfinite(motions[i].angular_velocity);
    else
      finite = motions[i].angular_velocity.allFinite();
    if (!finite) throw InputError("motions[" + std::to_string(i) + "].angular_velocity", "must be finite");
    if (!(motions[i].growth >= T(0)) || !isfinite(motions[i].growth))
      throw InputError("motions[" + std::to_string(i) + "].growth", "must be finite and >= 0");
  }
}

// A contact with no time, point or normal.
template <class T, int N>
Contact<T, N> no_answer(ContactStatus status) {
  const T nan = std::numeric_limits<T>::quiet_NaN();
  return {status, nan, Vec<T, N>::Constant(nan), Vec<T, N>::Constant(nan), 0};
}

// Rank of a pair's answer for the earliest contact: lower wins; hits compare by time.
int rank(ContactStatus s) {
  switch (s) {
    case ContactStatus::overlapping_at_start: return 0;
    case ContactStatus::touching_at_start: return 1;
    default: return 2;
  }
}

template <class T, int N>
PairContact<T, N> earliest(std::span<const Ellipsoid<T, N>> bodies, std::span<const RigidMotion<T, N>> motions, T t_max,
                           const PeriodicBox<N>* box, const Options& options) {
  check_motions(bodies, motions);
  PairContact<T, N> best{{}, no_answer<T, N>(ContactStatus::no_contact_in_window)};
  if (!(t_max >= T(0))) best.contact.status = ContactStatus::invalid_input;
  if (best.contact.status == ContactStatus::invalid_input || bodies.size() < 2) return best;

  // Slab length from t0: each body's swept box stays under 0.45 of a side (periodic box
  // only); a growing body's box widens at the rate of its box at radii times 1 per unit growth.
  if (box != nullptr) check_box(*box);
  auto slab_from = [&](double t0) {
    double slab = std::numeric_limits<double>::infinity();
    if (box == nullptr) return slab;
    for (std::size_t i = 0; i < bodies.size(); ++i) {
      const double growth = double(motions[i].growth), scale = grown_by(growth, t0);
      const Aabb<N> still = box_of<T, N>(bodies[i], Vec<T, N>::Zero(), spins(motions[i]), 0.0, 0.0);
      for (int k = 0; k < N; ++k) {
        const double extent = (still.hi[k] - still.lo[k]) * scale;
        if (!(extent < 0.25 * box->size[k]))
          throw InputError("box", "body " + std::to_string(i) +
                                      (t0 > 0.0 ? " grows beyond a quarter of the box side by time " + std::to_string(t0)
                                                : std::string(" must be smaller than a quarter of the box side")) +
                                      " on some axis");
        const double rate = abs(double(motions[i].velocity[k])) + (still.hi[k] - still.lo[k]) * growth;
        if (rate > 0.0) slab = std::min(slab, (0.45 * box->size[k] - extent) / rate);
      }
    }
    return slab;
  };

  T stopped = std::numeric_limits<T>::infinity();  // least lower bound of a stopped pair
  ImagePair<N> stopped_pair;
  double t0 = 0.0;
  for (int slabs = 0;; ++slabs) {
    if (box != nullptr && slabs == options.max_slabs) {
      best.contact = no_answer<T, N>(ContactStatus::did_not_converge);
      best.contact.time = T(t0);
      return best;
    }
    const double t1 = std::min(double(t_max), t0 + slab_from(t0));
    std::vector<ImagePair<N>> candidates;
    if (box != nullptr) {
      candidates = periodic_pairs<N>(boxes_of(bodies, motions, t0, t1), anchors_at(bodies, motions, t0), *box);
    } else {
      for (const auto& [i, j] : open_pairs(boxes_of(bodies, motions, t0, t1))) candidates.push_back({i, j, {}});
    }
    for (const ImagePair<N>& p : candidates) {
      const bool found = best.contact.status != ContactStatus::no_contact_in_window;
      if (found && rank(best.contact.status) == 0) break;
      const T window = found ? best.contact.time : T(t1);
      const auto b = image_of<T, N>(bodies[p.j], p.image, box);
      if (!b) continue;
      const Contact<T, N> c = first_contact(bodies[p.i], motions[p.i], *b, motions[p.j], window, options);
      if (c.status == ContactStatus::no_contact_in_window) continue;
      if (c.status == ContactStatus::did_not_converge) {
        if (c.time < stopped) stopped = c.time, stopped_pair = p;
        continue;
      }
      if (!found || rank(c.status) < rank(best.contact.status) ||
          (rank(c.status) == 2 && rank(best.contact.status) == 2 && c.time < best.contact.time))
        best = {p, c};
    }
    const bool found = best.contact.status != ContactStatus::no_contact_in_window;
    if (stopped < (found ? best.contact.time : std::numeric_limits<T>::infinity())) {
      best = {stopped_pair, no_answer<T, N>(ContactStatus::did_not_converge)};
      best.contact.time = stopped;
      return best;
    }
    if (found || t1 >= double(t_max)) return best;
    t0 = t1;
  }
}

}  // namespace

template <class T, int N>
std::vector<IndexPair> candidate_pairs(std::span<const Ellipsoid<T, N>> bodies,
                                       std::span<const Vec<T, N>> velocities, double t0, double t1) {
  if (velocities.size() != bodies.size())
    throw std::invalid_argument("ellipsect: velocities and bodies must have equal sizes");
  std::vector<Aabb<N>> boxes;
  boxes.reserve(bodies.size());
  for (std::size_t i = 0; i < bodies.size(); ++i) boxes.push_back(box_of(bodies[i], velocities[i], false, t0, t1));
  return open_pairs(boxes);
}

template <class T, int N>
std::vector<IndexPair> candidate_pairs(std::span<const Ellipsoid<T, N>> bodies,
                                       std::span<const RigidMotion<T, N>> motions, double t0, double t1) {
  return open_pairs(boxes_of(bodies, motions, t0, t1));
}

template <class T, int N>
std::vector<IndexPair> candidate_pairs(std::span<const Ellipsoid<T, N>> bodies) {
  const std::vector<RigidMotion<T, N>> rest(bodies.size());
  return open_pairs(boxes_of(bodies, std::span(rest), 0.0, 0.0));
}

template <class T, int N>
std::vector<ImagePair<N>> candidate_pairs(std::span<const Ellipsoid<T, N>> bodies, const PeriodicBox<N>& box) {
  const std::vector<RigidMotion<T, N>> rest(bodies.size());
  return candidate_pairs(bodies, std::span(rest), 0.0, 0.0, box);
}

template <class T, int N>
std::vector<ImagePair<N>> candidate_pairs(std::span<const Ellipsoid<T, N>> bodies,
                                          std::span<const RigidMotion<T, N>> motions, double t0, double t1,
                                          const PeriodicBox<N>& box) {
  return periodic_pairs<N>(boxes_of(bodies, motions, t0, t1), anchors_at(bodies, motions, t0), box);
}

namespace {

// The batch overlap of the given pairs (b translated by its image where a box is given), in
// blocks of 2^16 pairs (the batch columns take a few hundred bytes per pair).
template <class T, int N, class P>
std::vector<P> overlapping(std::span<const Ellipsoid<T, N>> bodies, std::vector<P> candidates,
                           const PeriodicBox<N>* box, const BatchOptions& options) {
  if constexpr (!std::is_same_v<P, IndexPair>)
    std::erase_if(candidates, [&](const P& p) { return !image_of<T, N>(bodies[p.j], p.image, box); });
  constexpr std::size_t block = std::size_t(1) << 16;
  Pairs<T, N> pairs;
  pairs.reserve(std::min(block, candidates.size()));
  const auto hit = std::make_unique<bool[]>(block);
  std::vector<P> out;
  for (std::size_t start = 0; start < candidates.size(); start += block) {
    const std::size_t n = std::min(block, candidates.size() - start);
    pairs.clear();
    for (std::size_t k = start; k < start + n; ++k) {
      const P& p = candidates[k];
      if constexpr (std::is_same_v<P, IndexPair>)
        pairs.push_back(bodies[p.first], bodies[p.second]);
      else
        pairs.push_back(bodies[p.i], *image_of<T, N>(bodies[p.j], p.image, box));
    }
    overlap(pairs, std::span<bool>(hit.get(), n), options);
    for (std::size_t k = 0; k < n; ++k)
      if (hit[k]) out.push_back(candidates[start + k]);
  }
  return out;
}

}  // namespace

template <class T, int N>
std::vector<IndexPair> overlapping_pairs(std::span<const Ellipsoid<T, N>> bodies, const BatchOptions& options) {
  return overlapping<T, N>(bodies, candidate_pairs(bodies), nullptr, options);
}

template <class T, int N>
std::vector<ImagePair<N>> overlapping_pairs(std::span<const Ellipsoid<T, N>> bodies, const PeriodicBox<N>& box,
                                            const BatchOptions& options) {
  return overlapping<T, N>(bodies, candidate_pairs(bodies, box), &box, options);
}

template <class T, int N>
PairContact<T, N> earliest_contact(std::span<const Ellipsoid<T, N>> bodies, std::span<const RigidMotion<T, N>> motions,
                                   T t_max, const Options& options) {
  return earliest<T, N>(bodies, motions, t_max, nullptr, options);
}

template <class T, int N>
PairContact<T, N> earliest_contact(std::span<const Ellipsoid<T, N>> bodies, std::span<const RigidMotion<T, N>> motions,
                                   T t_max, const PeriodicBox<N>& box, const Options& options) {
  return earliest<T, N>(bodies, motions, t_max, &box, options);
}

#define ELLIPSECT_INSTANTIATE(T, N)                                                                                  \
  template std::vector<IndexPair> candidate_pairs<T, N>(std::span<const Ellipsoid<T, N>>);                           \
  template std::vector<IndexPair> candidate_pairs<T, N>(std::span<const Ellipsoid<T, N>>,                            \
                                                        std::span<const Vec<T, N>>, double, double);                 \
  template std::vector<IndexPair> candidate_pairs<T, N>(std::span<const Ellipsoid<T, N>>,                            \
                                                        std::span<const RigidMotion<T, N>>, double, double);         \
  template std::vector<ImagePair<N>> candidate_pairs<T, N>(std::span<const Ellipsoid<T, N>>, const PeriodicBox<N>&); \
  template std::vector<ImagePair<N>> candidate_pairs<T, N>(                                                          \
      std::span<const Ellipsoid<T, N>>, std::span<const RigidMotion<T, N>>, double, double, const PeriodicBox<N>&);  \
  template std::vector<IndexPair> overlapping_pairs<T, N>(std::span<const Ellipsoid<T, N>>, const BatchOptions&);   \
  template std::vector<ImagePair<N>> overlapping_pairs<T, N>(std::span<const Ellipsoid<T, N>>,                       \
                                                             const PeriodicBox<N>&, const BatchOptions&);            \
  template PairContact<T, N> earliest_contact<T, N>(std::span<const Ellipsoid<T, N>>,                                \
                                                    std::span<const RigidMotion<T, N>>, T, const Options&);          \
  template PairContact<T, N> earliest_contact<T, N>(                                                                 \
      std::span<const Ellipsoid<T, N>>, std::span<const RigidMotion<T, N>>, T, const PeriodicBox<N>&, const Options&);
ELLIPSECT_FOR_EACH_TYPE_AND_DIM(ELLIPSECT_INSTANTIATE)
#undef ELLIPSECT_INSTANTIATE

}  // namespace ellipsect
