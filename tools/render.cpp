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

// What the picture shows: the time drawn and why, the bodies and obstacles at that time with
// the overlapping ones marked, and the first contacts over the window.
template <int N>
struct Scene {
  PairSet<N> set;
  Window w;
  bool contact = false;  // the scene has velocities: first contacts over the window
  std::vector<PairResult<N>> contacts;
  double time = 0;
  std::string time_note;
  std::vector<Body<N>> at_t;
  std::vector<Ellipsoid<double, N>> at_start;  // the moving bodies at the window's start
  std::vector<Obstacle<N>> obstacles_at_t;
  std::vector<char> red;  // overlapping at the time drawn: bodies, then obstacles
  std::size_t n_red = 0, n_red_obstacles = 0, n_contacts = 0;
  bool any_moving = false;
  double t_end = 0;  // the paths drawn end here

  std::size_t n() const { return set.bodies.size(); }
  std::size_t m() const { return set.obstacles.size(); }
  // The id of pair member j: a body, or an obstacle from n on.
  const std::string& id_of(std::uint32_t j) const { return j < n() ? set.bodies[j].id : set.obstacles[j - n()].id; }
};

// evaluate(pairs[k]) for every pair, blocks of them on the program's workers.
template <int N, class Evaluate>
std::vector<PairResult<N>> evaluate_all(const std::vector<IndexPair>& pairs, int threads, const Evaluate& evaluate) {
  std::vector<PairResult<N>> results(pairs.size());
  constexpr std::size_t block = 256;
  parallel_for((pairs.size() + block - 1) / block, threads, [&](std::size_t b) {
    const std::size_t end = std::min(pairs.size(), (b + 1) * block);
    for (std::size_t k = b * block; k < end; ++k) results[k] = evaluate(pairs[k]);
  });
  return results;
}

// The pair's answer to the queries, bodies and obstacles as given (a member j >= n is
// obstacle j - n).
template <int N>
PairResult<N> evaluate_pair(const IndexPair& p, const std::vector<Body<N>>& bodies,
                            const std::vector<Obstacle<N>>& obstacles, const Window& w, const Queries& q,
                            const std::string& path) {
  const std::size_t n = bodies.size();
  return p.second < n ? evaluate<N>(bodies[p.first], bodies[p.second], w, q, path)
                      : evaluate<N>(bodies[p.first], obstacles[p.second - n], w, q, path);
}

// The first contacts over the window, and the time to draw: --time, else the first contact,
// else the window's start.
template <int N>
void choose_time(Scene<N>& scene, const Input& in, const RenderOptions& opt, int threads) {
  if (scene.contact) {
    std::vector<Obstacle<N>> obstacles_t0;
    for (const auto& o : scene.set.obstacles) obstacles_t0.push_back(obstacle_at<N>(o, scene.w.t0, in.path));
    Queries cq;
    cq.relation = false;
    cq.contact = true;
    scene.contacts = evaluate_all<N>(scene.set.pairs, threads, [&](const IndexPair& p) {
      return evaluate_pair<N>(p, scene.set.bodies, obstacles_t0, scene.w, cq, in.path);
    });
  }
  double first = std::numeric_limits<double>::infinity();
  std::size_t first_pair = 0;
  for (std::size_t k = 0; k < scene.contacts.size(); ++k)
    if (has_contact_point(scene.contacts[k].contact.status)) {
      ++scene.n_contacts;
      if (scene.contacts[k].contact.time < first) {
        first = scene.contacts[k].contact.time;
        first_pair = k;
      }
    }
  scene.time = scene.w.t0;
  scene.time_note = scene.contact ? "window start; no contact" : "no velocities";
  if (opt.time) {
    scene.time = *opt.time;
    scene.time_note = "--time";
  } else if (std::isfinite(first)) {
    scene.time = first;
    scene.time_note = "first contact: " + scene.id_of(scene.set.pairs[first_pair].first) + " and " +
                      scene.id_of(scene.set.pairs[first_pair].second);
    if (in.kind == InputKind::pairs_csv) scene.time_note = "first contact";
  }
  if (!std::isfinite(scene.time)) throw UsageError("--time: must be finite");
}

