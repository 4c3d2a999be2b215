// Batch queries (include/ellipsect/batch.hpp): the SIMD certificate filter on chunks of
// pairs, the scalar function on the pairs it leaves open, chunks shared among threads.
#include <ellipsect/batch.hpp>
#include <ellipsect/gpu.hpp>
#include <ellipsect/parallel.hpp>

#include "detail/batch_gpu.hpp"
#include "detail/batch_kernels.hpp"
#include "detail/certificates-inl.hpp"
#include "detail/classify_impl.hpp"
#include "detail/instantiate.hpp"
#include "detail/scale.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>
#include <stdexcept>
#include <type_traits>

namespace ellipsect {

static_assert(Pairs<double, 2>::body_columns == detail::BodyLayout{2}.size());
static_assert(Pairs<double, 3>::body_columns == detail::BodyLayout{3}.size());

namespace {

// put(k, value) for every column k of pair (a, b) (Pairs' layout; M's columns only for
// Fill::quadric): Pairs::push_back and the span overloads' chunks. Pairs the scalar
// functions rescale or widen (detail/scale.hpp) are left to them: NaN radii fail every
// certificate's comparison, so the filter leaves the pair open.
template <class T, int N, class Put>
void put_pair(const Ellipsoid<T, N>& a, const Vec<T, N>& velocity_a, const Ellipsoid<T, N>& b,
              const Vec<T, N>& velocity_b, T t_max, detail::HWY_NAMESPACE::Fill fill, const Put& put) {
  constexpr detail::BodyLayout layout{N};
  constexpr int body_columns = Pairs<T, N>::body_columns;
  detail::Scale scale = detail::scale_of(a, b);
  scale.time = detail::time_exponent(scale, velocity_a, velocity_b);
  const bool open = !scale.as_given();
  auto body = [&](int first, const Ellipsoid<T, N>& e) {
    const auto lanes = detail::HWY_NAMESPACE::lanes_of(e, fill);
    for (int i = 0; i < N; ++i) {
      put(first + layout.center(i), lanes.c[i]);
      for (int j = i; j < N; ++j) {
        put(first + layout.s(i, j), lanes.s[i][j]);
        if (fill == detail::HWY_NAMESPACE::Fill::quadric) put(first + layout.m(i, j), lanes.m[i][j]);
      }
    }
    put(first + layout.rmax(), open ? NAN : lanes.rmax);
    put(first + layout.rmin(), open ? NAN : lanes.rmin);
  };
  body(0, a);
  body(body_columns, b);
  for (int i = 0; i < N; ++i) {
    put(2 * body_columns + i, double(velocity_a[i]));
    put(2 * body_columns + N + i, double(velocity_b[i]));
  }
  put(Pairs<T, N>::columns - 1, double(t_max));
}

}  // namespace

template <class T, int N>
void Pairs<T, N>::reserve(std::size_t n) {
  for (auto& c : columns_) c.reserve(n);
  a_.reserve(n);
  b_.reserve(n);
}

template <class T, int N>
void Pairs<T, N>::push_back(const Ellipsoid<T, N>& a, const Ellipsoid<T, N>& b) {
  push_back(a, Vec<T, N>::Zero(), b, Vec<T, N>::Zero(), T(0));
}

template <class T, int N>
void Pairs<T, N>::push_back(const Ellipsoid<T, N>& a, const Vec<T, N>& velocity_a, const Ellipsoid<T, N>& b,
                            const Vec<T, N>& velocity_b, T t_max) {
  put_pair(a, velocity_a, b, velocity_b, t_max, detail::HWY_NAMESPACE::Fill::quadric,
           [this](int k, double value) { columns_[static_cast<std::size_t>(k)].push_back(T(value)); });
  a_.push_back(a);
  b_.push_back(b);
}

template <class T, int N>
void Pairs<T, N>::clear() {
  for (auto& c : columns_) c.clear();
  a_.clear();
  b_.clear();
}

template <class T, int N>
Vec<T, N> Pairs<T, N>::velocity_a(std::size_t i) const {
  Vec<T, N> v;
  for (int k = 0; k < N; ++k) v[k] = T(columns_[static_cast<std::size_t>(2 * body_columns + k)][i]);
  return v;
}

template <class T, int N>
Vec<T, N> Pairs<T, N>::velocity_b(std::size_t i) const {
  Vec<T, N> v;
  for (int k = 0; k < N; ++k) v[k] = T(columns_[static_cast<std::size_t>(2 * body_columns + N + k)][i]);
  return v;
}

namespace {

constexpr std::size_t chunk = 1024;           // pairs per unit of work (a thread takes whole chunks)
constexpr std::size_t chunks_per_thread = 8;  // at least ~100 us of work per thread asked for


// BatchOptions::threads (0: all hardware threads), at most `at_most` (and at least 1).
int threads_wanted(int threads, std::size_t at_most) {
  const std::size_t cap = std::clamp<std::size_t>(at_most, 1, std::numeric_limits<int>::max());
  return threads > 0 ? int(std::min(std::size_t(threads), cap)) : int(cap);
}

// Calls work(begin, end) on every chunk of [0, n), on up to `threads` threads (0: all
// hardware threads; at most the pool and the caller).
template <class Work>
void for_each_chunk(std::size_t n, int threads, const Work& work) {
  const std::size_t chunks = (n + chunk - 1) / chunk;
  parallel_for(chunks, threads_wanted(threads, (chunks + chunks_per_thread - 1) / chunks_per_thread),
           [&](std::size_t c) { work(c * chunk, std::min(n, (c + 1) * chunk)); });
}

template <class T, int N>
std::array<const T*, Pairs<T, N>::columns> columns_of(const Pairs<T, N>& pairs) {
  std::array<const T*, Pairs<T, N>::columns> columns;
  for (int k = 0; k < Pairs<T, N>::columns; ++k) columns[static_cast<std::size_t>(k)] = pairs.column(k);
  return columns;
}

void require_size(std::size_t out_size, std::size_t pairs) {
  if (out_size != pairs) throw std::invalid_argument("ellipsect: out.size() must equal the number of pairs");
}

// `answer(i, code)` writes pair i's result from its code (0: undecided, the scalar function
// answers) on each chunk; the codes are `given` (all pairs') or the filter's on the chunk.
template <class T, int N, class Answer>
void run_batch(const Pairs<T, N>& pairs, std::size_t out_size, detail::BatchQuery query, const BatchOptions& options,
               const Answer& answer, const signed char* given = nullptr) {
  require_size(out_size, pairs.size());
  const auto columns = columns_of(pairs);
  for_each_chunk(pairs.size(), options.threads, [&](std::size_t begin, std::size_t end) {
    std::array<signed char, chunk> codes;
    const signed char* code = given ? given + begin : codes.data();
    if (!given) detail::certify_pairs(N, query, columns.data(), begin, end, options.query.tolerance, codes.data());
    for (std::size_t i = begin; i < end; ++i) answer(i, code[i - begin]);
  });
}

// run_batch with the codes from the GPU where it gives them (double columns: the device
// runs the double filter; float pairs are filtered on the CPU, gpu.hpp).
template <class T, int N, class Answer>
Backend run_on_gpu(const Pairs<T, N>& pairs, std::size_t out_size, detail::BatchQuery query,
                   const BatchOptions& options, const Answer& answer) {
  if constexpr (detail::gpu_built && std::is_same_v<T, double>) {
    require_size(out_size, pairs.size());  // before the device's work
    std::vector<signed char> codes(pairs.size());
    const auto parallel_for = [&options](std::size_t n, const std::function<void(std::size_t, std::size_t)>& work) {
      for_each_chunk(n, options.threads, work);
    };
    const bool on_gpu = detail::certify_pairs_gpu(N, query, columns_of(pairs).data(), pairs.size(),
                                                  options.query.tolerance, codes.data(), parallel_for);
    run_batch(pairs, out_size, query, options, answer, on_gpu ? codes.data() : nullptr);
    return on_gpu ? Backend::gpu : Backend::cpu;
  } else {
    run_batch(pairs, out_size, query, options, answer);
    return Backend::cpu;
  }
}

// Pairs given as spans of bodies (the array-of-structs entry points), read as Pairs are.
template <class T, int N>
struct BodySpans {
  std::span<const Ellipsoid<T, N>> as, bs;
  std::span<const Vec<T, N>> velocities_a, velocities_b;  // empty: at rest
  std::span<const T> t_maxes;                             // empty: t_max = 0

