#include "answers.hpp"

#include <ellipsect/ellipsect.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
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

// Eberly's first contact, the bodies at the viewed time t, and the reduced frame at t
// (his figures 2.2 and 3.1): Y = diag(1 / r_a) R_a^T (X - K_a) makes a the unit circle;
// b becomes the quadric M2 = S^T M_b S (S the inverse map) about K2, whose principal axes
// R (from_quadric) give Z = R^T Y, where b is axis-aligned. P: b's point nearest the origin.
Answer swept(const Params& p) {
  const auto a0 = ellipse(p, "a"), b0 = ellipse(p, "b");
  const Vec2<double> va = point(p, "a.vx", "a.vy"), vb = point(p, "b.vx", "b.vy");
  const double t = get(p, "t");
  const Contact<double, 2> c = first_contact(a0, va, b0, vb, get(p, "t_max"));
  const auto a = a0.translated(t * va), b = b0.translated(t * vb);

  const Mat2<double> to_y = a.radii().cwiseInverse().asDiagonal() * a.axes().transpose();
  const Mat2<double> from_y = a.axes() * a.radii().asDiagonal();
  Mat2<double> m2 = from_y.transpose() * b.quadric() * from_y;
  m2(0, 1) = m2(1, 0) = 0.5 * (m2(0, 1) + m2(1, 0));
  const auto by = Ellipse2<double>::from_quadric(to_y * (b.center() - a.center()), m2);
  const Mat2<double> to_z = by.axes().transpose();
  const auto bz = Ellipse2<double>::from_axes(to_z * by.center(), Mat2<double>::Identity(), by.radii());
  const ClosestPoint<double, 2> cp = closest_point(bz, Vec2<double>::Zero());

  return {{"status", label(to_string(c.status))},
          {"time", c.time},
          {"point", list(c.point)},
          {"normal", list(c.normal)},
          {"iterations", double(c.iterations)},
          {"relation_t", label(to_string(classify(a, b)))},
          {"a_center_t", list(a.center())},
          {"b_center_t", list(b.center())},
          {"reduced.center", list(bz.center())},
          {"reduced.radii", list(bz.radii())},
          {"reduced.p", list(cp.point)},
          {"reduced.velocity", list(to_z * to_y * (vb - va))}};
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

// Where the body touches the triangle (NaN when it does not).
Vec2<double> touching_point(const Ellipse2<double>& body, const Triangle<double, 2>& triangle) {
  const Vec2<double> still = Vec2<double>::Zero();
  const Contact<double, 2> c = first_contact(body, still, triangle, still, 0.0);
  return c.status == ContactStatus::touching_at_start ? c.point : Vec2<double>::Constant(std::nan(""));
}

// Collide and slide through the triangle mesh of the vertices v0 ... v(vertices - 1) (vK.x,
// vK.y) and the triangles t0 ... t(triangles - 1) (tK.a, tK.b, tK.c: vertex indices; a
// repeated index makes a segment) towards the target (tx, ty): the slide, its path round by
// round with the triangle hit and the contact point of each round that ended at a contact,
// and at the end the mesh's relation and each triangle touched with its contact point.
// Slide holds no per-round record, so the rounds are replayed: with Options::max_slide_rounds
// = k the slide makes its first k rounds (slide.hpp), those of the uncapped call (the
// triangle queries are closed forms, untouched by the cap: triangle.hpp); k runs to the
// first cap at which the slide is not blocked, which is the number of rounds.
Answer mesh_slide(const Params& p) {
  const auto e = ellipse(p, "e");
  std::vector<double> vertices;
  for (int k = 0; k < static_cast<int>(get(p, "vertices")); ++k) {
    const std::string v = indexed("v", k);
    vertices.insert(vertices.end(), {get(p, v + ".x"), get(p, v + ".y")});
  }
  std::vector<std::int64_t> triangles;
  for (int k = 0; k < static_cast<int>(get(p, "triangles")); ++k)
    for (const char* corner : {".a", ".b", ".c"})
      triangles.push_back(static_cast<std::int64_t>(get(p, indexed("t", k) + corner)));
  const auto mesh = TriangleMesh<double, 2>::from_arrays(vertices, triangles);
  const Vec2<double> displacement = point(p, "tx", "ty") - e.center();
  const Slide<double, 2> s = collide_and_slide(e, displacement, mesh);

  int rounds = 0;
  std::vector<double> path = list(e.center()), hit_points;
  std::vector<int> hits;
  if (s.status == SlideStatus::moved || s.status == SlideStatus::slid || s.status == SlideStatus::blocked) {
    for (Options cap; rounds < Options{}.max_slide_rounds;) {
      cap.max_slide_rounds = ++rounds;
      const Slide<double, 2> r = collide_and_slide(e, displacement, mesh, cap);
      path.insert(path.end(), {r.body.center().x(), r.body.center().y()});
      if (r.contacts > static_cast<int>(hits.size())) {
        hits.push_back(r.last_contact);
        const Vec2<double> at = touching_point(r.body, mesh.triangle(r.last_contact));
        hit_points.insert(hit_points.end(), {at.x(), at.y()});
      }
      if (r.status != SlideStatus::blocked) break;
    }
  }

  const MeshRelation end = classify(s.body, mesh);
  std::vector<int> touched;
  std::vector<double> touched_points;
  for (std::size_t k = 0; k < mesh.triangle_count(); ++k) {
    const Vec2<double> at = touching_point(s.body, mesh.triangle(k));
    if (std::isnan(at.x())) continue;
    touched.push_back(static_cast<int>(k));
    touched_points.insert(touched_points.end(), {at.x(), at.y()});
  }
  return {{"status", label(to_string(s.status))},
          {"contacts", double(s.contacts)},
          {"last_contact", double(s.last_contact)},
          {"end", list(s.body.center())},
          {"moved", list(s.moved)},
          {"rounds", double(rounds)},
          {"path", path},
          {"hits", indices(hits)},
          {"hits.points", hit_points},
          {"relation", label(to_string(end.relation))},
          {"relation.triangle", double(end.triangle)},
          {"touched", indices(touched)},
          {"touched.points", touched_points}};
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

}  // namespace

Answer answer(std::string_view demo, const Params& params) {
  try {
    if (demo == "ellipse_circle") return ellipse_circle(params);
    if (demo == "segment_circle") return segment(params);
    if (demo == "polygonal") return polygonal(params);
    if (demo == "swept") return swept(params);
    if (demo == "relation") return relation(params);
    if (demo == "slide") return slide(params);
    if (demo == "mesh_slide") return mesh_slide(params);
    if (demo == "geometry") return geometry(params);
  } catch (const InputError& e) {
    return {{"error", e.field()}, {"message", std::string(e.what())}};
  }
  throw std::invalid_argument("no demo " + std::string(demo));
}

}  // namespace ellipsect::web