// The bodies and obstacles at the time drawn, and which overlap there: the body pairs from
// the broad phase at that time where the scene's came from it, the obstacle pairs as listed.
template <int N>
void mark_overlaps(Scene<N>& scene, const Input& in, int threads) {
  const std::size_t n = scene.n(), m = scene.m();
  const double T = scene.time;
  scene.at_t.reserve(n);
  for (const auto& b : scene.set.bodies) scene.at_t.push_back(Body<N>{b.id, shape_at<N>(b, T, in.path), b.motion});
  for (const auto& o : scene.set.obstacles) scene.obstacles_at_t.push_back(obstacle_at<N>(o, T, in.path));
  std::vector<IndexPair> rel_pairs = scene.set.pairs;
  if (scene.set.pairs_from_broad_phase) {
    std::erase_if(rel_pairs, [&](const IndexPair& p) { return p.second < n; });
    const std::vector<IndexPair> near = broad_phase<N>(scene.at_t, Window{0.0, 0.0}, false);
    rel_pairs.insert(rel_pairs.begin(), near.begin(), near.end());
  }
  scene.red.assign(n + m, 0);
  Queries rq;
  rq.relation = true;
  rq.contact = false;
  const std::vector<PairResult<N>> relations = evaluate_all<N>(rel_pairs, threads, [&](const IndexPair& p) {
    return evaluate_pair<N>(p, scene.at_t, scene.obstacles_at_t, Window{0.0, 0.0}, rq, in.path);
  });
  for (std::size_t k = 0; k < rel_pairs.size(); ++k)
    if (is_overlap(relations[k].relation)) scene.red[rel_pairs[k].first] = scene.red[rel_pairs[k].second] = 1;
  for (std::size_t i = 0; i < n + m; ++i) (i < n ? scene.n_red : scene.n_red_obstacles) += scene.red[i] != 0;
}

template <int N>
Scene<N> scene_of(const Input& in, const RenderOptions& opt) {
  Scene<N> scene;
  scene.w = effective_window(in, opt.common);
  const int threads = resolve_threads(opt.common.threads);
  scene.contact = in.has_velocity;
  // A pairs CSV: the one pair of row --row; otherwise every body.
  const std::size_t limit = in.kind == InputKind::pairs_csv ? 1 : std::numeric_limits<std::size_t>::max();
  scene.set = load_pair_set<N>(in, opt.common, scene.w, scene.contact, limit, opt.row);
  choose_time(scene, in, opt, threads);
  mark_overlaps(scene, in, threads);
  // The paths run from the window's start to half as far again past the time drawn.
  scene.at_start.resize(scene.n());
  for (std::size_t i = 0; i < scene.n(); ++i)
    if (moves<N>(scene.set.bodies[i])) {
      scene.any_moving = true;
      scene.at_start[i] = shape_at<N>(scene.set.bodies[i], scene.w.t0, in.path);
    }
  const Window& w = scene.w;
  const double T = scene.time;
  scene.t_end = w.t0;
  if (scene.any_moving) {
    if (T > w.t0) {
      scene.t_end = std::min(w.t1, T + 0.5 * (T - w.t0));
    } else {
      scene.t_end = std::isfinite(w.t1) ? w.t1 : w.t0 + 1.0;
    }
    scene.t_end = std::max(scene.t_end, T);
  }
  return scene;
}

