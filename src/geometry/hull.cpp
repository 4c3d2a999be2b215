// hull_half_spaces (geometry.hpp): the faces of the convex hull of points as half-spaces.
// 2D: Andrew's monotone chain; 3D: Quickhull (each face keeps the points it sees; the farthest
// is added, the faces it sees replaced by a cone to their horizon). Every combinatorial
// decision is the exact sign of an orientation determinant: a double evaluation where its
// error bound (Shewchuk's) decides, rationals otherwise.
#include <ellipsect/geometry.hpp>
#include <ellipsect/half_space.hpp>

#include "detail/hull.hpp"
#include "detail/instantiate.hpp"
#include "detail/rational.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numeric>
#include <utility>
#include <vector>

namespace ellipsect {
namespace {

using D = detail::rational::Dyadic;
using detail::rational::Q;
using P2 = Eigen::Vector2d;
using P3 = Eigen::Vector3d;

// Shewchuk's filters fail where the products leave double's normal range: decide exactly.
bool filter_holds(double det, double bound) {
  return std::isfinite(det) && bound > 1e-280 && bound < 1e280 && std::abs(det) > bound;
}

// Sign of (a - c) x (b - c): positive where a, b, c turn counterclockwise.
int orient2(const P2& a, const P2& b, const P2& c) {
  const double l = (a.x() - c.x()) * (b.y() - c.y()), r = (a.y() - c.y()) * (b.x() - c.x());
  const double det = l - r;
  if (filter_holds(det, 3.3306690738754716e-16 * (std::abs(l) + std::abs(r)))) return det > 0 ? 1 : -1;
  return sign((D(a.x()) - D(c.x())) * (D(b.y()) - D(c.y())) - (D(a.y()) - D(c.y())) * (D(b.x()) - D(c.x())));
}

// Sign of ((b - a) x (c - a)) . (d - a): positive where d lies on the side of the plane abc
// that (b - a) x (c - a) points to.
int orient3(const P3& a, const P3& b, const P3& c, const P3& d) {
  const P3 ad = a - d, bd = b - d, cd = c - d;
  const double m1 = bd.y() * cd.z(), m2 = bd.z() * cd.y(), m3 = cd.y() * ad.z(), m4 = cd.z() * ad.y(),
               m5 = ad.y() * bd.z(), m6 = ad.z() * bd.y();
  const double det = ad.x() * (m1 - m2) + bd.x() * (m3 - m4) + cd.x() * (m5 - m6);
  const double bound = 7.771561172376103e-16 * ((std::abs(m1) + std::abs(m2)) * std::abs(ad.x()) +
                                                (std::abs(m3) + std::abs(m4)) * std::abs(bd.x()) +
                                                (std::abs(m5) + std::abs(m6)) * std::abs(cd.x()));
  // det above is -(the orientation of a, b, c, d as defined): the determinant of the rows
  // a - d, b - d, c - d equals -(b - a) x (c - a) . (d - a).
  if (filter_holds(det, bound)) return det > 0 ? -1 : 1;
  std::array<std::array<D, 3>, 3> m;
  for (int k = 0; k < 3; ++k) m[0][k] = D(b[k]) - D(a[k]), m[1][k] = D(c[k]) - D(a[k]), m[2][k] = D(d[k]) - D(a[k]);
  return sign(m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
              m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]));
}

