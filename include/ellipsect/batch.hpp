// Batch queries: overlap, classify and first_contact over arrays of pairs, several pairs
// per instruction (SIMD), on all cores; and every other pair query over spans of bodies, on
// all cores (the section "Every other pair query" below).
//
// Contract: out[i] equals the scalar function's answer for pair i bit for bit (every
// field of a Contact included), at every SIMD width and thread count
// (tests/unit/batch_test.cpp); the accuracy statements of classify.hpp and contact.hpp
// therefore hold unchanged. Invalid pairs cannot be stored: Pairs takes validated
// Ellipsoids, and a non-finite velocity or bad t_max gives ContactStatus::invalid_input
// exactly as first_contact does.
//
// Method (docs/batch.md): a vectorized filter evaluates, for several pairs at once, the
// certificates the scalar functions try first (detail/certificates-inl.hpp: circumscribed
// and inscribed balls, the Perram-Wertheim function with Newton steps on its parameter,
// support points against containment, swept balls for contact), with the same operations
// in the same order, so a pair it decides gets the scalar answer exactly (float pairs:
// overlap and classify by float certificates with proven error bounds, see Pairs). Pairs it leaves
// open (near tangency, aspect ratios above 1e4, containment, contacts that may happen) go
// to the scalar function: 0.4% of random 3D pairs, all near-tangent ones.
//
// SIMD: Highway compiles the filter for each x86-64 instruction set (AVX-512, AVX2, SSE4,
// SSSE3, and a portable scalar fallback) and picks the widest one the CPU has at run
// time; simd_targets() lists them and set_simd_target() pins one (tests, benchmarks).
// Threads: pairs are cut into chunks of 1024 that threads take in turn (a thread per 8
// chunks at most, from a pool kept between calls; a call made while another holds the
// pool, or in a forked child, runs on the calling thread); each answer is written to its
// own slot, so the output never depends on the thread count.
#pragma once

#include <ellipsect/classify.hpp>
#include <ellipsect/contact.hpp>
#include <ellipsect/contact_function.hpp>
#include <ellipsect/distance.hpp>
#include <ellipsect/intersect2.hpp>
#include <ellipsect/options.hpp>
#include <ellipsect/shapes.hpp>

#include <cstddef>
#include <span>
#include <string>
#include <vector>

namespace ellipsect {

struct BatchOptions {
  Options query;    // tolerance and iteration cap, as for the scalar functions
  int threads = 0;  // 0: every hardware thread; 1: the calling thread only
};

// Pairs (a_i, b_i), with velocities and a time window for first_contact, stored as
// structure of arrays: one contiguous column of T per quantity the filter reads, computed
// once per body (in double) when the pair is added (center, S = A diag(r^2) A^T and its
// inverse, the quadric matrix, as packed upper triangles, largest and smallest radius),
// plus the bodies themselves for the scalar fallback. Pairs the scalar functions rescale or
// compute in long double (docs/method.md, section 7) store NaN radii, which sends them to
// the scalar functions.
//
// float: the columns hold S and M rounded to float (centers, radii, velocities and t_max
// are exact), and overlap and classify filter them in float, twice the pairs per
// instruction and half the bytes per pair (detail/certificates_float-inl.hpp). That filter
// proves each answer it gives with bounds on every rounding, including the columns'; it
// decides fewer pairs than the double filter near tangency, and those take the scalar
// functions, so the answers are still theirs.
template <class T, int N>
class Pairs {
public:
  // Columns of one body: N center, 2 * N (N + 1) / 2 for S and M, 2 radii.
  static constexpr int body_columns = N + N * (N + 1) + 2;
  // a's columns, b's columns, velocity_a, velocity_b, t_max.
  static constexpr int columns = 2 * body_columns + 2 * N + 1;

  Pairs() : columns_(columns) {}