// The SVG of a scene, layer by layer: the frame and title, obstacles, paths, bodies,
// contacts, legend. The view holds every outline, path end, contact point and obstacle
// (a half-plane: the feet of the bodies' centers on its line) with a 4% margin.
template <int N>
class Drawing {
public:
  Drawing(const Scene<N>& scene, const Plane& plane, int plot_width) : scene_(scene), plane_(plane) {
    const std::size_t n = scene.n(), m = scene.m();
    const auto& bodies = scene.set.bodies;
    shapes_.resize(n);
    ghosts_.resize(n);
    for (std::size_t i = 0; i < n; ++i) {
      shapes_[i] = outline<N>(scene.at_t[i].shape, plane);
      bounds_.add(shapes_[i]);
      if (moves<N>(bodies[i])) {
        ghosts_[i] = outline<N>(scene.at_start[i], plane);
        if (scene.time != scene.w.t0) bounds_.add(ghosts_[i]);
        const Vec<double, N> c_end = bodies[i].shape.center() + bodies[i].motion.velocity * scene.t_end;
        bounds_.add(c_end[plane.u], c_end[plane.v]);
      }
    }
    for (const auto& r : scene.contacts)
      if (has_contact_point(r.contact.status)) bounds_.add(r.contact.point[plane.u], r.contact.point[plane.v]);
    for (const auto& o : scene.obstacles_at_t) {
      shadows_.push_back(shadow<N>(o, plane));
      const Shadow& s = shadows_.back();
      for (const auto& polygon : s.polygons)
        for (const Point2& x : polygon) bounds_.add(x[0], x[1]);
      if (s.capsule)
        for (const Point2& x : s.ends) bounds_.add(x[0], x[1], s.radius, s.radius);
      if (s.half_space && !s.everywhere && s.normal.squaredNorm() > 0)
        for (const Outline& b : shapes_) {
          const Point2 c(b.cu, b.cv);
          const Point2 foot = c - s.normal * (s.normal.dot(c - s.point) / s.normal.squaredNorm());
          bounds_.add(foot[0], foot[1]);
        }
    }
    double span_u = bounds_.umax - bounds_.umin, span_v = bounds_.vmax - bounds_.vmin;
    double span = std::max(span_u, span_v);
    if (!(span > 0) || !std::isfinite(span)) span = 1.0;
    bounds_.umin -= 0.04 * span;
    bounds_.umax += 0.04 * span;
    bounds_.vmin -= 0.04 * span;
    bounds_.vmax += 0.04 * span;
    span_u = std::max(bounds_.umax - bounds_.umin, 1e-300);
    span_v = std::max(bounds_.vmax - bounds_.vmin, 1e-300);
    const double plot = std::max(plot_width, 100);
    scale_ = plot / std::max(span_u, span_v);
    plot_w_ = span_u * scale_;
    plot_h_ = span_v * scale_;
    list_bodies_ = n <= max_legend_bodies;
    const double legend_rows = (list_bodies_ ? static_cast<double>(n) : 1.0) + 1.0 + (m > 0 ? 1.0 : 0.0) +
                               (scene.any_moving ? 2.0 : 0.0) + (scene.contact ? 2.0 : 0.0);
    const double legend_h = 8 + 22 + 6 + legend_rows * row_h + pad;
    width_ = pad + plot_w_ + pad + legend_w;
    height_ = std::max(title_h + plot_h_ + pad, title_h + legend_h);
  }

  std::string svg(const std::string& title, const std::string& subtitle) const {
    std::string out;
    out.reserve(512 + scene_.n() * 220);
    frame(out, title, subtitle);
    obstacles(out);
    paths(out);
    bodies(out);
    contacts(out);
    legend(out);
    out += "</svg>\n";
    return out;
  }

private:
  static constexpr double title_h = 48, legend_w = 240, pad = 10, row_h = 18, stroke = 1.5;

  double sx(double u) const { return pad + (u - bounds_.umin) * scale_; }
  double sy(double v) const { return title_h + (bounds_.vmax - v) * scale_; }
  const char* body_color(std::size_t i) const { return scene_.red[i] ? overlap_color : palette[i % palette_size]; }

  std::string ellipse(const Outline& o, const std::string& cls, const std::string& id, const char* fill,
                      const char* stroke_color, double fill_opacity, const char* dash) const {
    std::string e = "<ellipse class=\"" + cls + "\" data-id=\"" + xml_escape(id) + "\" cx=\"" + fmt(sx(o.cu)) +
                    "\" cy=\"" + fmt(sy(o.cv)) + "\" rx=\"" + fmt(std::max(o.major * scale_, 0.5)) + "\" ry=\"" +
                    fmt(std::max(o.minor * scale_, 0.5)) + "\" transform=\"rotate(" + fmt(-o.angle * 180.0 / pi) +
                    " " + fmt(sx(o.cu)) + " " + fmt(sy(o.cv)) + ")\" fill=\"" + fill + "\" fill-opacity=\"" +
                    fmt(fill_opacity) + "\" stroke=\"" + stroke_color + "\" stroke-width=\"" + fmt(stroke) + "\"";
    if (dash != nullptr) e += std::string(" stroke-dasharray=\"") + dash + "\"";
    e += "/>\n";
    return e;
  }

