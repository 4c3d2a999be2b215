// Fuzz target `broad_phase`: overlapping_pairs, candidate_pairs and earliest_contact on 2 to
// 7 bodies (2D or 3D, double or float) with motions and, for about half the inputs, a
// periodic box decoded from the input, checked against what broad_phase.hpp promises:
//   overlapping_pairs equals the all-pairs loop of overlap, and is within candidate_pairs;
//   in a periodic box, InputError naming "box.size", "box" or "bodies[k].center" exactly
//   where the input breaks those rules, else every (i, j, image) returned overlaps, and
//   every pair that overlaps through the image nearest its centers or the next ones is
//   returned;
//   earliest_contact: InputError naming "motions[k].velocity" or "...angular_velocity" for a
//   non-finite motion; invalid_input exactly for a NaN or negative t_max; in open space,
//   no_contact_in_window where first_contact says so of every pair, and only where no pair
//   has a hit or starts in contact (a pair first_contact cannot resolve may be certified
//   apart by its boxes), a hit never later than the earliest hit of first_contact over the
//   pairs (to the time's accuracy: the pairs are computed there with shorter windows) and
//   not at all where some pair starts overlapping or touching, and did_not_converge only
//   where some pair's first_contact stops.
#include "fuzz_support.hpp"

#include <ellipsect/broad_phase.hpp>
#include <ellipsect/classify.hpp>

#include <algorithm>
#include <array>
#include <vector>