  void reserve(std::size_t n);
  // A static pair (zero velocities, t_max = 0: first_contact reports the state at t = 0).
  void push_back(const Ellipsoid<T, N>& a, const Ellipsoid<T, N>& b);
  void push_back(const Ellipsoid<T, N>& a, const Vec<T, N>& velocity_a, const Ellipsoid<T, N>& b,
                 const Vec<T, N>& velocity_b, T t_max);
  void clear();
  // Replaces the contents with the pairs (a[i], b[i]), with velocities and windows in the
  // second form: the columns push_back would store, computed on `threads` threads (0: every
  // hardware thread; batch.hpp's pool). Spans of unequal sizes throw std::invalid_argument.
  void assign(std::span<const Ellipsoid<T, N>> a, std::span<const Ellipsoid<T, N>> b, int threads = 0);
  void assign(std::span<const Ellipsoid<T, N>> a, std::span<const Vec<T, N>> velocity_a,
              std::span<const Ellipsoid<T, N>> b, std::span<const Vec<T, N>> velocity_b, std::span<const T> t_max,
              int threads = 0);

  std::size_t size() const noexcept { return a_.size(); }
  const Ellipsoid<T, N>& a(std::size_t i) const { return a_[i]; }
  const Ellipsoid<T, N>& b(std::size_t i) const { return b_[i]; }
  Vec<T, N> velocity_a(std::size_t i) const;
  Vec<T, N> velocity_b(std::size_t i) const;
  T t_max(std::size_t i) const { return T(columns_[columns - 1][i]); }
  // Column k (see the order above; src/detail/batch_kernels.hpp), size() values.
  const T* column(int k) const noexcept { return columns_[static_cast<std::size_t>(k)].data(); }

private:
  template <class Source>
  void fill(const Source& pairs, int threads);  // assign's work (src/many/batch.cpp)

