// `ellipsect render`: an SVG (or PNG, through rsvg-convert) of the bodies at one time, their
// paths, the contact points and normals, overlapping bodies in red, and a legend.
#include "broad_phase.hpp"
#include "commands.hpp"
#include "common.hpp"

#include <Eigen/Eigenvalues>

#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <limits>
#include <type_traits>
#include <variant>
#include <vector>

extern char** environ;

namespace ellipsect::cli {

namespace {

constexpr double pi = 3.14159265358979323846;
const char* const palette[] = {"#1f77b4", "#2ca02c", "#9467bd", "#8c564b", "#e377c2",
                               "#7f7f7f", "#bcbd22", "#17becf", "#ff7f0e", "#393b79"};
constexpr int palette_size = 10;
const char* const overlap_color = "#d62728";
const char* const obstacle_color = "#555555";
const char* const contact_color = "#000000";
constexpr std::size_t max_legend_bodies = 12;
constexpr std::size_t max_labels = 40;

std::string xml_escape(std::string_view s) {
  std::string out;
  for (std::size_t i = 0; i < s.size(); ++i) {
    const char c = s[i];
    const auto u = static_cast<unsigned char>(c);
    if (u >= 0x80) {
      i += append_utf8_sequence(out, s, i) - 1;
      continue;
    }
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      case '\'': out += "&apos;"; break;
      default: out += u < 0x20 && c != '\t' && c != '\n' && c != '\r' ? utf8_replacement : std::string_view(&c, 1);
    }
  }
  return out;
}

std::string fmt(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.2f", x);
  return buf;
}

bool is_overlap(Relation r) {
  return r == Relation::overlapping || r == Relation::a_contains_b || r == Relation::b_contains_a ||
         r == Relation::equal;
}

bool has_contact_point(ContactStatus s) { return s == ContactStatus::hit || s == ContactStatus::touching_at_start; }

// A body's outline in the drawing plane: center, semi-axes and angle (radians, from u).
struct Outline {
  double cu, cv, major, minor, angle;
};

struct Plane {
  int u = 0, v = 1;
  std::string name = "xy";
};

template <int N>
Outline outline(const Ellipsoid<double, N>& e, const Plane& p) {
  const Mat<double, N> L = e.axes() * e.radii().asDiagonal();
  const Mat<double, N> S = L * L.transpose();
  Eigen::Matrix2d s2;
  s2 << S(p.u, p.u), S(p.u, p.v), S(p.v, p.u), S(p.v, p.v);
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> es(s2);
  const Eigen::Vector2d ev = es.eigenvalues();
  const Eigen::Vector2d major_dir = es.eigenvectors().col(1);
  return Outline{e.center()[p.u], e.center()[p.v], std::sqrt(std::max(ev[1], 0.0)), std::sqrt(std::max(ev[0], 0.0)),
                 std::atan2(major_dir[1], major_dir[0])};
}

struct Bounds {
  double umin = std::numeric_limits<double>::infinity(), umax = -std::numeric_limits<double>::infinity();
  double vmin = std::numeric_limits<double>::infinity(), vmax = -std::numeric_limits<double>::infinity();
  void add(double u, double v, double ru = 0, double rv = 0) {
    if (!std::isfinite(u) || !std::isfinite(v)) return;
    umin = std::min(umin, u - ru);
    umax = std::max(umax, u + ru);
    vmin = std::min(vmin, v - rv);
    vmax = std::max(vmax, v + rv);
  }
  void add(const Outline& o) {
    // Half extents of the rotated ellipse along u and v.
    const double c = std::cos(o.angle), s = std::sin(o.angle);
    add(o.cu, o.cv, std::hypot(o.major * c, o.minor * s), std::hypot(o.major * s, o.minor * c));
  }
};

using Point2 = Eigen::Vector2d;

// The part of `polygon` where n . (x - p) <= 0 (Sutherland-Hodgman against one line).
std::vector<Point2> clip(const std::vector<Point2>& polygon, const Point2& n, const Point2& p) {
  std::vector<Point2> out;
  for (std::size_t i = 0; i < polygon.size(); ++i) {
    const Point2& a = polygon[i];
    const Point2& b = polygon[(i + 1) % polygon.size()];
    const double fa = n.dot(a - p), fb = n.dot(b - p);
    if (fa <= 0) out.push_back(a);
    if ((fa < 0 && fb > 0) || (fa > 0 && fb < 0)) out.push_back(a + (b - a) * (fa / (fa - fb)));
  }
  return out;
}

// The convex hull of `points`, counter-clockwise (Andrew's monotone chain).
std::vector<Point2> convex_hull(std::vector<Point2> points) {
  std::sort(points.begin(), points.end(), [](const Point2& a, const Point2& b) {
    return a[0] < b[0] || (a[0] == b[0] && a[1] < b[1]);
  });
  if (points.size() < 3) return points;
  std::vector<Point2> hull(2 * points.size());
  std::size_t k = 0;
  const auto cross = [](const Point2& o, const Point2& a, const Point2& b) {
    return (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0]);
  };
  for (std::size_t i = 0; i < points.size(); ++i) {
    while (k >= 2 && cross(hull[k - 2], hull[k - 1], points[i]) <= 0) --k;
    hull[k++] = points[i];
  }
  for (std::size_t i = points.size() - 1, lower = k + 1; i-- > 0;) {
    while (k >= lower && cross(hull[k - 2], hull[k - 1], points[i]) <= 0) --k;
    hull[k++] = points[i];
  }
  hull.resize(k - 1);
  return hull;
}