  // The document, its markers and background, the title and the axis names.
  void frame(std::string& svg, const std::string& title, const std::string& subtitle) const {
    svg += "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n";
    svg += "<svg xmlns=\"http://www.w3.org/2000/svg\" version=\"1.1\" width=\"" + fmt(width_) + "\" height=\"" +
           fmt(height_) + "\" viewBox=\"0 0 " + fmt(width_) + " " + fmt(height_) + "\" class=\"ellipsect-scene\"" +
           " data-dimension=\"" + std::to_string(N) + "\" data-plane=\"" + plane_.name + "\" data-time=\"" +
           number_string(scene_.time) + "\" data-bodies=\"" + std::to_string(scene_.n()) + "\" data-overlapping=\"" +
           std::to_string(scene_.n_red) + "\" data-obstacles=\"" + std::to_string(scene_.m()) +
           "\" data-obstacles-overlapping=\"" + std::to_string(scene_.n_red_obstacles) + "\">\n";
    svg += "<defs><marker id=\"arrow\" viewBox=\"0 0 10 10\" refX=\"9\" refY=\"5\" markerWidth=\"7\" "
           "markerHeight=\"7\" orient=\"auto-start-reverse\"><path d=\"M 0 0 L 10 5 L 0 10 z\" fill=\"context-stroke\"/>"
           "</marker><marker id=\"arrow-black\" viewBox=\"0 0 10 10\" refX=\"9\" refY=\"5\" markerWidth=\"7\" "
           "markerHeight=\"7\" orient=\"auto\"><path d=\"M 0 0 L 10 5 L 0 10 z\" fill=\"#000\"/></marker>"
           "<marker id=\"arrow-grey\" viewBox=\"0 0 10 10\" refX=\"9\" refY=\"5\" markerWidth=\"6\" "
           "markerHeight=\"6\" orient=\"auto\"><path d=\"M 0 0 L 10 5 L 0 10 z\" fill=\"#888\"/></marker></defs>\n";
    svg += "<rect x=\"0\" y=\"0\" width=\"" + fmt(width_) + "\" height=\"" + fmt(height_) + "\" fill=\"#ffffff\"/>\n";
    svg += "<rect x=\"" + fmt(pad) + "\" y=\"" + fmt(title_h) + "\" width=\"" + fmt(plot_w_) + "\" height=\"" +
           fmt(plot_h_) + "\" fill=\"#fbfbfb\" stroke=\"#dddddd\"/>\n";
    svg += "<text x=\"" + fmt(pad) + "\" y=\"20\" font-family=\"sans-serif\" font-size=\"15\" font-weight=\"bold\">" +
           xml_escape(title) + "</text>\n";
    svg += "<text x=\"" + fmt(pad) + "\" y=\"38\" font-family=\"sans-serif\" font-size=\"12\" fill=\"#444\">" +
           xml_escape(subtitle) + "</text>\n";
    static const char* axis_names[3] = {"x", "y", "z"};
    svg += "<text x=\"" + fmt(pad + plot_w_ - 4) + "\" y=\"" + fmt(title_h + plot_h_ - 4) +
           "\" text-anchor=\"end\" font-family=\"sans-serif\" font-size=\"10\" fill=\"#999\">" + axis_names[plane_.u] +
           " \u2192, " + axis_names[plane_.v] + " \u2191</text>\n";
  }