// The half-space of a face with the outward normal n (in long double, rounded to T by the
// factory), through the face's vertex deepest along the stored normal (exactly), so that
// every vertex of the face lies on or outside its plane as stored.
template <class T, int N>
HalfSpace<T, N> face_half_space(const Eigen::Matrix<long double, N, 1>& n, std::span<const Vec<T, N>> vertices) {
  // n scaled to a largest coordinate of 1 first: a face of huge or tiny points has a normal
  // beyond T's range.
  const Vec<T, N> unit = (n / n.cwiseAbs().maxCoeff()).template cast<T>();
  const Vec<T, N> normal = HalfSpace<T, N>::from_point_normal(vertices[0], unit).normal();
  const auto exact = [&](std::size_t i) {
    D s;
    for (int k = 0; k < N; ++k) s += D(double(normal[k])) * D(double(vertices[i][k]));
    return s;
  };
  // n . v in double, each within its bound; the exact comparison among the candidates the
  // bounds leave.
  std::vector<double> value(vertices.size()), bound(vertices.size());
  std::size_t deepest = 0;
  for (std::size_t i = 0; i < vertices.size(); ++i) {
    double s = 0, m = 0;
    for (int k = 0; k < N; ++k) s += double(normal[k]) * double(vertices[i][k]), m += std::abs(double(normal[k]) * double(vertices[i][k]));
    value[i] = s, bound[i] = 4 * N * std::numeric_limits<double>::epsilon() * m + std::numeric_limits<double>::denorm_min();
    if (value[i] < value[deepest]) deepest = i;
  }
  const double cut = value[deepest] + bound[deepest];
  D lowest = exact(deepest);
  for (std::size_t i = 0; i < vertices.size(); ++i)
    if (i != deepest && value[i] - bound[i] <= cut)
      if (D s = exact(i); s < lowest) lowest = s, deepest = i;
  return HalfSpace<T, N>::from_point_normal(vertices[deepest], normal);
}

template <class T, int N>
std::vector<Eigen::Matrix<double, N, 1>> in_double(std::span<const Vec<T, N>> points) {
  std::vector<Eigen::Matrix<double, N, 1>> p;
  p.reserve(points.size());
  for (const auto& q : points) p.push_back(q.template cast<double>());
  return p;
}

// The hull's vertices counterclockwise (Andrew's monotone chain: the lower chain left to
// right, then the upper right to left), no collinear vertex kept; fewer than 3 for
// collinear points.
std::vector<std::size_t> chain(const std::vector<P2>& p) {
  std::vector<std::size_t> order(p.size());
  std::iota(order.begin(), order.end(), std::size_t(0));
  std::sort(order.begin(), order.end(), [&](std::size_t i, std::size_t j) {
    return p[i].x() < p[j].x() || (p[i].x() == p[j].x() && (p[i].y() < p[j].y() || (p[i].y() == p[j].y() && i < j)));
  });
  std::vector<std::size_t> hull;
  for (int pass = 0; pass < 2; ++pass) {
    const std::size_t floor = hull.size();
    for (std::size_t k = 0; k < order.size(); ++k) {
      const std::size_t i = pass == 0 ? order[k] : order[order.size() - 1 - k];
      while (hull.size() >= floor + 2 && orient2(p[hull[hull.size() - 2]], p[hull.back()], p[i]) <= 0) hull.pop_back();
      hull.push_back(i);
    }
    hull.pop_back();  // the chain's last point starts the other
  }
  return hull;
}

template <class T>
std::vector<HalfSpace<T, 2>> hull_2d(std::span<const Vec<T, 2>> points) {
  const std::vector<std::size_t> hull = chain(in_double<T, 2>(points));
  if (hull.size() < 3) throw InputError("points", "are collinear (or fewer than 3 distinct): their hull has no interior");
  std::vector<HalfSpace<T, 2>> out;
  for (std::size_t k = 0; k < hull.size(); ++k) {
    const Vec<T, 2> a = points[hull[k]], b = points[hull[(k + 1) % hull.size()]];
    const Eigen::Matrix<long double, 2, 1> d = b.template cast<long double>() - a.template cast<long double>();
    const std::array<Vec<T, 2>, 2> ends{a, b};
    out.push_back(face_half_space<T, 2>({d.y(), -d.x()}, ends));
  }
  return out;
}

// Quickhull's faces: vertices counterclockwise seen from outside; next[e] the face across
// the edge from v[e] to v[(e + 1) % 3].
struct Face {
  explicit Face(std::array<int, 3> vertices) : v(vertices) {}
  std::array<int, 3> v;
  std::array<int, 3> next{-1, -1, -1};
  std::vector<int> outside;  // the points this face sees (first of the faces that see them)
  bool alive = true;
  int round = -1;            // the last add() that tested it
  bool visible = false;      // in that round
};

class Hull3 {
public:
  explicit Hull3(std::vector<P3> p) : p_(std::move(p)) {}

  // The hull's faces (alive among faces()), or false for points of no volume (coplanar,
  // collinear, equal).
  bool build() {
    if (!start()) return false;
    std::vector<int> stack;
    for (int f = 0; f < int(faces_.size()); ++f) stack.push_back(f);
    while (!stack.empty()) {
      const int f = stack.back();
      stack.pop_back();
      if (faces_[std::size_t(f)].alive && !faces_[std::size_t(f)].outside.empty()) add(f, stack);
    }
    return true;
  }