// An obstacle in the drawing plane: polygons (a triangle, a box's outline, a mesh's
// triangles), a capsule's stadium, or for a half-space the region its projection covers
// within the view.
struct Shadow {
  std::vector<std::vector<Point2>> polygons;
  bool half_space = false;
  Point2 normal, point;  // half_space: the region normal . (x - point) <= 0 ...
  bool everywhere = false;  // ... or, in 3D with a normal off the plane, the whole view
  bool capsule = false;
  Point2 ends[2];       // capsule: the points within `radius` of the segment ends[0] ends[1]
  double radius = 0.0;  // (a capsule's projection is the stadium of its projected segment)
};

template <int N>
Shadow shadow(const Obstacle<N>& o, const Plane& p) {
  Shadow s;
  const auto project = [&](const Vec<double, N>& x) { return Point2(x[p.u], x[p.v]); };
  std::visit(
      [&](const auto& shape) {
        using S = std::decay_t<decltype(shape)>;
        if constexpr (std::is_same_v<S, HalfSpace<double, N>>) {
          s.half_space = true;
          s.normal = project(shape.normal());
          s.point = project(shape.point());
          // The projection of { n . x <= n . p } is all of the plane unless n lies in it.
          if constexpr (N == 3) s.everywhere = shape.normal()[3 - p.u - p.v] != 0.0;
        } else if constexpr (std::is_same_v<S, Triangle<double, N>>) {
          s.polygons.push_back({project(shape.vertex(0)), project(shape.vertex(1)), project(shape.vertex(2))});
        } else if constexpr (std::is_same_v<S, Box<double, N>>) {
          std::vector<Point2> corners;
          for (int k = 0; k < (1 << N); ++k) corners.push_back(project(shape.corner(k)));
          s.polygons.push_back(convex_hull(std::move(corners)));
        } else if constexpr (std::is_same_v<S, Capsule<double, N>>) {
          s.capsule = true;
          s.ends[0] = project(shape.point(0));
          s.ends[1] = project(shape.point(1));
          s.radius = shape.radius();
        } else {
          for (std::size_t k = 0; k < shape.triangle_count(); ++k) {
            const Triangle<double, N> t = shape.triangle(k);
            s.polygons.push_back({project(t.vertex(0)), project(t.vertex(1)), project(t.vertex(2))});
          }
        }
      },
      o.shape);
  return s;
}