  std::vector<std::vector<T>> columns_;
  std::vector<Ellipsoid<T, N>> a_, b_;
};
static_assert(detail::has_plain_layout<Pairs<double, 3>, std::vector<std::vector<double>>,
                                       std::vector<Ellipsoid3<double>>, std::vector<Ellipsoid3<double>>>);

// out.size() must equal pairs.size() (std::invalid_argument otherwise).
template <class T, int N>
void overlap(const Pairs<T, N>& pairs, std::span<bool> out, const BatchOptions& options = {});
template <class T, int N>
void classify(const Pairs<T, N>& pairs, std::span<Relation> out, const BatchOptions& options = {});
template <class T, int N>
void first_contact(const Pairs<T, N>& pairs, std::span<Contact<T, N>> out, const BatchOptions& options = {});

// Array-of-structs entry points: pair i is (a[i], b[i]); a, b and out of equal sizes. The
// answers are those of the Pairs overloads; no Pairs is built: each thread computes the
// columns of the chunk it filters, in a buffer of its own (bench/RESULTS.md, "Batch from
// bodies": about 30 ns per 3D overlap pair on 2 cores, against 11 on prebuilt Pairs and
// 360 when a Pairs was built first).
template <class T, int N>
void overlap(std::span<const Ellipsoid<T, N>> a, std::span<const Ellipsoid<T, N>> b, std::span<bool> out,
             const BatchOptions& options = {});
template <class T, int N>
void classify(std::span<const Ellipsoid<T, N>> a, std::span<const Ellipsoid<T, N>> b, std::span<Relation> out,
              const BatchOptions& options = {});
template <class T, int N>
void first_contact(std::span<const Ellipsoid<T, N>> a, std::span<const Vec<T, N>> velocity_a,
                   std::span<const Ellipsoid<T, N>> b, std::span<const Vec<T, N>> velocity_b,
                   std::span<const T> t_max, std::span<Contact<T, N>> out, const BatchOptions& options = {});

// ---- Every other pair query over spans of bodies ------------------------------------------
//
// out[i] is the scalar function's answer for pair i (a[i], b[i], and row i of the other
// spans) bit for bit, at every thread count: the scalar function on every pair, on the
// worker pool (parallel.hpp) in chunks of 64 pairs, options.query passed to it. There is no
// filter: these queries have no early out a batch could vectorize. Spans of unequal sizes
// throw std::invalid_argument, as above; a direction that closest_approach rejects throws
// InputError("direction[i]") before any pair is computed.
template <class T, int N>
void distance(std::span<const Ellipsoid<T, N>> a, std::span<const Ellipsoid<T, N>> b,
              std::span<Distance<T, N>> out, const BatchOptions& options = {});
template <class T, int N>
void signed_distance(std::span<const Ellipsoid<T, N>> a, std::span<const Ellipsoid<T, N>> b,
                     std::span<Distance<T, N>> out, const BatchOptions& options = {});
template <class T, int N>
void signed_distance_gradient(std::span<const Ellipsoid<T, N>> a, std::span<const Ellipsoid<T, N>> b,
                              std::span<DistanceGradient<T, N>> out, const BatchOptions& options = {});
template <class T, int N>
void perram_wertheim(std::span<const Ellipsoid<T, N>> a, std::span<const Ellipsoid<T, N>> b,
                     std::span<ContactFunction<T>> out, const BatchOptions& options = {});
template <class T, int N>
void perram_wertheim_gradient(std::span<const Ellipsoid<T, N>> a, std::span<const Ellipsoid<T, N>> b,
                              std::span<ContactFunctionGradient<T, N>> out, const BatchOptions& options = {});
template <class T, int N>
void closest_approach_gradient(std::span<const Ellipsoid<T, N>> a, std::span<const Ellipsoid<T, N>> b,
                               std::span<const Vec<T, N>> direction, std::span<ClosestApproachGradient<T, N>> out,
                               const BatchOptions& options = {});
// Linear motion, and rigid motion (each body's RigidMotion).
template <class T, int N>
void first_contact_gradient(std::span<const Ellipsoid<T, N>> a, std::span<const Vec<T, N>> velocity_a,
                            std::span<const Ellipsoid<T, N>> b, std::span<const Vec<T, N>> velocity_b,
                            std::span<const T> t_max, std::span<ContactGradient<T, N>> out,
                            const BatchOptions& options = {});
template <class T, int N>
void first_contact_gradient(std::span<const Ellipsoid<T, N>> a, std::span<const RigidMotion<T, N>> motion_a,
                            std::span<const Ellipsoid<T, N>> b, std::span<const RigidMotion<T, N>> motion_b,
                            std::span<const T> t_max, std::span<ContactGradient<T, N>> out,
                            const BatchOptions& options = {});
// Ellipses only (intersect2.hpp).
template <class T>
void overlap_area(std::span<const Ellipse2<T>> a, std::span<const Ellipse2<T>> b, std::span<OverlapArea<T>> out,
                  const BatchOptions& options = {});
template <class T>
void intersection_over_union(std::span<const Ellipse2<T>> a, std::span<const Ellipse2<T>> b, std::span<T> out,
                             const BatchOptions& options = {});
template <class T>
void overlap_area_gradient(std::span<const Ellipse2<T>> a, std::span<const Ellipse2<T>> b,
                           std::span<OverlapAreaGradient<T>> out, const BatchOptions& options = {});
template <class T>
void intersection_over_union_gradient(std::span<const Ellipse2<T>> a, std::span<const Ellipse2<T>> b,
                                      std::span<IouGradient<T>> out, const BatchOptions& options = {});

// Instruction sets the batch functions can use on this CPU, widest first (Highway's
// names: "AVX3" (AVX-512), "AVX2", "SSE4", "SSSE3", "SCALAR" on x86-64).
std::vector<std::string> simd_targets();
// The instruction set in use.
std::string simd_target();
// Pins one of simd_targets() for every later batch call; "" restores the widest. Not
// thread-safe: call it while no batch query runs. Throws InputError for an unknown name.
void set_simd_target(const std::string& name);

}  // namespace ellipsect