  std::size_t size() const noexcept { return as.size(); }
  const Ellipsoid<T, N>& a(std::size_t i) const { return as[i]; }
  const Ellipsoid<T, N>& b(std::size_t i) const { return bs[i]; }
  Vec<T, N> velocity_a(std::size_t i) const { return velocities_a.empty() ? Vec<T, N>::Zero() : velocities_a[i]; }
  Vec<T, N> velocity_b(std::size_t i) const { return velocities_b.empty() ? Vec<T, N>::Zero() : velocities_b[i]; }
  T t_max(std::size_t i) const { return t_maxes.empty() ? T(0) : t_maxes[i]; }
};

// BodySpans of static pairs, or of moving ones; spans of unequal sizes throw.
template <class T, int N>
BodySpans<T, N> body_spans(std::span<const Ellipsoid<T, N>> a, std::span<const Ellipsoid<T, N>> b) {
  if (a.size() != b.size()) throw std::invalid_argument("ellipsect: a and b must have equal sizes");
  return {a, b, {}, {}, {}};
}

template <class T, int N>
BodySpans<T, N> body_spans(std::span<const Ellipsoid<T, N>> a, std::span<const Vec<T, N>> velocity_a,
                           std::span<const Ellipsoid<T, N>> b, std::span<const Vec<T, N>> velocity_b,
                           std::span<const T> t_max) {
  const std::size_t n = a.size();
  if (b.size() != n || velocity_a.size() != n || velocity_b.size() != n || t_max.size() != n)
    throw std::invalid_argument("ellipsect: a, velocity_a, b, velocity_b and t_max must have equal sizes");
  return {a, b, velocity_a, velocity_b, t_max};
}

// At least `size` values of C of the calling thread's own, kept for the thread (one buffer
// for every query and dimension: at most 336 KB, 3D double).
template <class C>
C* thread_buffer(std::size_t size) {
  thread_local std::vector<C> buffer;
  if (buffer.size() < size) buffer.resize(size);
  return buffer.data();
}

// run_batch on spans of bodies: each thread fills the columns of its chunk in a buffer of
// its own (kept for the thread), so no Pairs of the whole array is built, on one thread,
// before the filter runs (it cost about 30 times the filter on 1M pairs).
template <class T, int N, class Answer>
void run_batch(const BodySpans<T, N>& pairs, std::size_t out_size, detail::BatchQuery query,
               const BatchOptions& options, const Answer& answer) {
  require_size(out_size, pairs.size());
  constexpr int columns = Pairs<T, N>::columns;
  namespace hw = detail::HWY_NAMESPACE;
  // The columns the filter reads: M for classify only.
  const hw::Fill fill = query == detail::BatchQuery::classify ? hw::Fill::quadric : hw::Fill::shape;
  for_each_chunk(pairs.size(), options.threads, [&](std::size_t begin, std::size_t end) {
    // Columns a cache line apart beyond their length: at a stride of exactly 8 KB, the
    // rows' writes to the 41 columns would all fall in one set of the L1 cache.
    constexpr std::size_t stride = chunk + 64 / sizeof(T);
    T* const buffer = thread_buffer<T>(columns * stride);
    std::array<const T*, columns> column;
    for (int k = 0; k < columns; ++k) column[static_cast<std::size_t>(k)] = buffer + k * stride;
    for (std::size_t i = begin; i < end; ++i)
      put_pair(pairs.a(i), pairs.velocity_a(i), pairs.b(i), pairs.velocity_b(i), pairs.t_max(i), fill,
               [&](int k, double value) { buffer[static_cast<std::size_t>(k) * stride + (i - begin)] = T(value); });
    std::array<signed char, chunk> codes;
    detail::certify_pairs(N, query, column.data(), 0, end - begin, options.query.tolerance, codes.data());
    for (std::size_t i = begin; i < end; ++i) answer(i, codes[i - begin]);
  });
}

template <class P>
auto overlap_answer(const P& pairs, std::span<bool> out, const BatchOptions& options) {
  return [&pairs, out, &options](std::size_t i, signed char code) {
    out[i] = code != 0 ? code > 0 : overlap(pairs.a(i), pairs.b(i), options.query);
  };
}

template <class P>
auto classify_answer(const P& pairs, std::span<Relation> out, const BatchOptions& options) {
  return [&pairs, out, &options](std::size_t i, signed char code) {
    out[i] = code != 0 ? detail::certified_relation(code) : classify(pairs.a(i), pairs.b(i), options.query);
  };
}

template <class P, class T, int N>
auto contact_answer(const P& pairs, std::span<Contact<T, N>> out, const BatchOptions& options) {
  return [&pairs, out, &options](std::size_t i, signed char code) {
    if (code > 0) {  // what first_contact answers when the swept balls stay apart
      Contact<T, N> c;
      c.status = ContactStatus::no_contact_in_window;
      c.time = std::numeric_limits<T>::quiet_NaN();
      c.point.setConstant(c.time);
      c.normal.setConstant(c.time);
      out[i] = c;
    } else {
      out[i] = first_contact(pairs.a(i), pairs.velocity_a(i), pairs.b(i), pairs.velocity_b(i), pairs.t_max(i),
                             options.query);
    }
  };
}

}  // namespace

template <class T, int N>
template <class Source>
void Pairs<T, N>::fill(const Source& pairs, int threads) {
  const std::size_t n = pairs.size();
  clear();
  // Sizing the columns and copying the bodies writes fresh memory (568 bytes per 3D pair):
  // one job per column on the pool, as the filling below. A job that fails to allocate
  // ends the assignment with its exception, the contents cleared.
  const std::size_t jobs = columns + 2;
  try {
    parallel_for(jobs, threads_wanted(threads, n >= chunk * chunks_per_thread ? jobs : 1), [&](std::size_t j) {
      if (j < columns)
        columns_[j].resize(n);
      else if (j == columns)
        a_.assign(pairs.as.begin(), pairs.as.end());
      else
        b_.assign(pairs.bs.begin(), pairs.bs.end());
    });
  } catch (...) {
    clear();
    throw;
  }
  for_each_chunk(n, threads, [&](std::size_t begin, std::size_t end) {
    for (std::size_t i = begin; i < end; ++i)
      put_pair(pairs.a(i), pairs.velocity_a(i), pairs.b(i), pairs.velocity_b(i), pairs.t_max(i),
               detail::HWY_NAMESPACE::Fill::quadric,
               [&](int k, double value) { columns_[static_cast<std::size_t>(k)][i] = T(value); });
  });
}

template <class T, int N>
void Pairs<T, N>::assign(std::span<const Ellipsoid<T, N>> a, std::span<const Ellipsoid<T, N>> b, int threads) {
  fill(body_spans(a, b), threads);
}

template <class T, int N>
void Pairs<T, N>::assign(std::span<const Ellipsoid<T, N>> a, std::span<const Vec<T, N>> velocity_a,
                         std::span<const Ellipsoid<T, N>> b, std::span<const Vec<T, N>> velocity_b,
                         std::span<const T> t_max, int threads) {
  fill(body_spans(a, velocity_a, b, velocity_b, t_max), threads);
}

template <class T, int N>
void overlap(const Pairs<T, N>& pairs, std::span<bool> out, const BatchOptions& options) {
  run_batch(pairs, out.size(), detail::BatchQuery::overlap, options, overlap_answer(pairs, out, options));
}

template <class T, int N>
void classify(const Pairs<T, N>& pairs, std::span<Relation> out, const BatchOptions& options) {
  run_batch(pairs, out.size(), detail::BatchQuery::classify, options, classify_answer(pairs, out, options));
}

template <class T, int N>
Backend overlap_on_gpu(const Pairs<T, N>& pairs, std::span<bool> out, const BatchOptions& options) {
  return run_on_gpu(pairs, out.size(), detail::BatchQuery::overlap, options, overlap_answer(pairs, out, options));
}

template <class T, int N>
Backend classify_on_gpu(const Pairs<T, N>& pairs, std::span<Relation> out, const BatchOptions& options) {
  return run_on_gpu(pairs, out.size(), detail::BatchQuery::classify, options, classify_answer(pairs, out, options));
}

GpuInfo gpu_info() {
  const detail::GpuDevice device = detail::gpu_device();
  return {detail::gpu_built, device.count, device.name};
}

std::string_view to_string(Backend b) noexcept { return b == Backend::gpu ? "gpu" : "cpu"; }

template <class T, int N>
void first_contact(const Pairs<T, N>& pairs, std::span<Contact<T, N>> out, const BatchOptions& options) {
  run_batch(pairs, out.size(), detail::BatchQuery::contact, options, contact_answer(pairs, out, options));
}

template <class T, int N>
void overlap(std::span<const Ellipsoid<T, N>> a, std::span<const Ellipsoid<T, N>> b, std::span<bool> out,
             const BatchOptions& options) {
  const BodySpans<T, N> pairs = body_spans(a, b);
  run_batch(pairs, out.size(), detail::BatchQuery::overlap, options, overlap_answer(pairs, out, options));
}

template <class T, int N>
void classify(std::span<const Ellipsoid<T, N>> a, std::span<const Ellipsoid<T, N>> b, std::span<Relation> out,
              const BatchOptions& options) {
  const BodySpans<T, N> pairs = body_spans(a, b);
  run_batch(pairs, out.size(), detail::BatchQuery::classify, options, classify_answer(pairs, out, options));
}

template <class T, int N>
void first_contact(std::span<const Ellipsoid<T, N>> a, std::span<const Vec<T, N>> velocity_a,
                   std::span<const Ellipsoid<T, N>> b, std::span<const Vec<T, N>> velocity_b,
                   std::span<const T> t_max, std::span<Contact<T, N>> out, const BatchOptions& options) {
  const BodySpans<T, N> pairs = body_spans(a, velocity_a, b, velocity_b, t_max);
  run_batch(pairs, out.size(), detail::BatchQuery::contact, options, contact_answer(pairs, out, options));
}

#define ELLIPSECT_INSTANTIATE(T, N)                                                                              \
  template class Pairs<T, N>;                                                                                    \
  template void overlap<T, N>(const Pairs<T, N>&, std::span<bool>, const BatchOptions&);                         \
  template void classify<T, N>(const Pairs<T, N>&, std::span<Relation>, const BatchOptions&);                    \
  template Backend overlap_on_gpu<T, N>(const Pairs<T, N>&, std::span<bool>, const BatchOptions&);               \
  template Backend classify_on_gpu<T, N>(const Pairs<T, N>&, std::span<Relation>, const BatchOptions&);          \
  template void first_contact<T, N>(const Pairs<T, N>&, std::span<Contact<T, N>>, const BatchOptions&);          \
  template void overlap<T, N>(std::span<const Ellipsoid<T, N>>, std::span<const Ellipsoid<T, N>>,                \
                              std::span<bool>, const BatchOptions&);                                             \
  template void classify<T, N>(std::span<const Ellipsoid<T, N>>, std::span<const Ellipsoid<T, N>>,               \
                               std::span<Relation>, const BatchOptions&);                                        \
  template void first_contact<T, N>(std::span<const Ellipsoid<T, N>>, std::span<const Vec<T, N>>,                \
                                    std::span<const Ellipsoid<T, N>>, std::span<const Vec<T, N>>,                \
                                    std::span<const T>, std::span<Contact<T, N>>, const BatchOptions&);
ELLIPSECT_FOR_EACH_TYPE_AND_DIM(ELLIPSECT_INSTANTIATE)
#undef ELLIPSECT_INSTANTIATE

}  // namespace ellipsect