// Runs rsvg-convert with the SVG on its standard input, writing PNG to `png_path`.
void svg_to_png(const std::string& svg, const std::string& png_path, const std::string& final_path) {
  int pipefd[2];
  if (::pipe(pipefd) != 0) throw IoError(final_path + ": cannot create a pipe: " + std::strerror(errno));
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_adddup2(&actions, pipefd[0], STDIN_FILENO);
  posix_spawn_file_actions_addclose(&actions, pipefd[0]);
  posix_spawn_file_actions_addclose(&actions, pipefd[1]);
  std::string prog = "rsvg-convert", f1 = "-f", f2 = "png", o1 = "-o", out = png_path;
  char* argv[] = {prog.data(), f1.data(), f2.data(), o1.data(), out.data(), nullptr};
  pid_t pid = 0;
  const int rc = posix_spawnp(&pid, "rsvg-convert", &actions, nullptr, argv, environ);
  posix_spawn_file_actions_destroy(&actions);
  ::close(pipefd[0]);
  if (rc != 0) {
    ::close(pipefd[1]);
    throw IoError(final_path + ": cannot run rsvg-convert (" + std::strerror(rc) +
                  "); install it (Debian package librsvg2-bin) or write an .svg file");
  }
  // A converter that exits early must not kill us with SIGPIPE.
  struct sigaction ignore {}, old {};
  ignore.sa_handler = SIG_IGN;
  ::sigaction(SIGPIPE, &ignore, &old);
  std::size_t done = 0;
  bool write_failed = false;
  while (done < svg.size()) {
    const ssize_t w = ::write(pipefd[1], svg.data() + done, svg.size() - done);
    if (w < 0) {
      if (errno == EINTR) continue;
      write_failed = true;
      break;
    }
    done += static_cast<std::size_t>(w);
  }
  ::close(pipefd[1]);
  ::sigaction(SIGPIPE, &old, nullptr);
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  if (write_failed || !WIFEXITED(status) || WEXITSTATUS(status) != 0)
    throw IoError(final_path + ": rsvg-convert failed (exit status " +
                  std::to_string(WIFEXITED(status) ? WEXITSTATUS(status) : -1) + ")");
}

bool ends_with(const std::string& s, const char* suffix) {
  const std::size_t n = std::strlen(suffix);
  if (s.size() < n) return false;
  for (std::size_t i = 0; i < n; ++i)
    if (std::tolower(static_cast<unsigned char>(s[s.size() - n + i])) != suffix[i]) return false;
  return true;
}