  // Obstacles at the time drawn, under everything else: polygons, half-planes clipped to the
  // view, capsules as stadiums.
  void obstacles(std::string& svg) const {
    const std::size_t n = scene_.n(), m = scene_.m();
    if (m == 0) return;
    svg += "<g id=\"obstacles\">\n";
    const std::vector<Point2> view = {Point2(bounds_.umin, bounds_.vmin), Point2(bounds_.umax, bounds_.vmin),
                                      Point2(bounds_.umax, bounds_.vmax), Point2(bounds_.umin, bounds_.vmax)};
    for (std::size_t k = 0; k < m; ++k) {
      const Shadow& s = shadows_[k];
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
        const std::string arc = "A " + fmt(s.radius * scale_) + " " + fmt(s.radius * scale_) + " 0 0 1 ";
        const auto at = [&](const Point2& x) { return fmt(sx(x[0])) + " " + fmt(sy(x[1])); };
        d += "M " + at(s.ends[0] + side) + " L " + at(s.ends[1] + side) + " " + arc + at(s.ends[1] - side) + " L " +
             at(s.ends[0] - side) + " " + arc + at(s.ends[0] + side) + " Z";
      }
      const bool red = scene_.red[n + k];
      const char* color = red ? overlap_color : obstacle_color;
      svg += "<path class=\"" + std::string(red ? "obstacle overlapping" : "obstacle") + "\" data-id=\"" +
             xml_escape(scene_.set.obstacles[k].id) + "\" data-type=\"" + obstacle_type<N>(scene_.set.obstacles[k]) +
             "\" d=\"" + d + "\" fill=\"" + color + "\" fill-opacity=\"0.2\" fill-rule=\"nonzero\" stroke=\"" + color +
             "\" stroke-width=\"1\" stroke-linejoin=\"round\"/>\n";
    }
    svg += "</g>\n";
  }

  // Start positions and the paths of the centers.
  void paths(std::string& svg) const {
    const auto& bodies = scene_.set.bodies;
    svg += "<g id=\"paths\">\n";
    for (std::size_t i = 0; i < scene_.n(); ++i) {
      if (!moves<N>(bodies[i])) continue;
      const char* color = body_color(i);
      if (scene_.time != scene_.w.t0) svg += ellipse(ghosts_[i], "start", bodies[i].id, "none", color, 0.0, "4 3");
      const Vec<double, N> c0 = bodies[i].shape.center() + bodies[i].motion.velocity * scene_.w.t0;
      const Vec<double, N> c1 = bodies[i].shape.center() + bodies[i].motion.velocity * scene_.t_end;
      if ((c1 - c0).norm() * scale_ < 1.0) continue;
      svg += "<line class=\"path\" data-id=\"" + xml_escape(bodies[i].id) + "\" x1=\"" + fmt(sx(c0[plane_.u])) +
             "\" y1=\"" + fmt(sy(c0[plane_.v])) + "\" x2=\"" + fmt(sx(c1[plane_.u])) + "\" y2=\"" +
             fmt(sy(c1[plane_.v])) + "\" stroke=\"#888\" stroke-width=\"1\" stroke-dasharray=\"6 4\" "
             "marker-end=\"url(#arrow-grey)\"/>\n";
    }
    svg += "</g>\n";
  }

  // The bodies at the time drawn, labeled where there are few.
  void bodies(std::string& svg) const {
    const auto& bodies = scene_.set.bodies;
    const std::size_t n = scene_.n();
    svg += "<g id=\"bodies\">\n";
    for (std::size_t i = 0; i < n; ++i) {
      const char* color = body_color(i);
      svg += ellipse(shapes_[i], scene_.red[i] ? "body overlapping" : "body", bodies[i].id, color, color, 0.25, nullptr);
    }
    if (n <= max_labels)
      for (std::size_t i = 0; i < n; ++i)
        svg += "<text class=\"label\" x=\"" + fmt(sx(shapes_[i].cu)) + "\" y=\"" + fmt(sy(shapes_[i].cv) + 4) +
               "\" text-anchor=\"middle\" font-family=\"sans-serif\" font-size=\"11\" fill=\"#222\">" +
               xml_escape(bodies[i].id) + "</text>\n";
    svg += "</g>\n";
  }

  // Contact points and normals.
  void contacts(std::string& svg) const {
    svg += "<g id=\"contacts\">\n";
    for (std::size_t k = 0; k < scene_.contacts.size(); ++k) {
      const Contact<double, N>& c = scene_.contacts[k].contact;
      if (!has_contact_point(c.status)) continue;
      const double px = sx(c.point[plane_.u]), py = sy(c.point[plane_.v]);
      const double nu = c.normal[plane_.u], nv = c.normal[plane_.v];
      const double len = 36.0;
      svg += "<g class=\"contact\" data-a=\"" + xml_escape(scene_.id_of(scene_.set.pairs[k].first)) + "\" data-b=\"" +
             xml_escape(scene_.id_of(scene_.set.pairs[k].second)) + "\" data-time=\"" + number_string(c.time) + "\">";
      if (std::hypot(nu, nv) > 1e-3)
        svg += "<line class=\"contact-normal\" x1=\"" + fmt(px) + "\" y1=\"" + fmt(py) + "\" x2=\"" +
               fmt(px + len * nu) + "\" y2=\"" + fmt(py - len * nv) + "\" stroke=\"" + contact_color +
               "\" stroke-width=\"1.5\" marker-end=\"url(#arrow-black)\"/>";
      svg += "<circle class=\"contact-point\" cx=\"" + fmt(px) + "\" cy=\"" + fmt(py) + "\" r=\"4\" fill=\"#ffffff\" "
             "stroke=\"" + std::string(contact_color) + "\" stroke-width=\"2\"/></g>\n";
    }
    svg += "</g>\n";
  }

  void legend(std::string& svg) const {
    const auto& bodies = scene_.set.bodies;
    const std::size_t n = scene_.n(), m = scene_.m();
    const double lx = pad + plot_w_ + pad + 10;
    double ly = title_h + 8;
    svg += "<g id=\"legend\" font-family=\"sans-serif\" font-size=\"12\">\n";
    auto legend_text = [&](double x, const std::string& text, const char* cls = "legend-entry") {
      svg += "<text class=\"" + std::string(cls) + "\" x=\"" + fmt(x) + "\" y=\"" + fmt(ly + 4) + "\">" +
             xml_escape(text) + "</text>\n";
    };
    auto swatch = [&](const char* color, const char* opacity) {
      svg += "<rect x=\"" + fmt(lx) + "\" y=\"" + fmt(ly - 6) + "\" width=\"18\" height=\"12\" fill=\"" + color +
             "\" fill-opacity=\"" + opacity + "\" stroke=\"" + color + "\"/>\n";
    };
    svg += "<text x=\"" + fmt(lx) + "\" y=\"" + fmt(ly + 4) + "\" font-weight=\"bold\">Legend</text>\n";
    ly += 22;
    if (list_bodies_) {
      for (std::size_t i = 0; i < n; ++i) {
        swatch(body_color(i), "0.25");
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
    swatch(overlap_color, "0.25");
    legend_text(lx + 26, "overlapping at t (" + std::to_string(scene_.n_red) + " bodies)");
    ly += row_h;
    if (m > 0) {
      swatch(obstacle_color, "0.2");
      legend_text(lx + 26, "obstacles (" + std::to_string(m) + ", " + std::to_string(scene_.n_red_obstacles) +
                               " overlapped at t)");
      ly += row_h;
    }
    if (scene_.any_moving) {
      svg += "<ellipse cx=\"" + fmt(lx + 9) + "\" cy=\"" + fmt(ly) + "\" rx=\"9\" ry=\"5\" fill=\"none\" stroke=\"#555\" "
             "stroke-dasharray=\"4 3\"/>\n";
      legend_text(lx + 26, "position at t = " + number_string(scene_.w.t0));
      ly += row_h;
      svg += "<line x1=\"" + fmt(lx) + "\" y1=\"" + fmt(ly) + "\" x2=\"" + fmt(lx + 18) + "\" y2=\"" + fmt(ly) +
             "\" stroke=\"#888\" stroke-dasharray=\"6 4\" marker-end=\"url(#arrow-grey)\"/>\n";
      legend_text(lx + 26, "path of the center");
      ly += row_h;
    }
    if (scene_.contact) {
      svg += "<circle cx=\"" + fmt(lx + 9) + "\" cy=\"" + fmt(ly) + "\" r=\"4\" fill=\"#fff\" stroke=\"#000\" "
             "stroke-width=\"2\"/>\n";
      legend_text(lx + 26, "contact point (" + std::to_string(scene_.n_contacts) + ")");
      ly += row_h;
      svg += "<line x1=\"" + fmt(lx) + "\" y1=\"" + fmt(ly) + "\" x2=\"" + fmt(lx + 18) + "\" y2=\"" + fmt(ly) +
             "\" stroke=\"#000\" stroke-width=\"1.5\" marker-end=\"url(#arrow-black)\"/>\n";
      legend_text(lx + 26, "contact normal (a to b)");
      ly += row_h;
    }
    svg += "</g>\n";
  }

  const Scene<N>& scene_;
  const Plane& plane_;
  std::vector<Outline> shapes_, ghosts_;
  std::vector<Shadow> shadows_;
  Bounds bounds_;
  double scale_ = 1, plot_w_ = 0, plot_h_ = 0, width_ = 0, height_ = 0;
  bool list_bodies_ = true;
};

template <int N>
int render(const Input& in, const RenderOptions& opt, const Plane& plane) {
  const Scene<N> scene = scene_of<N>(in, opt);
  std::string subtitle = "t = " + number_string(scene.time) + " (" + scene.time_note + ")";
  if (in.kind == InputKind::pairs_csv) subtitle = "row " + std::to_string(opt.row) + ", " + subtitle;
  if (N == 3) subtitle += ", projected onto the " + plane.name + " plane";
  const std::string svg = Drawing<N>(scene, plane, opt.width).svg(in.title, subtitle);
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