  const std::vector<Face>& faces() const { return faces_; }
  bool sees(const Face& f, int i) const { return orient(f, i) > 0; }
  int orient(const Face& f, int i) const { return orient3(p_[f.v[0]], p_[f.v[1]], p_[f.v[2]], p_[i]); }

private:
  // A first tetrahedron (extreme points by double measures, each choice confirmed exactly,
  // every point tried before volume is denied), and the points each face sees.
  bool start() {
    const int n = int(p_.size());
    int a = 0;
    for (int i = 1; i < n; ++i) if (p_[i].x() < p_[a].x()) a = i;
    int b = farthest(n, [&](int i) { return (p_[i] - p_[a]).squaredNorm(); });
    if (p_[b] == p_[a]) return false;
    int c = farthest(n, [&](int i) { return (p_[i] - p_[a]).cross(p_[b] - p_[a]).squaredNorm(); });
    if (!independent(a, b, c)) {
      c = -1;
      for (int i = 0; i < n && c < 0; ++i) if (independent(a, b, i)) c = i;
      if (c < 0) return false;
    }
    int d = farthest(n, [&](int i) { return std::abs((p_[b] - p_[a]).cross(p_[c] - p_[a]).dot(p_[i] - p_[a])); });
    if (orient3(p_[a], p_[b], p_[c], p_[d]) == 0) {
      d = -1;
      for (int i = 0; i < n && d < 0; ++i) if (orient3(p_[a], p_[b], p_[c], p_[i]) != 0) d = i;
      if (d < 0) return false;
    }
    if (orient3(p_[a], p_[b], p_[c], p_[d]) > 0) std::swap(b, c);  // d below abc
    // Faces abc, adb, bdc, cda: each counterclockwise from outside.
    const std::array<std::array<int, 3>, 4> tet{{{a, b, c}, {a, d, b}, {b, d, c}, {c, d, a}}};
    for (const auto& v : tet) faces_.push_back(Face{v});
    link({0, 1, 2, 3});
    std::vector<int> all;
    for (int i = 0; i < n; ++i) if (i != a && i != b && i != c && i != d) all.push_back(i);
    assign(all, {0, 1, 2, 3});
    return true;
  }

  template <class F>
  int farthest(int n, F measure) const {
    int best = 0;
    double m = -1;
    for (int i = 0; i < n; ++i) if (const double x = measure(i); x > m) m = x, best = i;
    return best;
  }

  bool independent(int a, int b, int i) const {
    // a, b, i not collinear: some coordinate plane's projection turns.
    for (int k = 0; k < 3; ++k) {
      const auto proj = [&](int j) { return P2(p_[j][(k + 1) % 3], p_[j][(k + 2) % 3]); };
      if (orient2(proj(a), proj(b), proj(i)) != 0) return true;
    }
    return false;
  }

  // Neighbors among the listed faces: the face holding the reversed edge.
  void link(const std::vector<int>& ids) {
    for (int f : ids)
      for (int e = 0; e < 3; ++e) {
        const int u = faces_[std::size_t(f)].v[e], w = faces_[std::size_t(f)].v[(e + 1) % 3];
        for (int g : ids)
          for (int k = 0; k < 3; ++k)
            if (faces_[std::size_t(g)].v[k] == w && faces_[std::size_t(g)].v[(k + 1) % 3] == u) faces_[std::size_t(f)].next[e] = g;
      }
  }

  void assign(const std::vector<int>& points, const std::vector<int>& ids) {
    for (int i : points)
      for (int f : ids)
        if (sees(faces_[std::size_t(f)], i)) {
          faces_[std::size_t(f)].outside.push_back(i);
          break;
        }
  }