namespace {

using namespace ellipsect;
using namespace ellipsect::fuzz;

template <class T, int N>
void check_periodic(const std::vector<Ellipsoid<T, N>>& bodies, const PeriodicBox<N>& box) {
  std::vector<ImagePair<N>> got;
  try {
    got = overlapping_pairs<T, N>(bodies, box);
  } catch (const InputError& e) {
    const std::string& f = e.field();
    bool bad_size = false;
    for (int k = 0; k < N; ++k) bad_size = bad_size || !(std::isfinite(box.size[k]) && box.size[k] > 0.0);
    FUZZ_CHECK(bad_size ? f == "box.size" : (f == "box" || f.starts_with("bodies[")), "periodic threw for " << f);
    return;
  }
  // j's image (the center summed in double); nothing beyond the range of T.
  auto image_of = [&](const Ellipsoid<T, N>& b, const std::array<std::int32_t, N>& m) -> std::optional<Ellipsoid<T, N>> {
    Vec<double, N> offset;
    for (int k = 0; k < N; ++k) offset[k] = double(m[k]) * box.size[k];
    const Vec<T, N> center = (b.center().template cast<double>() + offset).template cast<T>();
    if (!center.allFinite()) return std::nullopt;
    return Ellipsoid<T, N>::from_axes(center, b.axes(), b.radii());
  };
  for (const ImagePair<N>& p : got) {
    FUZZ_CHECK(p.i < p.j && p.j < bodies.size(), "pair " << p.i << " " << p.j);
    const auto b = image_of(bodies[p.j], p.image);
    FUZZ_CHECK(b && overlap(bodies[p.i], *b), "returned pair does not overlap");
  }
  for (std::uint32_t i = 0; i < bodies.size(); ++i)
    for (std::uint32_t j = i + 1; j < bodies.size(); ++j)
      for (int code = 0; code < (N == 2 ? 9 : 27); ++code) {
        std::array<std::int32_t, N> m;
        for (int k = 0, c = code; k < N; ++k, c /= 3)
          m[k] = std::int32_t(std::round((double(bodies[i].center()[k]) - double(bodies[j].center()[k])) /
                                         box.size[k])) + c % 3 - 1;
        const auto b = image_of(bodies[j], m);
        if (b && overlap(bodies[i], *b))
          FUZZ_CHECK(std::binary_search(got.begin(), got.end(), ImagePair<N>{i, j, m}), "missed pair " << i << " " << j);
      }
}

template <class T, int N>
void check_earliest(const std::vector<Ellipsoid<T, N>>& bodies, const std::vector<RigidMotion<T, N>>& motions,
                    T t_max, const PeriodicBox<N>* box) {
  std::string want;
  for (std::size_t k = 0; k < motions.size() && want.empty(); ++k) {
    if (!motions[k].velocity.allFinite()) want = "motions[" + std::to_string(k) + "].velocity";
    else if (!finite_spin(motions[k])) want = "motions[" + std::to_string(k) + "].angular_velocity";
  }
  PairContact<T, N> e;
  try {
    e = box ? earliest_contact<T, N>(bodies, motions, t_max, *box) : earliest_contact<T, N>(bodies, motions, t_max);
  } catch (const InputError& error) {
    const std::string& f = error.field();
    FUZZ_CHECK(f == want || (want.empty() && box && (f == "box" || f == "box.size" || f.starts_with("bodies["))),
               "earliest_contact threw for " << f << " (expected " << want << ")");
    return;
  }
  FUZZ_CHECK(want.empty(), "earliest_contact accepted " << want);
  const bool bad_window = std::isnan(t_max) || t_max < T(0);
  FUZZ_CHECK((e.contact.status == ContactStatus::invalid_input) == bad_window, "invalid_input " << int(e.contact.status));
  if (bad_window) return;
  // (The periodic search stopped after max_motion_steps slabs names no pair: (0, 0).)
  const bool slabs_out = box && e.contact.status == ContactStatus::did_not_converge && e.pair == ImagePair<N>{};
  if (e.contact.status != ContactStatus::no_contact_in_window && !slabs_out)
    FUZZ_CHECK(e.pair.i < e.pair.j && e.pair.j < bodies.size(), "pair " << e.pair.i << " " << e.pair.j);
  if (e.contact.status == ContactStatus::hit || e.contact.status == ContactStatus::did_not_converge)
    FUZZ_CHECK(e.contact.time >= T(0) && e.contact.time <= t_max, "time " << e.contact.time);
  if (box) return;
  // Open space: against first_contact on every pair.
  bool stopped = false, at_start = false, none = true;
  T earliest = std::numeric_limits<T>::infinity();
  for (std::uint32_t i = 0; i < bodies.size(); ++i)
    for (std::uint32_t j = i + 1; j < bodies.size(); ++j) {
      const Contact<T, N> c = first_contact(bodies[i], motions[i], bodies[j], motions[j], t_max);
      stopped = stopped || c.status == ContactStatus::did_not_converge;
      at_start = at_start || c.status == ContactStatus::overlapping_at_start ||
                 c.status == ContactStatus::touching_at_start;
      none = none && c.status == ContactStatus::no_contact_in_window;
      if (c.status == ContactStatus::hit) earliest = std::min(earliest, c.time);
    }
  // A pair whose first_contact stops (coordinates beyond what double resolves) may still be
  // certified apart by its boxes: no contact where every pair has none or stops.
  if (none) FUZZ_CHECK(e.contact.status == ContactStatus::no_contact_in_window, "no contact " << int(e.contact.status));
  if (e.contact.status == ContactStatus::no_contact_in_window)
    FUZZ_CHECK(!at_start && earliest == std::numeric_limits<T>::infinity(), "contact missed");
  if (e.contact.status == ContactStatus::did_not_converge) FUZZ_CHECK(stopped, "stopped without a pair that stops");
  if (e.contact.status == ContactStatus::hit) {
    FUZZ_CHECK(!at_start, "hit while a pair starts in contact");
    // The pairs are computed with shorter windows there: the same time to its accuracy.
    const T slack = sizeof(T) >= sizeof(double) ? T(1e-9) : T(1e-4);
    if (!stopped)
      FUZZ_CHECK(e.contact.time <= earliest + slack * earliest, "hit at " << e.contact.time << " after " << earliest);
  }
}

template <class T, int N>
void run(Bytes& in) {
  const int n = 2 + in.byte() % 6;
  std::vector<Ellipsoid<T, N>> bodies;
  std::vector<RigidMotion<T, N>> motions;
  for (int k = 0; k < n; ++k) {
    const auto b = k == 0 ? read_body<T, N>(in) : read_partner<T, N>(in, bodies.back());
    if (!b) return;
    bodies.push_back(*b);
    motions.push_back(read_motion<T, N>(in));
    trace() += describe(*b) + " v " + hex(motions.back().velocity) + "; ";
  }
  const T t_max = in.flag() ? std::numeric_limits<T>::infinity() : static_cast<T>(in.number());
  std::optional<PeriodicBox<N>> box;
  if (in.flag()) {
    box.emplace();
    for (int k = 0; k < N; ++k) box->size[k] = in.number();
    trace() += "box " + hex(Vec<double, N>(Eigen::Map<const Vec<double, N>>(box->size.data())));
  }
  trace() += " t_max " + hex(t_max);

  std::vector<IndexPair> all;
  for (std::uint32_t i = 0; i < bodies.size(); ++i)
    for (std::uint32_t j = i + 1; j < bodies.size(); ++j)
      if (overlap(bodies[i], bodies[j])) all.emplace_back(i, j);
  FUZZ_CHECK((overlapping_pairs<T, N>(bodies)) == all, "overlapping_pairs differs from the all-pairs loop");
  const auto candidates = candidate_pairs<T, N>(bodies);
  FUZZ_CHECK(std::includes(candidates.begin(), candidates.end(), all.begin(), all.end()), "candidates miss a pair");
  if (box) check_periodic(bodies, *box);
  check_earliest(bodies, motions, t_max, box ? &*box : nullptr);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  Bytes in(data, size);
  for_type_and_dim(in, [&]<class T, int N>() { run<T, N>(in); });
  return 0;
}
