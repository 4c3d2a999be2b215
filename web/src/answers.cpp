#include "answers.hpp"

#include <ellipsect/ellipsect.hpp>
#include <ellipsect/packing.hpp>

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <optional>
#include <random>
#include <stdexcept>

namespace ellipsect::web {
namespace {

double get(const Params& p, const std::string& name) {
  const auto it = p.find(name);
  if (it == p.end()) throw std::out_of_range("missing parameter " + name);
  return it->second;
}

Vec2<double> point(const Params& p, const std::string& x, const std::string& y) { return {get(p, x), get(p, y)}; }

Ellipse2<double> ellipse(const Params& p, const std::string& n) {
  return make_ellipse<double>(point(p, n + ".cx", n + ".cy"), get(p, n + ".angle"),
                              point(p, n + ".r0", n + ".r1"));
}

Circle<double> circle(const Params& p, const std::string& n) {
  return make_circle<double>(point(p, n + ".cx", n + ".cy"), get(p, n + ".r"));
}

std::vector<double> list(const Vec2<double>& v) { return {v.x(), v.y()}; }

std::vector<double> list(const std::vector<Vec2<double>>& vs) {
  std::vector<double> out;
  out.reserve(2 * vs.size());
  for (const auto& v : vs) out.insert(out.end(), {v.x(), v.y()});
  return out;
}

std::string label(std::string_view s) { return std::string(s); }

// The parameter "dim": 2 or 3 (InputError "dim" otherwise).
int dimension(const Params& p) {
  const double dim = get(p, "dim");
  if (dim != 2 && dim != 3) throw InputError("dim", "must be 2 or 3");
  return int(dim);
}

Vec3<double> point3(const Params& p, const std::string& n) { return {get(p, n + "x"), get(p, n + "y"), get(p, n + "z")}; }

std::vector<double> list3(const Vec3<double>& v) { return {v.x(), v.y(), v.z()}; }

template <int N>
std::vector<double> coordinates(const Vec<double, N>& v) {
  if constexpr (N == 2) return list(v); else return list3(v);
}

// prefix + k, as "w3" (appended, not `indexed("w", k)`, where GCC 12 warns falsely
// of an overlapping memcpy).
std::string indexed(std::string_view prefix, int k) {
  std::string out(prefix);
  out += std::to_string(k);
  return out;
}

// Indices as a label: "3,0,12".
std::string indices(const std::vector<int>& ks) {
  std::string out;
  for (const int k : ks) {
    if (!out.empty()) out += ',';
    out += std::to_string(k);
  }
  return out;
}

// The seed's demo 1: the closed form's foot of the normal from the circle's center; the
// circle collides when the center is inside (the early out) or the foot within its radius.
void add_closest(Answer& out, const std::string& name, const QuarticPoint<double>& q, double radius) {
  const char* verdict = q.status == QuarticStatus::inside    ? "early_out"
                        : q.status != QuarticStatus::outside ? "failed"
                        : q.distance <= radius               ? "collision"
                                                             : "no_collision";
  out.insert(out.end(), {{name + ".status", label(to_string(q.status))},
                         {name + ".point", list(q.point)},
                         {name + ".distance", q.distance},
                         {name + ".verdict", std::string(verdict)}});
}

const char* collides(bool hit) { return hit ? "collision" : "no_collision"; }

// The exact answer for an ellipse and a circle (a point when the radius is 0).
bool exact_overlap(const Ellipse2<double>& e, const Circle<double>& c) {
  return c.radius() > 0 ? overlap(e, c.ellipse()) : closest_point(e, c.center()).signed_distance <= 0;
}

Answer ellipse_circle(const Params& p) {
  const auto e = ellipse(p, "e");
  const auto c = circle(p, "c");
  Answer out;
  add_closest(out, "closed", closest_point_closed_form(e, c.center()), c.radius());
  add_closest(out, "quartic", closest_point_quartic(e, c.center()), c.radius());
  out.emplace_back("exact", collides(exact_overlap(e, c)));
  return out;
}

Answer segment(const Params& p) {
  const SegmentCircle s = segment_circle<double>(point(p, "s.ax", "s.ay"), point(p, "s.bx", "s.by"), circle(p, "c"));
  return {{"verdict", label(to_string(s.verdict))}, {"side", label(to_string(s.side))}};
}

// Polygons of the levels drawn: 0 .. min(deepest level examined, this).
constexpr int drawn_levels = 8;

Answer polygonal(const Params& p) {
  const auto a = ellipse(p, "a");
  const int max_level = static_cast<int>(get(p, "level"));
  const bool is_circle = get(p, "body") == 0, cover = get(p, "cover") != 0;
  PolygonalOverlap<double> r;
  bool exact;
  if (is_circle) {
    const auto c = circle(p, "c");
    r = cover ? circle_cover_overlap(a, c, max_level) : polygonal_overlap(a, c, max_level);
    exact = exact_overlap(a, c);
  } else {
    const auto b = ellipse(p, "b");
    r = polygonal_overlap(a, b, max_level);
    exact = overlap(a, b);
  }
  Answer out{{"verdict", label(to_string(r.verdict))},
             {"level", double(r.level)},
             {"iterations", double(r.iterations)},
             {"gap_lo", r.gap_lo},
             {"gap_hi", r.gap_hi},
             {"error_bound", niemitalo_error_bound(a, max_level)},
             {"exact", collides(exact)}};
  const int levels = std::clamp(r.level, 0, drawn_levels);
  out.emplace_back("drawn_levels", double(levels + 1));
  for (int n = 0; n <= levels; ++n) {
    const NiemitaloPolygons<double> poly = niemitalo_polygons(a, n);
    out.emplace_back(indexed("inscribed.", n), list(poly.inscribed));
    out.emplace_back(indexed("circumscribed.", n), list(poly.circumscribed));
  }
  return out;
}

// Eberly's reduced frame of a and b moving apart at `velocity` (b's less a's) (his figures
// 2.2 and 3.1): Y = diag(1 / r_a) R_a^T (X - K_a) makes a the unit ball; b becomes the quadric
// M2 = S^T M_b S (S the inverse map) about K2, whose principal axes R (from_quadric) give
// Z = R^T Y, where b is axis-aligned: reduced.center, reduced.radii, reduced.p (b's point
// nearest the origin: a and b touch where it is at distance 1) and reduced.velocity (b's in Z).
template <int N>
void add_reduced_frame(Answer& out, const Ellipsoid<double, N>& a, const Ellipsoid<double, N>& b,
                       const Vec<double, N>& velocity) {
  const Mat<double, N> to_y = a.radii().cwiseInverse().asDiagonal() * a.axes().transpose();
  const Mat<double, N> from_y = a.axes() * a.radii().asDiagonal();
  Mat<double, N> m2 = from_y.transpose() * b.quadric() * from_y;
  m2 = (0.5 * (m2 + m2.transpose())).eval();
  const auto by = Ellipsoid<double, N>::from_quadric(to_y * (b.center() - a.center()), m2);
  const Mat<double, N> to_z = by.axes().transpose();
  const auto bz = Ellipsoid<double, N>::from_axes(to_z * by.center(), Mat<double, N>::Identity(), by.radii());
  const ClosestPoint<double, N> cp = closest_point(bz, Vec<double, N>::Zero());
  out.insert(out.end(), {{"reduced.center", coordinates<N>(bz.center())},
                         {"reduced.radii", coordinates<N>(bz.radii())},
                         {"reduced.p", coordinates<N>(cp.point)},
                         {"reduced.velocity", coordinates<N>(Vec<double, N>(to_z * to_y * velocity))}});
}

// Eberly's first contact, the bodies at the viewed time t, and the reduced frame at t.
Answer swept(const Params& p) {
  const auto a0 = ellipse(p, "a"), b0 = ellipse(p, "b");
  const Vec2<double> va = point(p, "a.vx", "a.vy"), vb = point(p, "b.vx", "b.vy");
  const double t = get(p, "t");
  const Contact<double, 2> c = first_contact(a0, va, b0, vb, get(p, "t_max"));
  const auto a = a0.translated(t * va), b = b0.translated(t * vb);
  Answer out{{"status", label(to_string(c.status))},
          {"time", c.time},
          {"point", list(c.point)},
          {"normal", list(c.normal)},
          {"iterations", double(c.iterations)},
          {"relation_t", label(to_string(classify(a, b)))},
          {"a_center_t", list(a.center())},
          {"b_center_t", list(b.center())}};
  add_reduced_frame<2>(out, a, b, Vec2<double>(vb - va));
  return out;
}

Answer relation(const Params& p) {
  const auto a = ellipse(p, "a"), b = ellipse(p, "b");
  const Distance<double, 2> d = signed_distance(a, b);
  const BoundaryIntersection<double> x = intersect_boundaries(a, b);
  const OverlapArea<double> area = overlap_area(a, b);
  std::vector<double> points;
  std::string kinds;
  for (int i = 0; i < x.count; ++i) {
    points.insert(points.end(), {x.points[i].x(), x.points[i].y()});
    kinds += std::string(i ? "," : "") + std::string(to_string(x.kinds[i]));
  }
  return {{"relation", label(to_string(classify(a, b)))},
          {"distance.status", label(to_string(d.status))},
          {"distance", d.distance},
          {"point_a", list(d.point_a)},
          {"point_b", list(d.point_b)},
          {"normal", list(d.normal)},
          {"crossings.status", label(to_string(x.status))},
          {"crossings.count", double(x.count)},
          {"crossings.points", points},
          {"crossings.kinds", kinds},
          {"area", area.area},
          {"iou", intersection_over_union(a, b)}};
}

// Collide and slide through the half-planes w0 ... w(walls - 1) (wK.px, wK.py: a point of
// the boundary; wK.nx, wK.ny: the outward normal) towards the target (tx, ty).
Answer slide(const Params& p) {
  const auto e = ellipse(p, "e");
  std::vector<HalfSpace<double, 2>> world;
  for (int k = 0; k < static_cast<int>(get(p, "walls")); ++k) {
    const std::string w = indexed("w", k);
    world.push_back(make_half_space<double, 2>(point(p, w + ".px", w + ".py"), point(p, w + ".nx", w + ".ny")));
  }
  const Vec2<double> displacement = point(p, "tx", "ty") - e.center();
  const Slide<double, 2> s = collide_and_slide(e, displacement, std::span<const HalfSpace<double, 2>>(world));
  return {{"status", label(to_string(s.status))},
          {"contacts", double(s.contacts)},
          {"last_contact", double(s.last_contact)},
          {"end", list(s.body.center())},
          {"moved", list(s.moved)}};
}

// Points to bodies (geometry.hpp): the points p0 .. p(n-1) (pk.x, pk.y); the enclosing
// ellipse, the hull's faces (points and outward normals) with the largest ellipse inside
// them, and the least-squares ellipse. Each part answers or says why not (its .error).
void add_ellipse(Answer& out, const std::string& name, const Ellipse2<double>& e) {
  out.insert(out.end(), {{name + ".center", list(e.center())},
                         {name + ".angle", std::atan2(e.axes()(1, 0), e.axes()(0, 0))},
                         {name + ".radii", list(e.radii())}});
}

template <class F>
void part(Answer& out, const std::string& name, F f) {
  try {
    f();
  } catch (const InputError& e) {
    out.emplace_back(name + ".error", std::string(e.what()));
  }
}

Answer geometry(const Params& p) {
  std::vector<Vec2<double>> points;
  const int n = static_cast<int>(get(p, "n"));
  for (int k = 0; k < n; ++k) points.push_back(point(p, indexed("p", k) + ".x", indexed("p", k) + ".y"));
  Answer out;
  part(out, "enclose", [&] {
    const auto e = enclosing_ellipsoid<double, 2>(points);
    out.insert(out.end(), {{"enclose.status", label(to_string(e.status))},
                           {"enclose.volume_gap", e.volume_gap},
                           {"enclose.iterations", double(e.iterations)},
                           {"enclose.support", list(e.support_points)}});
    add_ellipse(out, "enclose", e.body);
  });
  part(out, "inscribe", [&] {
    const std::vector<HalfSpace<double, 2>> faces = hull_half_spaces<double, 2>(points);
    std::vector<double> at, normals;
    for (const auto& f : faces) at.insert(at.end(), {f.point().x(), f.point().y()}), normals.insert(normals.end(), {f.normal().x(), f.normal().y()});
    out.insert(out.end(), {{"hull.faces", double(faces.size())}, {"hull.points", at}, {"hull.normals", normals}});
    const auto e = inscribed_ellipsoid<double, 2>(faces);
    out.insert(out.end(), {{"inscribe.status", label(to_string(e.status))},
                           {"inscribe.volume_gap", e.volume_gap},
                           {"inscribe.iterations", double(e.iterations)}});
    add_ellipse(out, "inscribe", e.body);
  });
  part(out, "fit", [&] {
    const auto f = fit_ellipsoid<double, 2>(points);
    out.insert(out.end(), {{"fit.status", label(to_string(f.status))},
                           {"fit.rms_residual", f.rms_residual},
                           {"fit.max_residual", f.max_residual},
                           {"fit.iterations", double(f.iterations)}});
    add_ellipse(out, "fit", f.body);
  });
  return out;
}


// ---- 3D ---------------------------------------------------------------------------------


// Runs f; an InputError comes out naming the field within the body `n` ("a.radii[1]").
template <class F>
auto within(const std::string& n, F f) {
  try {
    return f();
  } catch (const InputError& e) {
    const std::string said = e.what(), prefix = "ellipsect: " + e.field() + ": ";
    throw InputError(n + "." + e.field(), said.starts_with(prefix) ? said.substr(prefix.size()) : said);
  }
}

// A 3D body "x": its center x.cx, x.cy, x.cz, radii x.r0, x.r1, x.r2 and axes Rz(x.yaw)
// Ry(x.pitch) Rx(x.roll) (radians; the columns of the rotation are the axes of the radii).
Ellipsoid3<double> ellipsoid3(const Params& p, const std::string& n) {
  using Turn = Eigen::AngleAxisd;
  const Mat3<double> axes = (Turn(get(p, n + ".yaw"), Eigen::Vector3d::UnitZ()) *
                             Turn(get(p, n + ".pitch"), Eigen::Vector3d::UnitY()) *
                             Turn(get(p, n + ".roll"), Eigen::Vector3d::UnitX())).toRotationMatrix();
  const Vec3<double> radii{get(p, n + ".r0"), get(p, n + ".r1"), get(p, n + ".r2")};
  return within(n, [&] { return make_ellipsoid<double>(point3(p, n + ".c"), axes, radii); });
}

// The pair explorer's body "x" in N dimensions: in 3D ellipsoid3's; in 2D the ellipse of
// center x.cx, x.cy, radii x.r0, x.r1, turned by x.yaw (the turn about z).
template <int N>
Ellipsoid<double, N> pair_body(const Params& p, const std::string& n) {
  if constexpr (N == 3) {
    return ellipsoid3(p, n);
  } else {
    return within(n, [&] {
      return make_ellipse<double>(point(p, n + ".cx", n + ".cy"), get(p, n + ".yaw"), point(p, n + ".r0", n + ".r1"));
    });
  }
}

// A body as the library stores it, for drawing: name.center, name.axes (column-major N x N),
// name.radii.
template <int N>
void add_body(Answer& out, const std::string& name, const Ellipsoid<double, N>& e) {
  const Mat<double, N> axes = e.axes();
  out.insert(out.end(), {{name + ".center", coordinates<N>(e.center())},
                         {name + ".axes", std::vector<double>(axes.data(), axes.data() + N * N)},
                         {name + ".radii", coordinates<N>(e.radii())}});
}

template <int N>
void add_gradient(Answer& out, const std::string& name, const BodyGradient<double, N>& g) {
  Value turn;
  if constexpr (N == 2) turn = g.orientation; else turn = list3(g.orientation);
  out.insert(out.end(), {{name + ".center", coordinates<N>(g.center)},
                         {name + ".orientation", turn},
                         {name + ".radii", coordinates<N>(g.radii)}});
}

// Two ellipsoids a and b (or, with dim 2, ellipses: pair_body): the relation, the signed
// distance with its witnesses and its gradient by each body's parameters (gradient.hpp), the
// Perram-Wertheim F with mu = sqrt(F) (the factor by which both bodies, scaled about their
// centers, touch), and the distance of closest approach along the line of the centers
// (compared with the centers' distance).
template <int N>
Answer pair_answer(const Params& p) {
  const auto a = pair_body<N>(p, "a"), b = pair_body<N>(p, "b");
  const DistanceGradient<double, N> g = signed_distance_gradient(a, b);
  const Distance<double, N>& d = g.value;
  const ContactFunction<double> f = perram_wertheim(a, b);
  Answer out;
  add_body(out, "a", a);
  add_body(out, "b", b);
  out.insert(out.end(), {{"relation", label(to_string(classify(a, b)))},
                         {"distance.status", label(to_string(d.status))},
                         {"distance", d.distance},
                         {"point_a", coordinates<N>(d.point_a)},
                         {"point_b", coordinates<N>(d.point_b)},
                         {"normal", coordinates<N>(d.normal)}});
  add_gradient(out, "gradient.a", g.a);
  add_gradient(out, "gradient.b", g.b);
  out.insert(out.end(), {{"pw.status", label(to_string(f.status))},
                         {"pw.f", f.f},
                         {"pw.mu", std::sqrt(f.f)},
                         {"pw.lambda", f.lambda},
                         {"center_distance", (b.center() - a.center()).norm()}});
  part(out, "approach", [&] {
    const ClosestApproach<double, N> c = closest_approach(a, b, Vec<double, N>(b.center() - a.center()));
    out.insert(out.end(), {{"approach.status", label(to_string(c.status))},
                           {"approach.distance", c.distance},
                           {"approach.point", coordinates<N>(c.point)},
                           {"approach.normal", coordinates<N>(c.normal)}});
  });
  return out;
}

// A body's rigid motion "x": velocity x.vx, x.vy, x.vz; angular velocity x.wx, x.wy, x.wz
// (radians per unit time); growth x.g (contact.hpp).
RigidMotion<double, 3> motion3(const Params& p, const std::string& n) {
  RigidMotion<double, 3> m;
  m.velocity = point3(p, n + ".v");
  m.angular_velocity = point3(p, n + ".w");
  m.growth = get(p, n + ".g");
  return m;
}

// The samples of a sampling CCD over the window: overlap at t_k = k t_max / 10, k = 1 .. 10.
constexpr int ccd_samples = 10;

// Bodies a and b in rigid motion (motion3) over [0, t_max]: the certified first contact
// (contact.hpp), the bodies at 0, at the viewed time t and at the contact time, and what a sampling
// CCD makes of the window: the samples' overlaps, the first sample that overlaps, and its
// verdict against the certified contact (missed: no sample overlaps; late: the first that
// does is after the contact, by sampling.delay; agrees: neither finds a contact). "motion":
// linear where neither body spins or grows (first_contact then answers by Eberly's
// translational method), with the reduced frame at t (add_reduced_frame); rigid otherwise.
Answer motion3d(const Params& p) {
  const auto a = ellipsoid3(p, "a"), b = ellipsoid3(p, "b");
  const auto ma = motion3(p, "a"), mb = motion3(p, "b");
  const double t_max = get(p, "t_max"), t = get(p, "t");
  const auto at = [&](double s) {
    return std::pair{within("a", [&] { return body_at(a, ma, s); }), within("b", [&] { return body_at(b, mb, s); })};
  };
  const auto [a_t, b_t] = at(t);  // throws for a motion first_contact would call invalid_input
  const Contact<double, 3> c = first_contact(a, ma, b, mb, t_max);
  if (c.status == ContactStatus::invalid_input) throw InputError("t_max", "must be >= 0 (first_contact: invalid_input)");
  Answer out{{"contact.status", label(to_string(c.status))},
             {"contact.time", c.time},
             {"contact.point", list3(c.point)},
             {"contact.normal", list3(c.normal)},
             {"contact.iterations", double(c.iterations)}};
  add_body(out, "a", a);
  add_body(out, "b", b);
  add_body(out, "a_t", a_t);
  add_body(out, "b_t", b_t);
  out.emplace_back("relation_t", label(to_string(classify(a_t, b_t))));
  const bool linear = ma.angular_velocity.isZero(0.0) && mb.angular_velocity.isZero(0.0) && ma.growth == 0.0 &&
                      mb.growth == 0.0;
  out.emplace_back("motion", std::string(linear ? "linear" : "rigid"));
  if (linear) add_reduced_frame<3>(out, a_t, b_t, Vec3<double>(mb.velocity - ma.velocity));
  const bool contact = c.status == ContactStatus::hit || c.status == ContactStatus::touching_at_start ||
                       c.status == ContactStatus::overlapping_at_start;
  if (contact) {
    const auto [a_c, b_c] = at(c.time);
    add_body(out, "a_c", a_c);
    add_body(out, "b_c", b_c);
  }
  std::vector<double> times, overlaps;
  double first = std::nan("");
  for (int k = 1; k <= ccd_samples; ++k) {
    const double s = k * t_max / ccd_samples;
    const auto [a_s, b_s] = at(s);
    const bool hit = overlap(a_s, b_s);
    times.push_back(s);
    overlaps.push_back(hit ? 1.0 : 0.0);
    if (hit && std::isnan(first)) first = s;
  }
  const char* verdict = !contact ? (std::isnan(first) ? "agrees" : "contradicts")
                        : std::isnan(first) ? "missed"
                                            : "late";
  out.insert(out.end(), {{"samples.times", times},
                         {"samples.overlap", overlaps},
                         {"sampling.time", first},
                         {"sampling.delay", contact ? first - c.time : std::nan("")},
                         {"sampling.verdict", std::string(verdict)}});
  return out;
}

}  // namespace

// Where the body touches the triangle (NaN when it does not).
template <int N>
Vec<double, N> touching_point(const Ellipsoid<double, N>& body, const Triangle<double, N>& triangle) {
  const Vec<double, N> still = Vec<double, N>::Zero();
  const Contact<double, N> c = first_contact(body, still, triangle, still, 0.0);
  return c.status == ContactStatus::touching_at_start ? c.point : Vec<double, N>::Constant(std::nan(""));
}

// Collide and slide of the ellipse (2D: "e" as ellipse() reads it) or ellipsoid (3D: as
// ellipsoid3() reads it) through the triangle mesh of the vertices v0 ... v(vertices - 1)
// (vK.x, vK.y, and in 3D vK.z) and the triangles t0 ... t(triangles - 1) (tK.a, tK.b, tK.c:
// vertex indices; a repeated index makes a segment) towards the target (tx, ty, and in 3D tz):
// the slide, its path round by round with the triangle hit and the contact point of each round
// that ended at a contact, and at the end the mesh's relation and each triangle touched with
// its contact point (3D: the start body too, for drawing).
// Slide holds no per-round record, so the rounds are replayed: with Options::max_slide_rounds
// = k the slide makes its first k rounds (slide.hpp), those of the uncapped call (the
// triangle queries are closed forms, untouched by the cap: triangle.hpp); k runs to the
// first cap at which the slide is not blocked, which is the number of rounds.
template <int N>
Answer mesh_slide(const Params& p) {
  const Ellipsoid<double, N> e = [&] {
    if constexpr (N == 2) return ellipse(p, "e"); else return ellipsoid3(p, "e");
  }();
  const Vec<double, N> target = [&] {
    if constexpr (N == 2) return point(p, "tx", "ty"); else return point3(p, "t");
  }();
  std::vector<double> vertices;
  for (int k = 0; k < static_cast<int>(get(p, "vertices")); ++k) {
    const std::string v = indexed("v", k);
    for (int d = 0; d < N; ++d) vertices.push_back(get(p, v + '.' + "xyz"[d]));
  }
  std::vector<std::int64_t> triangles;
  for (int k = 0; k < static_cast<int>(get(p, "triangles")); ++k)
    for (const char* corner : {".a", ".b", ".c"})
      triangles.push_back(static_cast<std::int64_t>(get(p, indexed("t", k) + corner)));
  const auto mesh = TriangleMesh<double, N>::from_arrays(vertices, triangles);
  const Vec<double, N> displacement = target - e.center();
  const Slide<double, N> s = collide_and_slide(e, displacement, mesh);

  int rounds = 0;
  std::vector<double> path = coordinates<N>(e.center()), hit_points;
  std::vector<int> hits;
  if (s.status == SlideStatus::moved || s.status == SlideStatus::slid || s.status == SlideStatus::blocked) {
    for (Options cap; rounds < Options{}.max_slide_rounds;) {
      cap.max_slide_rounds = ++rounds;
      const Slide<double, N> r = collide_and_slide(e, displacement, mesh, cap);
      const std::vector<double> at_end = coordinates<N>(r.body.center());
      path.insert(path.end(), at_end.begin(), at_end.end());
      if (r.contacts > static_cast<int>(hits.size())) {
        hits.push_back(r.last_contact);
        const std::vector<double> at = coordinates<N>(touching_point(r.body, mesh.triangle(r.last_contact)));
        hit_points.insert(hit_points.end(), at.begin(), at.end());
      }
      if (r.status != SlideStatus::blocked) break;
    }
  }

  const MeshRelation end = classify(s.body, mesh);
  std::vector<int> touched;
  std::vector<double> touched_points;
  for (std::size_t k = 0; k < mesh.triangle_count(); ++k) {
    const Vec<double, N> at = touching_point(s.body, mesh.triangle(k));
    if (std::isnan(at.x())) continue;
    touched.push_back(static_cast<int>(k));
    const std::vector<double> c = coordinates<N>(at);
    touched_points.insert(touched_points.end(), c.begin(), c.end());
  }
  Answer out{{"status", label(to_string(s.status))},
             {"contacts", double(s.contacts)},
             {"last_contact", double(s.last_contact)},
             {"end", coordinates<N>(s.body.center())},
             {"moved", coordinates<N>(s.moved)},
             {"rounds", double(rounds)},
             {"path", path},
             {"hits", indices(hits)},
             {"hits.points", hit_points},
             {"relation", label(to_string(end.relation))},
             {"relation.triangle", double(end.triangle)},
             {"touched", indices(touched)},
             {"touched.points", touched_points}};
  if constexpr (N == 3) add_body(out, "e", e);
  return out;
}

// ---- Live packing -------------------------------------------------------------------------

namespace {

// Raw bits of mt19937_64 as a uniform double in [0, 1): the standard fixes the engine's
// output (not its distributions'), so the wasm and native starts are the same.
double uniform(std::mt19937_64& rng) { return double(rng() >> 11) * 0x1p-53; }

// A random orientation from a normalized random vector (2D: (cos, sin); 3D: a quaternion),
// by square roots alone (correctly rounded everywhere).
template <int N>
Mat<double, N> random_axes(std::mt19937_64& rng) {
  Eigen::Matrix<double, N == 2 ? 2 : 4, 1> v;
  do {
    for (auto& x : v) x = 2 * uniform(rng) - 1;
  } while (!(v.squaredNorm() > 0.01 && v.squaredNorm() <= 1));
  v.normalize();
  if constexpr (N == 2) {
    Mat<double, 2> a;
    a << v[0], -v[1], v[1], v[0];
    return a;
  } else {
    return Quat<double>(v[0], v[1], v[2], v[3]).toRotationMatrix();
  }
}

// A whole number in [lo, hi] under `name` (InputError naming it otherwise).
std::int64_t whole(const Params& p, const std::string& name, double lo, double hi) {
  const double v = get(p, name);
  if (!(v >= lo && v <= hi && v == std::floor(v)))
    throw InputError(name, "must be a whole number in [" + std::to_string(std::int64_t(lo)) + ", " +
                               std::to_string(std::int64_t(hi)) + "]");
  return static_cast<std::int64_t>(v);
}

double body_volume(const Vec<double, 2>& r) { return std::numbers::pi * r[0] * r[1]; }
double body_volume(const Vec<double, 3>& r) { return 4.0 / 3.0 * std::numbers::pi * r[0] * r[1] * r[2]; }

}  // namespace

// The live packing: the packing module's Compression, from a start of the page's own whose
// draws come from mt19937_64's raw bits and square roots alone, so that the wasm and native
// runs are the same (std's distributions and libm's sines differ between the two). n bodies
// (the largest radius 1, the others 1 / aspect) on a cubic lattice (cells at least 2.1 wide:
// no two touch) in a box with density 0.2 at the start (larger where the lattice needs it;
// each body under an eighth of its side, as jam_packing has it), each turned at random,
// velocities uniform in [-1, 1) less their mean, no spin. Growth at `rate` (thermal speeds
// per largest diameter), a fifth of it from reduced pressure 100; jammed at `pressure`.
template <int N>
struct LiveRun {
  std::optional<Compression<N>> compression;  // always set: Compression has no empty state
  std::optional<Packing<N>> end;  // the packing, once ended
};

namespace {

template <int N>
std::unique_ptr<LiveRun<N>> live_run(const Params& p) {
  constexpr double initial_density = 0.2, min_cell = 2.1;
  const int n = static_cast<int>(whole(p, "n", 2, 1e5));
  const double aspect = get(p, "aspect"), rate = get(p, "rate");
  if (!(aspect >= 1) || !std::isfinite(aspect)) throw InputError("aspect", "must be finite and >= 1");
  if (!(rate > 0) || !std::isfinite(rate)) throw InputError("rate", "must be finite and > 0");
  PackingOptions options;
  options.pressure = get(p, "pressure");  // InputError "pressure" outside (1, inf)
  options.schedule = GrowthSchedule{{0.0, rate}, {1e2, rate / 5}};
  Vec<double, N> radii = Vec<double, N>::Constant(1.0 / aspect);
  radii[0] = 1.0;
  int m = 1;  // lattice cells per side
  while (std::pow(m, N) < n) ++m;
  const double side = std::max(std::pow(n * body_volume(radii) / initial_density, 1.0 / N), min_cell * m);
  if (!(8 < side)) throw InputError("n", "too few bodies: each must be under an eighth of the box side");
  const double cell = side / m;
  PeriodicBox<N> box;
  box.size.fill(side);
  std::mt19937_64 rng(static_cast<std::uint64_t>(whole(p, "seed", 0, 0x1p53)));
  std::vector<Ellipsoid<double, N>> bodies;
  std::vector<RigidMotion<double, N>> motions(static_cast<std::size_t>(n));
  Vec<double, N> mean = Vec<double, N>::Zero();
  for (int i = 0; i < n; ++i) {
    Vec<double, N> c;
    for (int k = 0, q = i; k < N; ++k, q /= m) c[k] = (q % m + 0.5) * cell;
    bodies.push_back(Ellipsoid<double, N>::from_axes(c, random_axes<N>(rng), radii));
    for (int k = 0; k < N; ++k) motions[i].velocity[k] = 2 * uniform(rng) - 1;
    mean += motions[i].velocity;
  }
  for (auto& mo : motions) mo.velocity -= mean / n;
  auto run = std::make_unique<LiveRun<N>>();
  run->compression.emplace(bodies, motions, box, options);
  return run;
}

// Up to `collisions` collisions; at the end, the packing.
template <int N>
void advance(LiveRun<N>& run, int collisions) {
  if (run.end) return;
  run.compression->advance(static_cast<std::uint64_t>(std::max(collisions, 0)));
  if (run.compression->status() != PackingStatus::compressing) run.end = run.compression->packing();
}

// status (compressing, jammed, collision_limit), collisions, time, density now, the last
// interval's pressure (NaN before the first) and the (density, pressure) of every interval.
template <int N>
Answer state(const LiveRun<N>& run) {
  const Compression<N>& c = *run.compression;
  const HardBodies<N>& s = c.system();
  std::vector<double> history;
  for (const auto& h : c.history()) history.insert(history.end(), h.begin(), h.end());
  return {{"status", std::string(to_string(c.status()))},
          {"collisions", double(s.collisions())},
          {"time", s.now()},
          {"density", c.density_at(s.now())},
          {"pressure", c.pressure()},
          {"history", history},
          {"box", std::vector<double>(s.box().size.begin(), s.box().size.end())}};
}

// The bodies for drawing (centers wrapped into the box): "centers", "axes" (column-major)
// and "radii", N, N * N and N numbers per body, now or, once ended, the packing's (halfway
// to the next event, where no pair touches) with its contacts: "contacts", "mean_contacts",
// "overlapping" (pairs classify finds neither separated nor touching: 0 in a sound run) and
// "contacts.segments", each contact as the segment between the centers (through the image).
template <int N>
Answer bodies(const LiveRun<N>& run) {
  const double time = run.end ? run.end->time : run.compression->system().now();
  const std::vector<Ellipsoid<double, N>> shapes = run.end ? run.end->bodies : run.compression->system().shapes_at(time);
  std::vector<double> centers, axes, radii;
  for (const auto& b : shapes) {
    const Mat<double, N> a = b.axes();
    centers.insert(centers.end(), b.center().data(), b.center().data() + N);
    axes.insert(axes.end(), a.data(), a.data() + N * N);
    radii.insert(radii.end(), b.radii().data(), b.radii().data() + N);
  }
  Answer out{{"bodies.time", time}, {"centers", centers}, {"axes", axes}, {"radii", radii}};
  if (!run.end) return out;
  const Packing<N>& p = *run.end;
  std::vector<double> segments;
  for (const ImagePair<N>& q : p.contacts) {
    const Vec<double, N> a = p.bodies[q.i].center();
    Vec<double, N> b = p.bodies[q.j].center();
    for (int k = 0; k < N; ++k) b[k] += q.image[k] * p.box.size[k];
    segments.insert(segments.end(), a.data(), a.data() + N);
    segments.insert(segments.end(), b.data(), b.data() + N);
  }
  out.insert(out.end(), {{"contacts", double(p.contacts.size())},
                         {"mean_contacts", p.mean_contacts},
                         {"overlapping", double(p.overlapping)},
                         {"contacts.segments", segments}});
  return out;
}

}  // namespace

namespace {

LivePacking::Run make_run(const Params& p) {
  if (dimension(p) == 2) return live_run<2>(p);
  return live_run<3>(p);
}

// The native answers of the live packing: run to `collisions` (or, without it, to jamming),
// its state and bodies; "packing_check": the overlapping pairs (classify, through the periodic
// box's images) of the bodies given as the page drew them (centers, axes, radii as from
// LivePacking::bodies, under the names centers.k, axes.k, radii.k; box.k).
Answer packing(const Params& p) {
  LivePacking live(p);
  const auto it = p.find("collisions");
  if (it != p.end()) {
    live.advance(static_cast<int>(it->second));
  } else {
    while (std::get<std::string>(live.state().front().second) == "compressing") live.advance(1000);
  }
  Answer out = live.state();
  for (auto& entry : live.bodies()) out.push_back(std::move(entry));
  return out;
}

template <int N>
Answer packing_check(const Params& p) {
  const int n = static_cast<int>(get(p, "n"));
  PeriodicBox<N> box;
  for (int k = 0; k < N; ++k) box.size[k] = get(p, indexed("box.", k));
  std::vector<Ellipsoid<double, N>> bodies;
  for (int i = 0; i < n; ++i) {
    Vec<double, N> c, r;
    Mat<double, N> a;
    for (int k = 0; k < N; ++k) c[k] = get(p, indexed("centers.", N * i + k)), r[k] = get(p, indexed("radii.", N * i + k));
    for (int k = 0; k < N * N; ++k) a.data()[k] = get(p, indexed("axes.", N * N * i + k));
    bodies.push_back(Ellipsoid<double, N>::from_axes(c, a, r));
  }
  int overlapping = 0;
  for (const ImagePair<N>& q : candidate_pairs<double, N>(bodies, box)) {
    Vec<double, N> offset;
    for (int k = 0; k < N; ++k) offset[k] = q.image[k] * box.size[k];
    const Relation r = classify(bodies[q.i], bodies[q.j].translated(offset));
    if (r != Relation::separated && r != Relation::touching) ++overlapping;
  }
  return {{"overlapping", double(overlapping)}};
}

}  // namespace

LivePacking::LivePacking(const Params& params) : run_(make_run(params)) {}
LivePacking::~LivePacking() = default;
void LivePacking::advance(int collisions) {
  std::visit([&](auto& r) { web::advance(*r, collisions); }, run_);
}
Answer LivePacking::state() const {
  return std::visit([](const auto& r) { return web::state(*r); }, run_);
}
Answer LivePacking::bodies() const {
  return std::visit([](const auto& r) { return web::bodies(*r); }, run_);
}

Answer answer(std::string_view demo, const Params& params) {
  try {
    if (demo == "ellipse_circle") return ellipse_circle(params);
    if (demo == "segment_circle") return segment(params);
    if (demo == "polygonal") return polygonal(params);
    if (demo == "swept") return swept(params);
    if (demo == "relation") return relation(params);
    if (demo == "slide") return slide(params);
    if (demo == "mesh_slide") return mesh_slide<2>(params);
    if (demo == "mesh_slide3d") return mesh_slide<3>(params);
    if (demo == "geometry") return geometry(params);
    if (demo == "pair3d") return dimension(params) == 2 ? pair_answer<2>(params) : pair_answer<3>(params);
    if (demo == "motion3d") return motion3d(params);
    if (demo == "packing") return packing(params);
    if (demo == "packing_check") return dimension(params) == 2 ? packing_check<2>(params) : packing_check<3>(params);
  } catch (const InputError& e) {
    return {{"error", e.field()}, {"message", std::string(e.what())}};
  }
  throw std::invalid_argument("no demo " + std::string(demo));
}

}  // namespace ellipsect::web
