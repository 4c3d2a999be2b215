// Exact classification (Options::tolerance = 0) on pairs whose relation is known by
// construction: integer and dyadic data, axes that are signed permutation matrices (exactly
// orthonormal), bodies touching on a coordinate axis; then the same pairs with b moved or
// grown by one ulp, which makes the relation strict in a direction derived below.
//
// Claim under test (options.hpp, classify.hpp, contact.hpp, distance.hpp, batch.hpp): at
// tolerance 0, classify answers the exact relation of the bodies as stored (the closed
// quadrics of the stored centers, axes and radii), overlap answers relation != separated,
// first_contact with zero velocities reports touching_at_start exactly for touching pairs
// and overlapping_at_start for overlapping, containing and equal ones, signed_distance
// reports touching / overlapping / separated likewise, and the batch forms give the same
// answers; for float and double, 2D and 3D, both argument orders, at scales 2^-500 to 2^500
// (float: 2^-60 to 2^60), at the origin and 2^30 sizes from it (float: 2^10). At the
// default tolerance the exact tangencies are still touching (the band model), and a
// perturbation wider than the band (one ulp of a float, or of a far coordinate) gets the
// exact answer too.
//
// Why each perturbation has its relation (d: the unit coordinate direction from a's center
// to the contact point, along which both bodies are symmetric):
//   external tangency: the plane normal to d through the contact point separates the
//     bodies and meets each in that point alone. b moved along +d, or its radius along d
//     shrunk, lies strictly beyond the plane: separated. b moved along -d, or its radius
//     along d grown, covers the contact point moved into both interiors: overlapping.
//   internal tangency at one point (b inside a, both extreme along d at the contact point,
//     containment shown for each pair below): b moved along +d or grown along d has a point
//     beyond a's extreme point along d: overlapping (its center stays inside a). b moved
//     along -d lies strictly inside (for each pair below the containment measure decreases
//     under that move), as does b shrunk along d (a subset of b): a_contains_b.
//   internal tangency at two points (concentric, tangent at +-d): any move along d pushes b
//     beyond a on one side: overlapping; grown along d: overlapping; shrunk: a_contains_b.
//   equal (the same set stored with other axes, or column signs): b moved by an ulp is a
//     translate of a, neither contains the other, interiors meet: overlapping; b's radius
//     along d grown: b contains a (tangent from inside elsewhere): b_contains_a; shrunk:
//     a_contains_b.
#include <ellipsect/batch.hpp>
#include <ellipsect/classify.hpp>
#include <ellipsect/contact.hpp>
#include <ellipsect/distance.hpp>

#include "tests/support.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <initializer_list>
#include <iterator>
#include <limits>
#include <memory>
#include <span>
#include <sstream>
#include <string>
#include <vector>