template <int N>
int render(const Input& in, const RenderOptions& opt, const Plane& plane) {
  const Window w = effective_window(in, opt.common);
  const int threads = resolve_threads(opt.common.threads);
  const bool contact = in.has_velocity;
  // A pairs CSV: the one pair of row --row; otherwise every body.
  const std::size_t limit = in.kind == InputKind::pairs_csv ? 1 : std::numeric_limits<std::size_t>::max();
  PairSet<N> set = load_pair_set<N>(in, opt.common, w, contact, limit, opt.row);
  const auto& bodies = set.bodies;
  const std::size_t n = bodies.size();
  const std::size_t m = set.obstacles.size();
  std::vector<Obstacle<N>> obstacles_t0;
  for (const auto& o : set.obstacles) obstacles_t0.push_back(obstacle_at<N>(o, w.t0, in.path));
  // The id of pair member j: a body, or an obstacle from n on.
  const auto id_of = [&](std::uint32_t j) -> const std::string& {
    return j < n ? bodies[j].id : set.obstacles[j - n].id;
  };

  // First contacts over the window.
  Queries cq;
  cq.relation = false;
  cq.contact = true;
  std::vector<PairResult<N>> contacts;
  if (contact) {
    contacts.resize(set.pairs.size());
    constexpr std::size_t block = 256;
    parallel_for((set.pairs.size() + block - 1) / block, threads, [&](std::size_t b) {
      const std::size_t end = std::min(set.pairs.size(), (b + 1) * block);
      for (std::size_t k = b * block; k < end; ++k)
        contacts[k] = set.pairs[k].second < n
                          ? evaluate<N>(bodies[set.pairs[k].first], bodies[set.pairs[k].second], w, cq, in.path)
                          : evaluate<N>(bodies[set.pairs[k].first], obstacles_t0[set.pairs[k].second - n], w, cq,
                                        in.path);
    });
  }
  double first = std::numeric_limits<double>::infinity();
  std::size_t first_pair = 0;
  for (std::size_t k = 0; k < contacts.size(); ++k)
    if (has_contact_point(contacts[k].contact.status) && contacts[k].contact.time < first) {
      first = contacts[k].contact.time;
      first_pair = k;
    }
  double T = w.t0;
  std::string time_note = contact ? "window start; no contact" : "no velocities";
  if (opt.time) {
    T = *opt.time;
    time_note = "--time";
  } else if (std::isfinite(first)) {
    T = first;
    time_note = "first contact: " + id_of(set.pairs[first_pair].first) + " and " + id_of(set.pairs[first_pair].second);
    if (in.kind == InputKind::pairs_csv) time_note = "first contact";
  }
  if (!std::isfinite(T)) throw UsageError("--time: must be finite");

  // Bodies at T and their relations there.
  std::vector<Body<N>> at_t;
  at_t.reserve(n);
  for (const auto& b : bodies) at_t.push_back(Body<N>{b.id, shape_at<N>(b, T, in.path), b.motion});
  std::vector<Obstacle<N>> obstacles_at_t;
  for (const auto& o : set.obstacles) obstacles_at_t.push_back(obstacle_at<N>(o, T, in.path));
  std::vector<IndexPair> rel_pairs = set.pairs;
  if (set.pairs_from_broad_phase) {
    // The body pairs from the broad phase at T; the obstacle pairs as listed.
    std::erase_if(rel_pairs, [&](const IndexPair& p) { return p.second < n; });
    const std::vector<IndexPair> near = broad_phase<N>(at_t, Window{0.0, 0.0}, false);
    rel_pairs.insert(rel_pairs.begin(), near.begin(), near.end());
  }
  std::vector<char> red(n + m, 0);  // bodies, then obstacles
  {
    Queries rq;
    rq.relation = true;
    rq.contact = false;
    std::vector<char> over(rel_pairs.size(), 0);
    constexpr std::size_t block = 256;
    parallel_for((rel_pairs.size() + block - 1) / block, threads, [&](std::size_t b) {
      const std::size_t end = std::min(rel_pairs.size(), (b + 1) * block);
      for (std::size_t k = b * block; k < end; ++k)
        over[k] = is_overlap((rel_pairs[k].second < n
                                  ? evaluate<N>(at_t[rel_pairs[k].first], at_t[rel_pairs[k].second], Window{0.0, 0.0},
                                                rq, in.path)
                                  : evaluate<N>(at_t[rel_pairs[k].first], obstacles_at_t[rel_pairs[k].second - n],
                                                Window{0.0, 0.0}, rq, in.path))
                                 .relation);
    });
    for (std::size_t k = 0; k < rel_pairs.size(); ++k)
      if (over[k]) red[rel_pairs[k].first] = red[rel_pairs[k].second] = 1;
  }
  std::size_t n_red = 0, n_red_obstacles = 0;
  for (std::size_t i = 0; i < n + m; ++i) (i < n ? n_red : n_red_obstacles) += red[i] != 0;

  // Geometry in the drawing plane.
  bool any_moving = false;
  for (const auto& b : bodies) any_moving = any_moving || moves<N>(b);
  double t_end = w.t0;
  if (any_moving) {
    if (T > w.t0) {
      t_end = std::min(w.t1, T + 0.5 * (T - w.t0));
    } else {
      t_end = std::isfinite(w.t1) ? w.t1 : w.t0 + 1.0;
    }
    t_end = std::max(t_end, T);
  }
  std::vector<Outline> shapes(n), ghosts(n);
  Bounds bounds;
  for (std::size_t i = 0; i < n; ++i) {
    shapes[i] = outline<N>(at_t[i].shape, plane);
    bounds.add(shapes[i]);
    if (moves<N>(bodies[i])) {
      ghosts[i] = outline<N>(shape_at<N>(bodies[i], w.t0, in.path), plane);
      if (T != w.t0) bounds.add(ghosts[i]);
      const Vec<double, N> c_end = bodies[i].shape.center() + bodies[i].motion.velocity * t_end;
      bounds.add(c_end[plane.u], c_end[plane.v]);
    }
  }
  for (const auto& r : contacts)
    if (has_contact_point(r.contact.status)) bounds.add(r.contact.point[plane.u], r.contact.point[plane.v]);
  std::vector<Shadow> shadows;
  for (const auto& o : obstacles_at_t) {
    shadows.push_back(shadow<N>(o, plane));
    const Shadow& s = shadows.back();
    for (const auto& polygon : s.polygons)
      for (const Point2& x : polygon) bounds.add(x[0], x[1]);
    if (s.capsule)
      for (const Point2& x : s.ends) bounds.add(x[0], x[1], s.radius, s.radius);
    // A half-plane: the feet of the bodies' centers on its line.
    if (s.half_space && !s.everywhere && s.normal.squaredNorm() > 0)
      for (const Outline& b : shapes) {
        const Point2 c(b.cu, b.cv);
        const Point2 foot = c - s.normal * (s.normal.dot(c - s.point) / s.normal.squaredNorm());
        bounds.add(foot[0], foot[1]);
      }
  }
  double span_u = bounds.umax - bounds.umin, span_v = bounds.vmax - bounds.vmin;
  double span = std::max(span_u, span_v);
  if (!(span > 0) || !std::isfinite(span)) span = 1.0;
  // 4% margin on every side.
  bounds.umin -= 0.04 * span;
  bounds.umax += 0.04 * span;
  bounds.vmin -= 0.04 * span;
  bounds.vmax += 0.04 * span;
  span_u = std::max(bounds.umax - bounds.umin, 1e-300);
  span_v = std::max(bounds.vmax - bounds.vmin, 1e-300);
  const double plot = std::max(opt.width, 100);
  const double scale = plot / std::max(span_u, span_v);
  const double plot_w = span_u * scale, plot_h = span_v * scale;
  constexpr double title_h = 48, legend_w = 240, pad = 10, row_h = 18;
  const bool list_bodies = n <= max_legend_bodies;
  const double legend_rows = (list_bodies ? static_cast<double>(n) : 1.0) + 1.0 + (m > 0 ? 1.0 : 0.0) +
                             (any_moving ? 2.0 : 0.0) + (contact ? 2.0 : 0.0);
  const double legend_h = 8 + 22 + 6 + legend_rows * row_h + pad;
  const double width = pad + plot_w + pad + legend_w;
  const double height = std::max(title_h + plot_h + pad, title_h + legend_h);
  auto sx = [&](double u) { return pad + (u - bounds.umin) * scale; };
  auto sy = [&](double v) { return title_h + (bounds.vmax - v) * scale; };
  const double stroke = 1.5;

  std::string svg;
  svg.reserve(512 + n * 220);
  svg += "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n";
  svg += "<svg xmlns=\"http://www.w3.org/2000/svg\" version=\"1.1\" width=\"" + fmt(width) + "\" height=\"" +
         fmt(height) + "\" viewBox=\"0 0 " + fmt(width) + " " + fmt(height) + "\" class=\"ellipsect-scene\"" +
         " data-dimension=\"" + std::to_string(N) + "\" data-plane=\"" + plane.name + "\" data-time=\"" +
         number_string(T) + "\" data-bodies=\"" + std::to_string(n) + "\" data-overlapping=\"" +
         std::to_string(n_red) + "\" data-obstacles=\"" + std::to_string(m) + "\" data-obstacles-overlapping=\"" +
         std::to_string(n_red_obstacles) + "\">\n";
  svg += "<defs><marker id=\"arrow\" viewBox=\"0 0 10 10\" refX=\"9\" refY=\"5\" markerWidth=\"7\" "
         "markerHeight=\"7\" orient=\"auto-start-reverse\"><path d=\"M 0 0 L 10 5 L 0 10 z\" fill=\"context-stroke\"/>"
         "</marker><marker id=\"arrow-black\" viewBox=\"0 0 10 10\" refX=\"9\" refY=\"5\" markerWidth=\"7\" "
         "markerHeight=\"7\" orient=\"auto\"><path d=\"M 0 0 L 10 5 L 0 10 z\" fill=\"#000\"/></marker>"
         "<marker id=\"arrow-grey\" viewBox=\"0 0 10 10\" refX=\"9\" refY=\"5\" markerWidth=\"6\" "
         "markerHeight=\"6\" orient=\"auto\"><path d=\"M 0 0 L 10 5 L 0 10 z\" fill=\"#888\"/></marker></defs>\n";
  svg += "<rect x=\"0\" y=\"0\" width=\"" + fmt(width) + "\" height=\"" + fmt(height) + "\" fill=\"#ffffff\"/>\n";
  svg += "<rect x=\"" + fmt(pad) + "\" y=\"" + fmt(title_h) + "\" width=\"" + fmt(plot_w) + "\" height=\"" +
         fmt(plot_h) + "\" fill=\"#fbfbfb\" stroke=\"#dddddd\"/>\n";
  // Title.
  svg += "<text x=\"" + fmt(pad) + "\" y=\"20\" font-family=\"sans-serif\" font-size=\"15\" font-weight=\"bold\">" +
         xml_escape(in.title) + "</text>\n";
  std::string sub = "t = " + number_string(T) + " (" + time_note + ")";
  if (in.kind == InputKind::pairs_csv) sub = "row " + std::to_string(opt.row) + ", " + sub;
  if (N == 3) sub += ", projected onto the " + plane.name + " plane";
  svg += "<text x=\"" + fmt(pad) + "\" y=\"38\" font-family=\"sans-serif\" font-size=\"12\" fill=\"#444\">" +
         xml_escape(sub) + "</text>\n";
  // Axis names at the plot's corner.
  static const char* axis_names[3] = {"x", "y", "z"};
  svg += "<text x=\"" + fmt(pad + plot_w - 4) + "\" y=\"" + fmt(title_h + plot_h - 4) +
         "\" text-anchor=\"end\" font-family=\"sans-serif\" font-size=\"10\" fill=\"#999\">" + axis_names[plane.u] +
         " \u2192, " + axis_names[plane.v] + " \u2191</text>\n";

  auto ellipse = [&](const Outline& o, const std::string& cls, const std::string& id, const char* fill,
                     const char* stroke_color, double fill_opacity, const char* dash) {
    std::string e = "<ellipse class=\"" + cls + "\" data-id=\"" + xml_escape(id) + "\" cx=\"" + fmt(sx(o.cu)) +
                    "\" cy=\"" + fmt(sy(o.cv)) + "\" rx=\"" + fmt(std::max(o.major * scale, 0.5)) + "\" ry=\"" +
                    fmt(std::max(o.minor * scale, 0.5)) + "\" transform=\"rotate(" + fmt(-o.angle * 180.0 / pi) +
                    " " + fmt(sx(o.cu)) + " " + fmt(sy(o.cv)) + ")\" fill=\"" + fill + "\" fill-opacity=\"" +
                    fmt(fill_opacity) + "\" stroke=\"" + stroke_color + "\" stroke-width=\"" + fmt(stroke) + "\"";
    if (dash != nullptr) e += std::string(" stroke-dasharray=\"") + dash + "\"";
    e += "/>\n";
    return e;
  };

  // Obstacles at T, under everything else: polygons, half-planes clipped to the view.
  if (m > 0) {
    svg += "<g id=\"obstacles\">\n";
    const std::vector<Point2> view = {Point2(bounds.umin, bounds.vmin), Point2(bounds.umax, bounds.vmin),
                                      Point2(bounds.umax, bounds.vmax), Point2(bounds.umin, bounds.vmax)};
    for (std::size_t k = 0; k < m; ++k) {
      const Shadow& s = shadows[k];
      std::vector<std::vector<Point2>> polygons = s.polygons;
      if (s.half_space) polygons.push_back(s.everywhere ? view : clip(view, s.normal, s.point));
      std::string d;
      for (const auto& polygon : polygons) {
        for (std::size_t i = 0; i < polygon.size(); ++i)
          d += (i == 0 ? "M " : " L ") + fmt(sx(polygon[i][0])) + " " + fmt(sy(polygon[i][1]));
        if (!polygon.empty()) d += " Z ";
      }
      if (s.capsule) {
        // Along the segment's left side, round its second end, back along its right side, round
        // its first end: half circles turning clockwise as drawn (SVG's sweep flag 1). A ball
        // (equal ends) is the two half circles.
        const Point2 along = s.ends[1] - s.ends[0];
        const Point2 side = along.norm() > 0 ? Point2(-along[1], along[0]).normalized() * s.radius
                                             : Point2(0.0, s.radius);
        const std::string arc = "A " + fmt(s.radius * scale) + " " + fmt(s.radius * scale) + " 0 0 1 ";
        const auto at = [&](const Point2& x) { return fmt(sx(x[0])) + " " + fmt(sy(x[1])); };
        d += "M " + at(s.ends[0] + side) + " L " + at(s.ends[1] + side) + " " + arc + at(s.ends[1] - side) + " L " +
             at(s.ends[0] - side) + " " + arc + at(s.ends[0] + side) + " Z";
      }
      const char* color = red[n + k] ? overlap_color : obstacle_color;
      svg += "<path class=\"" + std::string(red[n + k] ? "obstacle overlapping" : "obstacle") + "\" data-id=\"" +
             xml_escape(set.obstacles[k].id) + "\" data-type=\"" + obstacle_type<N>(set.obstacles[k]) + "\" d=\"" + d +
             "\" fill=\"" + color + "\" fill-opacity=\"0.2\" fill-rule=\"nonzero\" stroke=\"" + color +
             "\" stroke-width=\"1\" stroke-linejoin=\"round\"/>\n";
    }
    svg += "</g>\n";
  }

  // Start positions and paths.
  svg += "<g id=\"paths\">\n";
  for (std::size_t i = 0; i < n; ++i) {
    if (!moves<N>(bodies[i])) continue;
    const char* color = red[i] ? overlap_color : palette[i % palette_size];
    if (T != w.t0) svg += ellipse(ghosts[i], "start", bodies[i].id, "none", color, 0.0, "4 3");
    const Vec<double, N> c0 = bodies[i].shape.center() + bodies[i].motion.velocity * w.t0;
    const Vec<double, N> c1 = bodies[i].shape.center() + bodies[i].motion.velocity * t_end;
    if ((c1 - c0).norm() * scale < 1.0) continue;
    svg += "<line class=\"path\" data-id=\"" + xml_escape(bodies[i].id) + "\" x1=\"" + fmt(sx(c0[plane.u])) +
           "\" y1=\"" + fmt(sy(c0[plane.v])) + "\" x2=\"" + fmt(sx(c1[plane.u])) + "\" y2=\"" +
           fmt(sy(c1[plane.v])) + "\" stroke=\"#888\" stroke-width=\"1\" stroke-dasharray=\"6 4\" "
           "marker-end=\"url(#arrow-grey)\"/>\n";
  }
  svg += "</g>\n";

  // Bodies at T.
  svg += "<g id=\"bodies\">\n";
  for (std::size_t i = 0; i < n; ++i) {
    const char* color = red[i] ? overlap_color : palette[i % palette_size];
    svg += ellipse(shapes[i], red[i] ? "body overlapping" : "body", bodies[i].id, color, color, 0.25, nullptr);
  }
  if (n <= max_labels)
    for (std::size_t i = 0; i < n; ++i)
      svg += "<text class=\"label\" x=\"" + fmt(sx(shapes[i].cu)) + "\" y=\"" + fmt(sy(shapes[i].cv) + 4) +
             "\" text-anchor=\"middle\" font-family=\"sans-serif\" font-size=\"11\" fill=\"#222\">" +
             xml_escape(bodies[i].id) + "</text>\n";
  svg += "</g>\n";

  // Contact points and normals.
  svg += "<g id=\"contacts\">\n";
  std::size_t n_contacts = 0;
  for (std::size_t k = 0; k < contacts.size(); ++k) {
    const Contact<double, N>& c = contacts[k].contact;
    if (!has_contact_point(c.status)) continue;
    ++n_contacts;
    const double px = sx(c.point[plane.u]), py = sy(c.point[plane.v]);
    const double nu = c.normal[plane.u], nv = c.normal[plane.v];
    const double len = 36.0;
    svg += "<g class=\"contact\" data-a=\"" + xml_escape(id_of(set.pairs[k].first)) + "\" data-b=\"" +
           xml_escape(id_of(set.pairs[k].second)) + "\" data-time=\"" + number_string(c.time) + "\">";
    if (std::hypot(nu, nv) > 1e-3)
      svg += "<line class=\"contact-normal\" x1=\"" + fmt(px) + "\" y1=\"" + fmt(py) + "\" x2=\"" +
             fmt(px + len * nu) + "\" y2=\"" + fmt(py - len * nv) + "\" stroke=\"" + contact_color +
             "\" stroke-width=\"1.5\" marker-end=\"url(#arrow-black)\"/>";
    svg += "<circle class=\"contact-point\" cx=\"" + fmt(px) + "\" cy=\"" + fmt(py) + "\" r=\"4\" fill=\"#ffffff\" "
           "stroke=\"" + std::string(contact_color) + "\" stroke-width=\"2\"/></g>\n";
  }
  svg += "</g>\n";

  // Legend.
  const double lx = pad + plot_w + pad + 10;
  double ly = title_h + 8;
  svg += "<g id=\"legend\" font-family=\"sans-serif\" font-size=\"12\">\n";
  auto legend_text = [&](double x, const std::string& text, const char* cls = "legend-entry") {
    svg += "<text class=\"" + std::string(cls) + "\" x=\"" + fmt(x) + "\" y=\"" + fmt(ly + 4) + "\">" +
           xml_escape(text) + "</text>\n";
  };
  svg += "<text x=\"" + fmt(lx) + "\" y=\"" + fmt(ly + 4) + "\" font-weight=\"bold\">Legend</text>\n";
  ly += 22;
  if (list_bodies) {
    for (std::size_t i = 0; i < n; ++i) {
      const char* color = red[i] ? overlap_color : palette[i % palette_size];
      svg += "<rect x=\"" + fmt(lx) + "\" y=\"" + fmt(ly - 6) + "\" width=\"18\" height=\"12\" fill=\"" + color +
             "\" fill-opacity=\"0.25\" stroke=\"" + color + "\"/>\n";
      legend_text(lx + 26, bodies[i].id.empty() ? (i % 2 == 0 ? "a" : "b") : bodies[i].id);
      ly += row_h;
    }
  } else {
    for (int k = 0; k < 3; ++k)
      svg += "<rect x=\"" + fmt(lx + 6 * k) + "\" y=\"" + fmt(ly - 6) + "\" width=\"6\" height=\"12\" fill=\"" +
             palette[k] + "\" fill-opacity=\"0.5\"/>\n";
    legend_text(lx + 26, std::to_string(n) + " bodies");
    ly += row_h;
  }
  ly += 6;
  svg += "<rect x=\"" + fmt(lx) + "\" y=\"" + fmt(ly - 6) + "\" width=\"18\" height=\"12\" fill=\"" + overlap_color +
         "\" fill-opacity=\"0.25\" stroke=\"" + overlap_color + "\"/>\n";
  legend_text(lx + 26, "overlapping at t (" + std::to_string(n_red) + " bodies)");
  ly += row_h;
  if (m > 0) {
    svg += "<rect x=\"" + fmt(lx) + "\" y=\"" + fmt(ly - 6) + "\" width=\"18\" height=\"12\" fill=\"" + obstacle_color +
           "\" fill-opacity=\"0.2\" stroke=\"" + obstacle_color + "\"/>\n";
    legend_text(lx + 26, "obstacles (" + std::to_string(m) + ", " + std::to_string(n_red_obstacles) +
                             " overlapped at t)");
    ly += row_h;
  }
  if (any_moving) {
    svg += "<ellipse cx=\"" + fmt(lx + 9) + "\" cy=\"" + fmt(ly) + "\" rx=\"9\" ry=\"5\" fill=\"none\" stroke=\"#555\" "
           "stroke-dasharray=\"4 3\"/>\n";
    legend_text(lx + 26, "position at t = " + number_string(w.t0));
    ly += row_h;
    svg += "<line x1=\"" + fmt(lx) + "\" y1=\"" + fmt(ly) + "\" x2=\"" + fmt(lx + 18) + "\" y2=\"" + fmt(ly) +
           "\" stroke=\"#888\" stroke-dasharray=\"6 4\" marker-end=\"url(#arrow-grey)\"/>\n";
    legend_text(lx + 26, "path of the center");
    ly += row_h;
  }
  if (contact) {
    svg += "<circle cx=\"" + fmt(lx + 9) + "\" cy=\"" + fmt(ly) + "\" r=\"4\" fill=\"#fff\" stroke=\"#000\" "
           "stroke-width=\"2\"/>\n";
    legend_text(lx + 26, "contact point (" + std::to_string(n_contacts) + ")");
    ly += row_h;
    svg += "<line x1=\"" + fmt(lx) + "\" y1=\"" + fmt(ly) + "\" x2=\"" + fmt(lx + 18) + "\" y2=\"" + fmt(ly) +
           "\" stroke=\"#000\" stroke-width=\"1.5\" marker-end=\"url(#arrow-black)\"/>\n";
    legend_text(lx + 26, "contact normal (a to b)");
    ly += row_h;
  }
  svg += "</g>\n</svg>\n";

  Output out(opt.output);
  if (ends_with(opt.output, ".png")) {
    out.close_stream();
    svg_to_png(svg, out.writing_path(), opt.output);
  } else {
    out.write(svg);
  }
  out.commit();
  return exit_ok;
}

}  // namespace

int run_render(const RenderOptions& opt) {
  if (opt.output.empty() || opt.output == "-")
    throw UsageError("render: -o OUT.svg (or OUT.png) is required");
  if (!ends_with(opt.output, ".svg") && !ends_with(opt.output, ".png"))
    throw UsageError("render: the output must end in .svg or .png, got " + opt.output);
  Input in = open_input(opt.common.scene);
  in.read_mesh_files = opt.common.read_mesh_files;
  Plane plane;
  plane.name = opt.plane;
  if (opt.plane == "xy") {
    plane.u = 0;
    plane.v = 1;
  } else if (opt.plane == "yz") {
    plane.u = 1;
    plane.v = 2;
  } else if (opt.plane == "xz") {
    plane.u = 0;
    plane.v = 2;
  } else {
    throw UsageError("--plane: must be xy, yz or xz, got " + opt.plane);
  }
  if (in.dim == 2 && opt.plane != "xy") throw UsageError("--plane " + opt.plane + ": the scene is 2D (only xy)");
  return in.dim == 2 ? render<2>(in, opt, plane) : render<3>(in, opt, plane);
}

}  // namespace ellipsect::cli