  // Adds the farthest point face f sees: the faces it sees (connected, from f) give way to
  // a cone from it to their horizon.
  void add(int f0, std::vector<int>& stack) {
    const Face& f = faces_[std::size_t(f0)];
    const P3 n = (p_[f.v[1]] - p_[f.v[0]]).cross(p_[f.v[2]] - p_[f.v[0]]);
    const int eye = *std::max_element(f.outside.begin(), f.outside.end(), [&](int i, int j) {
      return n.dot(p_[i] - p_[f.v[0]]) < n.dot(p_[j] - p_[f.v[0]]);
    });
    std::vector<int> visible{f0};
    ++round_;
    const auto test = [&](int g, bool sees_eye) {
      faces_[std::size_t(g)].round = round_;
      faces_[std::size_t(g)].visible = sees_eye;
    };
    test(f0, true);
    for (std::size_t k = 0; k < visible.size(); ++k)
      for (int h : faces_[std::size_t(visible[k])].next)
        if (faces_[std::size_t(h)].round != round_) {
          test(h, sees(faces_[std::size_t(h)], eye));
          if (faces_[std::size_t(h)].visible) visible.push_back(h);
        }
    std::vector<int> horizon_face, horizon_edge;  // the visible set's edges to the others
    for (int g : visible)
      for (int e = 0; e < 3; ++e)
        if (!faces_[std::size_t(faces_[std::size_t(g)].next[e])].visible) horizon_face.push_back(g), horizon_edge.push_back(e);
    std::vector<int> orphans, made;
    for (int g : visible) {
      faces_[std::size_t(g)].alive = false;
      for (int i : faces_[std::size_t(g)].outside) if (i != eye) orphans.push_back(i);
      faces_[std::size_t(g)].outside.clear();
    }
    std::vector<std::pair<int, int>> starting;  // (the horizon edge's first vertex, its new face)
    for (std::size_t k = 0; k < horizon_face.size(); ++k) {
      const Face& g = faces_[std::size_t(horizon_face[k])];
      const int e = horizon_edge[k], u = g.v[e], w = g.v[(e + 1) % 3], across = g.next[e];
      Face cone({u, w, eye});
      cone.next[0] = across;
      const int id = int(faces_.size());
      Face& other = faces_[std::size_t(across)];
      for (int j = 0; j < 3; ++j)
        if (other.v[j] == w && other.v[(j + 1) % 3] == u) other.next[j] = id;
      faces_.push_back(cone);
      made.push_back(id);
      starting.emplace_back(u, id);
    }
    // Face (u, w, eye): across w -> eye the face starting at w, across eye -> u the one ending at u.
    std::sort(starting.begin(), starting.end());
    for (int id : made) {
      Face& c = faces_[std::size_t(id)];
      c.next[1] = std::lower_bound(starting.begin(), starting.end(), std::pair<int, int>(c.v[1], -1))->second;
      faces_[std::size_t(c.next[1])].next[2] = id;
    }
    assign(orphans, made);
    for (int id : made) stack.push_back(id);
  }

  std::vector<P3> p_;
  std::vector<Face> faces_;
  int round_ = 0;
};

// (b - a) x (c - a) of a face's vertices, exact, rounded to long double.
Eigen::Matrix<long double, 3, 1> exact_normal(const std::vector<P3>& p, const std::array<int, 3>& v) {
  std::array<Q, 3> e1, e2;
  for (int k = 0; k < 3; ++k) e1[k] = Q(p[v[1]][k]) - Q(p[v[0]][k]), e2[k] = Q(p[v[2]][k]) - Q(p[v[0]][k]);
  Eigen::Matrix<long double, 3, 1> n;
  for (int k = 0; k < 3; ++k)
    n[k] = (e1[(k + 1) % 3] * e2[(k + 2) % 3] - e1[(k + 2) % 3] * e2[(k + 1) % 3]).convert_to<long double>();
  return n;
}