namespace {
namespace ELLIPSECT_UNITY_ID {

using namespace ellipsect;
using namespace ellipsect::testing;

enum class Kind { external, inside_one_point, inside_two_points, equal };
enum class Nudge { none, out, in, grow, shrink };
constexpr const char* nudge_names[] = {"exact", "b moved +d by an ulp", "b moved -d by an ulp",
                                       "b's radius along d up an ulp", "b's radius along d down an ulp"};

// The relation of (a, b) for each nudge of b (see the top of the file).
Relation expected(Kind kind, Nudge nudge) {
  using R = Relation;
  constexpr R table[4][5] = {
      {R::touching, R::separated, R::overlapping, R::overlapping, R::separated},
      {R::a_contains_b, R::overlapping, R::a_contains_b, R::overlapping, R::a_contains_b},
      {R::a_contains_b, R::overlapping, R::overlapping, R::overlapping, R::a_contains_b},
      {R::equal, R::overlapping, R::overlapping, R::b_contains_a, R::a_contains_b},
  };
  return table[static_cast<int>(kind)][static_cast<int>(nudge)];
}

Relation mirrored(Relation r) {
  if (r == Relation::a_contains_b) return Relation::b_contains_a;
  if (r == Relation::b_contains_a) return Relation::a_contains_b;
  return r;
}

ContactStatus contact_status(Relation r) {
  if (r == Relation::separated) return ContactStatus::no_contact_in_window;
  return r == Relation::touching ? ContactStatus::touching_at_start : ContactStatus::overlapping_at_start;
}

DistanceStatus distance_status(Relation r) {
  if (r == Relation::separated) return DistanceStatus::separated;
  return r == Relation::touching ? DistanceStatus::touching : DistanceStatus::overlapping;
}

// A body in base units (integers and halves), axes a signed permutation.
template <int N>
struct Shape {
  Vec<double, N> center;
  Mat<double, N> axes;
  Vec<double, N> radii;
};

template <int N>
struct Config {
  std::string name;
  Kind kind;
  Shape<N> a, b;
  Vec<double, N> d;  // unit coordinate direction from a's center to the contact point
};

template <int N>
Vec<double, N> vec(std::initializer_list<double> v) {
  Vec<double, N> out;
  int i = 0;
  for (double x : v) out[i++] = x;
  return out;
}

// Axes whose column j is sign(s_j) e_|s_j| (1-based): perm<3>({2, 3, 1}) = (e2, e3, e1).
template <int N>
Mat<double, N> perm(std::initializer_list<int> s) {
  Mat<double, N> m = Mat<double, N>::Zero();
  int j = 0;
  for (int k : s) m(std::abs(k) - 1, j++) = k > 0 ? 1 : -1;
  return m;
}

// Index of the column of `axes` along d (axes a signed permutation, d a signed axis).
template <int N>
int column_along(const Mat<double, N>& axes, const Vec<double, N>& d) {
  int j;
  (axes.transpose() * d).cwiseAbs().maxCoeff(&j);
  return j;
}

// Extent of a body from its center along the signed axis d: its radius along d.
template <int N>
double extent(const Mat<double, N>& axes, const Vec<double, N>& radii, const Vec<double, N>& d) {
  return radii[column_along<N>(axes, d)];
}

// a at `center`; b placed on the line center + s d so that the bodies touch at a's extreme
// point along d: from outside (external) or from inside (inside_one_point); concentric for
// inside_two_points and equal.
template <int N>
Config<N> config(std::string name, Kind kind, const Vec<double, N>& center, const Mat<double, N>& axes_a,
                 const Vec<double, N>& radii_a, const Mat<double, N>& axes_b, const Vec<double, N>& radii_b,
                 const Vec<double, N>& d) {
  const double ea = extent<N>(axes_a, radii_a, d), eb = extent<N>(axes_b, radii_b, d);
  const double s = kind == Kind::external ? ea + eb : kind == Kind::inside_one_point ? ea - eb : 0;
  return {std::move(name), kind, {center, axes_a, radii_a}, {center + s * d, axes_b, radii_b}, d};
}

std::vector<Config<2>> configs2() {
  const auto I = perm<2>({1, 2});
  const auto x = vec<2>({1, 0}), y = vec<2>({0, 1}), mx = vec<2>({-1, 0}), my = vec<2>({0, -1});
  const auto c0 = vec<2>({0, 0}), c1 = vec<2>({3, -2});
  using K = Kind;
  return {
      config<2>("circles 3 and 2, centers 5 apart", K::external, c0, I, vec<2>({3, 3}), I, vec<2>({2, 2}), x),
      config<2>("ellipse (2, 1), unit circle at (3, 0)", K::external, c0, I, vec<2>({2, 1}), I, vec<2>({1, 1}), x),
      config<2>("ellipse (2, 1), unit circle below it", K::external, c1, I, vec<2>({2, 1}), I, vec<2>({1, 1}), my),
      config<2>("ellipses (2, 1) and (1, 3) side by side", K::external, c1, I, vec<2>({2, 1}), I, vec<2>({1, 3}), mx),
      config<2>("ellipses (2, 1) and (1, 3) stacked", K::external, c0, I, vec<2>({2, 1}), I, vec<2>({1, 3}), y),
      config<2>("two copies of ellipse (2, 1), along x", K::external, c1, I, vec<2>({2, 1}), I, vec<2>({2, 1}), x),
      config<2>("two copies of ellipse (2, 1), along y", K::external, c0, I, vec<2>({2, 1}), I, vec<2>({2, 1}), y),
      config<2>("ellipse (2, 1) standing, ellipse (3, 1/2) lying", K::external, c1, perm<2>({2, -1}),
                vec<2>({2, 1}), I, vec<2>({3, 0.5}), x),
      // |x - c_b| <= 2 gives |x| <= 3 + 2 = 5, equality only at (5, 0).
      config<2>("circle 2 inside circle 5, centers 3 apart", K::inside_one_point, c1, I, vec<2>({5, 5}), I,
                vec<2>({2, 2}), x),
      // The circle (7/2 + c/2, s/2) gives q_a = (13.25 + 3.5 c - 0.75 c^2) / 16, increasing in
      // c on [-1, 1] (slope 3.5 - 1.5 c > 0) to 1 at c = 1: inside, tangent at (4, 0) only;
      // moved towards the center, q_a decreases at every point.
      config<2>("circle 1/2 inside ellipse (4, 2) at (7/2, 0)", K::inside_one_point, c0, I, vec<2>({4, 2}), I,
                vec<2>({0.5, 0.5}), x),
      // x^2/4 + y^2 <= 1 gives x^2 + y^2 <= 4 - 3 y^2 <= 4, equality at (+-2, 0).
      config<2>("ellipse (2, 1) inside circle 2, concentric", K::inside_two_points, c1, I, vec<2>({2, 2}), I,
                vec<2>({2, 1}), x),
      // x^2 + y^2 <= 1 gives x^2/4 + y^2 <= 1 - 3 x^2/4, equality at (0, +-1).
      config<2>("circle 1 inside ellipse (2, 1), concentric", K::inside_two_points, c0, I, vec<2>({2, 1}), I,
                vec<2>({1, 1}), my),
      // Radii componentwise no larger (each term of b's form dominates a's), equal along x.
      config<2>("ellipse (2, 1) inside ellipse (2, 3), concentric", K::inside_two_points, c1, I, vec<2>({2, 3}), I,
                vec<2>({2, 1}), x),
      config<2>("ellipse (2, 1), axes turned a quarter, radii swapped", K::equal, c1, I, vec<2>({2, 1}),
                perm<2>({2, -1}), vec<2>({1, 2}), x),
      config<2>("ellipse (3, 1), axes' signs flipped", K::equal, c0, I, vec<2>({3, 1}), perm<2>({-1, -2}),
                vec<2>({3, 1}), y),
      config<2>("circle 2 and a copy", K::equal, c1, I, vec<2>({2, 2}), I, vec<2>({2, 2}), mx),
  };
}

std::vector<Config<3>> configs3() {
  const auto I = perm<3>({1, 2, 3});
  const auto x = vec<3>({1, 0, 0}), y = vec<3>({0, 1, 0}), z = vec<3>({0, 0, 1}), mz = vec<3>({0, 0, -1});
  const auto c0 = vec<3>({0, 0, 0}), c1 = vec<3>({-2, 3, 1});
  const auto r321 = vec<3>({3, 2, 1}), unit = vec<3>({1, 1, 1});
  using K = Kind;
  return {
      config<3>("spheres 3 and 2, centers 5 apart", K::external, c0, I, vec<3>({3, 3, 3}), I, vec<3>({2, 2, 2}), x),
      config<3>("ellipsoid (2, 1, 1), unit sphere at (3, 0, 0)", K::external, c0, I, vec<3>({2, 1, 1}), I, unit, x),
      config<3>("ellipsoid (3, 2, 1), unit ball along x", K::external, c1, I, r321, I, unit, x),
      config<3>("ellipsoid (3, 2, 1), unit ball along y", K::external, c0, I, r321, I, unit, y),
      config<3>("ellipsoid (3, 2, 1), unit ball along -z", K::external, c1, I, r321, I, unit, mz),
      config<3>("two copies of ellipsoid (3, 2, 1), along x", K::external, c0, I, r321, I, r321, x),
      config<3>("two copies of ellipsoid (3, 2, 1), along y", K::external, c1, I, r321, I, r321, y),
      config<3>("two copies of ellipsoid (3, 2, 1), along z", K::external, c0, I, r321, I, r321, z),
      config<3>("ellipsoid (3, 2, 1), ellipsoid (3, 2, 1/2) on permuted axes", K::external, c1, I, r321,
                perm<3>({2, 3, 1}), vec<3>({3, 2, 0.5}), z),
      // |x - c_b| <= 1 gives |x| <= 2 + 1 = 3, equality only at (0, 3, 0).
      config<3>("ball 1 inside ball 3, centers 2 apart", K::inside_one_point, c1, I, vec<3>({3, 3, 3}), I, unit, y),
      // As the 2D pair: with z radius 3 >= 2, q_a is at most the spheroid (4, 2, 2)'s value,
      // (13.25 + 3.5 c - 0.75 c^2) / 16 <= 1, equality only at (4, 0, 0).
      config<3>("ball 1/2 inside ellipsoid (4, 2, 3) at (7/2, 0, 0)", K::inside_one_point, c0, I,
                vec<3>({4, 2, 3}), I, vec<3>({0.5, 0.5, 0.5}), x),
      // |x|^2 = x^2 + y^2 + z^2 <= 9 (x^2/9 + y^2/4 + z^2) <= 9, equality at (+-3, 0, 0).
      config<3>("ellipsoid (3, 2, 1) inside ball 3, concentric", K::inside_two_points, c1, I, vec<3>({3, 3, 3}), I,
                r321, x),
      // x^2/9 + y^2/4 + z^2 <= |x|^2 <= 1, equality at (0, 0, +-1).
      config<3>("ball 1 inside ellipsoid (3, 2, 1), concentric", K::inside_two_points, c0, I, r321, I, unit, mz),
      config<3>("ellipsoid (3, 1, 1/2) inside (3, 2, 1), concentric", K::inside_two_points, c1, I, r321, I,
                vec<3>({3, 1, 0.5}), x),
      config<3>("ellipsoid (3, 2, 1) on cyclically permuted axes", K::equal, c0, I, r321, perm<3>({2, 3, 1}),
                vec<3>({2, 1, 3}), y),
      config<3>("ellipsoid (3, 2, 1), two axes' signs flipped", K::equal, c1, I, r321, perm<3>({-1, 2, -3}), r321, z),
  };
}

// Quarter turns applied to a whole configuration: the identity, and one that moves every
// axis (2D: a quarter turn; 3D: a quarter turn about z, then one about x).
template <int N>
std::vector<Mat<double, N>> quarter_turns() {
  if constexpr (N == 2) return {perm<2>({1, 2}), perm<2>({2, -1})};
  else return {perm<3>({1, 2, 3}), perm<3>({3, -1, -2})};
}

template <class T>
struct Range;
template <>
struct Range<double> {
  static constexpr int scales[] = {-500, -200, -60, 0, 60, 200, 500};
  static constexpr int far = 30;  // log2 of the offset, in sizes
  static constexpr const char* name = "double";
};
template <>
struct Range<float> {
  static constexpr int scales[] = {-60, -20, 0, 20, 60};
  static constexpr int far = 10;
  static constexpr const char* name = "float";
};

template <class T, int N>
struct Case {
  Ellipsoid<T, N> a, b;
  Relation want;
  bool pinned_by_band;  // exact, or perturbed by more than the default band: known at 1e-12 too
  std::string where;
};

// The configuration turned by q, scaled by 2^k, moved by `offset` (times 2^k), with b
// nudged; as Ellipsoid<T, N>. Every coordinate is checked to be exact in T.
template <class T, int N>
Case<T, N> make_case(const Config<N>& c, const Mat<double, N>& q, int k, const Vec<double, N>& offset,
                     Nudge nudge, const std::string& where) {
  bool exact = true;
  auto stored = [&](double base, double off) {
    const double v = std::ldexp(base, k) + std::ldexp(off, k);
    exact = exact && v - std::ldexp(off, k) == std::ldexp(base, k) && double(T(v)) == v;
    return T(v);
  };
  auto body = [&](const Shape<N>& s, Vec<T, N>& center, Mat<T, N>& axes, Vec<T, N>& radii) {
    const Vec<double, N> turned = q * s.center;
    for (int i = 0; i < N; ++i) center[i] = stored(turned[i], offset[i]);
    for (int i = 0; i < N; ++i) radii[i] = stored(s.radii[i], 0);
    axes = (q * s.axes).template cast<T>();
  };
  Vec<T, N> ca, cb, ra, rb;
  Mat<T, N> axa, axb;
  body(c.a, ca, axa, ra);
  body(c.b, cb, axb, rb);
  EXPECT_TRUE(exact) << where << ": the data is not exact in " << Range<T>::name;
  const Vec<double, N> d = q * c.d;
  int i;
  d.cwiseAbs().maxCoeff(&i);
  const T up = std::numeric_limits<T>::infinity();
  const T toward_d = d[i] > 0 ? up : -up;
  const int j = column_along<N>(q * c.b.axes, d);
  double moved = 0;  // the nudge's length, in units of 2^k
  auto step = [&](T& v, T toward) {
    const T w = std::nextafter(v, toward);
    moved = std::ldexp(std::abs(double(w) - double(v)), -k);
    v = w;
  };
  if (nudge == Nudge::out) step(cb[i], toward_d);
  if (nudge == Nudge::in) step(cb[i], -toward_d);
  if (nudge == Nudge::grow) step(rb[j], up);
  if (nudge == Nudge::shrink) step(rb[j], -up);
  std::ostringstream label;
  label << where;
  if (nudge != Nudge::none) label << " (" << moved << " of 2^k)";
  return {Ellipsoid<T, N>::from_axes(ca, axa, ra), Ellipsoid<T, N>::from_axes(cb, axb, rb),
          expected(c.kind, nudge), nudge == Nudge::none || moved > 1e-8, label.str()};
}

template <class T, int N>
std::vector<Case<T, N>> all_cases(const std::vector<Config<N>>& configs) {
  std::vector<Case<T, N>> cases;
  const auto turns = quarter_turns<N>();
  // The sanitizer pass (ELLIPSECT_CASE_SCALE < 1): the smallest, unit and largest scales.
  std::vector<int> scales(std::begin(Range<T>::scales), std::end(Range<T>::scales));
  if (!full_case_counts()) scales = {scales.front(), 0, scales.back()};
  for (const auto& c : configs)
    for (std::size_t t = 0; t < turns.size(); ++t)
      for (int k : scales)
        for (int far : {0, 1})
          for (int n = 0; n < 5; ++n) {
            Vec<double, N> offset;
            for (int i = 0; i < N; ++i) offset[i] = far ? std::ldexp(i % 2 == 0 ? 1.0 : -1.0, Range<T>::far) : 0;
            std::ostringstream where;
            where << Range<T>::name << " " << N << "D \"" << c.name << "\"" << (t > 0 ? " turned" : "") << " scale 2^"
                  << k << (far ? " far" : "") << ", " << nudge_names[n];
            const auto x = make_case<T, N>(c, turns[t], k, offset, Nudge(n), where.str());
            cases.push_back(x);
            cases.push_back({x.b, x.a, mirrored(x.want), x.pinned_by_band, x.where + ", arguments swapped"});
          }
  return cases;
}

// Every query on every case: the scalar functions, then the batch forms over all of them.
template <class T, int N>
void check_queries(const std::vector<Case<T, N>>& cases, const Options& options, const std::string& tol,
                   AnswerCount& answers) {
  const Vec<T, N> still = Vec<T, N>::Zero();
  const BatchOptions batch{.query = options};
  Pairs<T, N> pairs;
  std::vector<Ellipsoid<T, N>> as, bs;
  for (const auto& c : cases) {
    answers.check(c.where, "classify " + tol, c.want, classify(c.a, c.b, options));
    answers.check(c.where, "overlap " + tol, c.want != Relation::separated, overlap(c.a, c.b, options));
    answers.check(c.where, "first_contact " + tol, contact_status(c.want),
                  first_contact(c.a, still, c.b, still, T(1), options).status);
    answers.check(c.where, "signed_distance " + tol, distance_status(c.want), signed_distance(c.a, c.b, options).status);
    pairs.push_back(c.a, still, c.b, still, T(1));
    as.push_back(c.a);
    bs.push_back(c.b);
  }
  const std::size_t n = cases.size();
  std::vector<Relation> relations(n), relations_aos(n);
  const auto overlaps = std::make_unique<bool[]>(n);
  std::vector<Contact<T, N>> contacts(n);
  classify(pairs, std::span<Relation>(relations), batch);
  overlap(pairs, std::span<bool>(overlaps.get(), n), batch);
  first_contact(pairs, std::span<Contact<T, N>>(contacts), batch);
  classify(std::span<const Ellipsoid<T, N>>(as), std::span<const Ellipsoid<T, N>>(bs),
           std::span<Relation>(relations_aos), batch);
  for (std::size_t i = 0; i < n; ++i) {
    const auto& c = cases[i];
    answers.check(c.where, "batch classify " + tol, c.want, relations[i]);
    answers.check(c.where, "batch classify (arrays) " + tol, c.want, relations_aos[i]);
    answers.check(c.where, "batch overlap " + tol, c.want != Relation::separated, overlaps[i]);
    answers.check(c.where, "batch first_contact " + tol, contact_status(c.want), contacts[i].status);
  }
}

template <class T, int N>
void check_exact(const std::vector<Config<N>>& configs) {
  const Options exact = exact_options;
  const auto cases = all_cases<T, N>(configs);
  AnswerCount answers;
  check_queries<T, N>(cases, exact, "(tolerance 0)", answers);
  answers.report(std::string("exact, ") + Range<T>::name + " " + std::to_string(N) + "D, " +
                 std::to_string(cases.size()) + " pairs");
}

// The default band: the exact tangencies (touching, internal tangency, equal) and the
// perturbations wider than the band keep the relations above.
template <class T, int N>
void check_default_band(const std::vector<Config<N>>& configs) {
  std::vector<Case<T, N>> cases;
  for (const auto& c : all_cases<T, N>(configs))
    if (c.pinned_by_band) cases.push_back(c);
  AnswerCount answers;
  check_queries<T, N>(cases, Options{}, "(tolerance 1e-12)", answers);
  answers.report(std::string("default band, ") + Range<T>::name + " " + std::to_string(N) + "D, " +
                 std::to_string(cases.size()) + " pairs");
}

TEST(ExactClassify, TangentPairs2D) {
  check_exact<double, 2>(configs2());
  check_exact<float, 2>(configs2());
}
TEST(ExactClassify, TangentPairs3D) {
  check_exact<double, 3>(configs3());
  check_exact<float, 3>(configs3());
}
TEST(ExactClassify, DefaultBandOnTangentPairs2D) {
  check_default_band<double, 2>(configs2());
  check_default_band<float, 2>(configs2());
}
TEST(ExactClassify, DefaultBandOnTangentPairs3D) {
  check_default_band<double, 3>(configs3());
  check_default_band<float, 3>(configs3());
}

}  // namespace ELLIPSECT_UNITY_ID
}  // namespace