template <class T>
std::vector<HalfSpace<T, 3>> hull_3d(std::span<const Vec<T, 3>> points) {
  const std::vector<P3> p = in_double<T, 3>(points);
  Hull3 hull(p);
  if (!hull.build()) throw InputError("points", "are coplanar (or collinear, or equal): their hull has no interior");
  std::vector<Face> faces;
  std::vector<int> index(hull.faces().size(), -1);  // face id -> position in faces
  for (const Face& f : hull.faces())
    if (f.alive) index[std::size_t(&f - hull.faces().data())] = int(faces.size()), faces.push_back(f);
  // Faces in one plane (a neighbor's far vertex on it, exactly) make one half-space: groups
  // by union-find over such edges.
  std::vector<int> parent(faces.size());
  std::iota(parent.begin(), parent.end(), 0);
  const auto root = [&](int i) {
    while (parent[std::size_t(i)] != i) i = parent[std::size_t(i)] = parent[std::size_t(parent[std::size_t(i)])];
    return i;
  };
  for (std::size_t a = 0; a < faces.size(); ++a)
    for (int e = 0; e < 3; ++e) {
      const int b = index[std::size_t(faces[a].next[e])];
      const Face& g = faces[std::size_t(b)];
      int far = g.v[0];
      for (int j = 0; j < 3; ++j)
        if (g.v[j] != faces[a].v[e] && g.v[j] != faces[a].v[(e + 1) % 3]) far = g.v[j];
      if (hull.orient(faces[a], far) == 0) parent[std::size_t(root(int(a)))] = root(b);
    }
  std::vector<std::vector<int>> groups(faces.size());
  for (std::size_t a = 0; a < faces.size(); ++a) groups[std::size_t(root(int(a)))].push_back(int(a));
  std::vector<HalfSpace<T, 3>> out;
  using L3 = Eigen::Matrix<long double, 3, 1>;
  for (const auto& group : groups) {
    if (group.empty()) continue;
    // The normal of the group's largest face (by a double estimate), exact in rationals then
    // rounded to long double (differences of far-apart coordinates lose their small parts in
    // double); its vertices, each once.
    int largest = group[0];
    double area = -1;
    std::vector<int> ids;
    for (int a : group) {
      const auto& v = faces[std::size_t(a)].v;
      if (const double m = (p[v[1]] - p[v[0]]).cross(p[v[2]] - p[v[0]]).squaredNorm(); m > area) area = m, largest = a;
      ids.insert(ids.end(), v.begin(), v.end());
    }
    const L3 n = exact_normal(p, faces[std::size_t(largest)].v);
    std::sort(ids.begin(), ids.end());
    ids.erase(std::unique(ids.begin(), ids.end()), ids.end());
    std::vector<Vec<T, 3>> vertices;
    for (int i : ids) vertices.push_back(points[std::size_t(i)]);
    out.push_back(face_half_space<T, 3>(n, vertices));
  }
  return out;
}

}  // namespace

template <class T, int N>
std::vector<HalfSpace<T, N>> hull_half_spaces(std::span<const Vec<T, N>> points) {
  for (std::size_t i = 0; i < points.size(); ++i)
    if (!points[i].allFinite()) throw RowInputError(i, "points", "must be finite");
  if (points.size() < std::size_t(N + 1))
    throw InputError("points", "must hold at least " + std::to_string(N + 1) + " points (got " +
                                   std::to_string(points.size()) + ")");
  if constexpr (N == 2) {
    return hull_2d<T>(points);
  } else {
    return hull_3d<T>(points);
  }
}

namespace detail {

template <class T, int N>
bool surrounds_origin(std::span<const Vec<T, N>> points) {
  if constexpr (N == 2) {
    const std::vector<P2> p = in_double<T, 2>(points);
    const std::vector<std::size_t> hull = chain(p);
    if (hull.size() < 3) return false;
    for (std::size_t k = 0; k < hull.size(); ++k)
      if (orient2(p[hull[k]], p[hull[(k + 1) % hull.size()]], P2::Zero()) <= 0) return false;
    return true;
  } else {
    std::vector<P3> p = in_double<T, 3>(points);
    p.push_back(P3::Zero());
    const int origin = int(p.size()) - 1;
    Hull3 hull(p);
    if (!hull.build()) return false;
    for (const Face& f : hull.faces())
      if (f.alive && (hull.orient(f, origin) >= 0 || std::find(f.v.begin(), f.v.end(), origin) != f.v.end())) return false;
    return true;
  }
}

}  // namespace detail

#define ELLIPSECT_INSTANTIATE(T, N) \
  template std::vector<HalfSpace<T, N>> hull_half_spaces<T, N>(std::span<const Vec<T, N>>); \
  template bool detail::surrounds_origin<T, N>(std::span<const Vec<T, N>>);
ELLIPSECT_FOR_EACH_TYPE_AND_DIM(ELLIPSECT_INSTANTIATE)
#undef ELLIPSECT_INSTANTIATE

}  // namespace ellipsect
