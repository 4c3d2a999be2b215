// The least-squares ellipse (geometry.hpp, fit_ellipsoid) side by side with OpenCV's
// fitEllipse, fitEllipseAMS and fitEllipseDirect on the same seeded 2D clouds.
//
// Clouds (20 seeds each, 5 for 10^5 points; the generating ellipse known):
//   ellipse     uniform in angle on the ellipse of radii (40, 15), noise of 1% of the major
//               radius (normal, per coordinate), 1000 points, a random pose about (320, 240)
//   near_circle the circle of radius 100 about (320, 240), radial noise 1e-4 of the radius,
//               10^3, 10^4, 10^5 points
//   arc30       a 30 degree arc of the circle of radius 100, noise 1e-3 of the radius, 200 points
//   hyperbola   both branches of x^2 / 4 - y^2 = 1, |y| <= sinh 1.5, noise 1e-3, 400 points:
//               no ellipse is right
// OpenCV takes float points: it gets each cloud less its first point, its answer moved back.
// Timed: fit/<method>/<cloud>/<m>, per fit, cycling over the cloud's seeds.
// Counters, over the seeds: far (the returned ellipse's center off the generating one's by more
// than 10% of its largest radius; on hyperbola every returned ellipse), refused (no ellipse:
// ellipsect's status not_an_ellipse or did_not_converge, OpenCV's size not finite or not
// positive), rms (the mean RMS orthogonal residual of the returned ellipses, by closest_point),
// below_ellipsect (the clouds where the method's residual is below ellipsect's by more than
// 1e-9 relative, both returning an ellipse), near_where_ellipsect_far (the clouds where the
// method's ellipse is not far and ellipsect's converged one is).
#include <ellipsect/geometry.hpp>
#include <ellipsect/point.hpp>

#include "scenarios/scenarios.hpp"

#include <benchmark/benchmark.h>

#ifdef ELLIPSECT_HAVE_OPENCV
#include <opencv2/imgproc.hpp>
#endif

#include <cmath>
#include <map>
#include <numbers>
#include <optional>
#include <random>
#include <string>
#include <vector>

namespace {

using namespace ellipsect;
using Cloud = std::vector<Vec2<double>>;

struct Case {
  Cloud points;
  Vec2<double> center;  // of the generating ellipse
  double size = 1;      // its largest radius
  bool ellipse = true;  // false: a hyperbola
};

Case make_case(const std::string& kind, int m, int seed) {
  std::mt19937_64 rng(4848 + 1000 * seed + m + int(kind.size()));
  std::normal_distribution<double> g;
  std::uniform_real_distribution<double> u(0, 1);
  Case k;
  k.center = Vec2<double>(320, 240);
  const Mat2<double> R = scenarios::detail::orthogonal<2>(rng);
  for (int i = 0; i < m; ++i) {
    Vec2<double> p;
    if (kind == "ellipse") {
      const double t = 2 * std::numbers::pi * u(rng);
      p = k.center + R * Vec2<double>(40 * std::cos(t), 15 * std::sin(t)) + 0.4 * Vec2<double>(g(rng), g(rng));
      k.size = 40;
    } else if (kind == "near_circle") {
      const double t = 2 * std::numbers::pi * u(rng);
      p = k.center + 100 * (1 + 1e-4 * g(rng)) * Vec2<double>(std::cos(t), std::sin(t));
      k.size = 100;
    } else if (kind == "arc30") {
      const double t = 2 * std::numbers::pi * seed / 20 + std::numbers::pi / 6 * u(rng);
      p = k.center + 100 * Vec2<double>(std::cos(t), std::sin(t)) + 0.1 * Vec2<double>(g(rng), g(rng));
      k.size = 100;
    } else {  // hyperbola
      const double s = 3 * u(rng) - 1.5, branch = i % 2 ? -1 : 1;
      p = k.center + 10 * R * Vec2<double>(branch * 2 * std::cosh(s), std::sinh(s)) + 0.01 * Vec2<double>(g(rng), g(rng));
      k.ellipse = false;
      k.size = 10;
    }
    k.points.push_back(p);
  }
  return k;
}

const std::vector<Case>& cases_of(const std::string& kind, int m) {
  static std::map<std::pair<std::string, int>, std::vector<Case>> all;
  auto it = all.find({kind, m});
  if (it == all.end()) {
    std::vector<Case> cases;
    for (int seed = 0; seed < (m >= 100000 ? 5 : 20); ++seed) cases.push_back(make_case(kind, m, seed));
    it = all.emplace(std::make_pair(kind, m), std::move(cases)).first;
  }
  return it->second;
}

double rms_of(const Ellipse2<double>& e, const Cloud& points) {
  long double ss = 0;
  for (const auto& p : points) {
    const double d = closest_point(e, p).signed_distance;
    ss += (long double)d * d;
  }
  return double(std::sqrt(ss / (long double)points.size()));
}

// A method's answer on a cloud: an ellipse or none.
using Method = std::optional<Ellipse2<double>> (*)(const Cloud&);

std::optional<Ellipse2<double>> ellipsect_fit(const Cloud& points) {
  const auto f = fit_ellipsoid<double, 2>(points);
  if (f.status != FitStatus::converged) return std::nullopt;
  return f.body;
}

#ifdef ELLIPSECT_HAVE_OPENCV
template <cv::RotatedRect (*Fit)(cv::InputArray)>
std::optional<Ellipse2<double>> opencv_fit(const Cloud& points) {
  std::vector<cv::Point2f> shifted;
  shifted.reserve(points.size());
  for (const auto& p : points) shifted.emplace_back(float(p[0] - points[0][0]), float(p[1] - points[0][1]));
  cv::RotatedRect r;
  try {
    r = Fit(shifted);
  } catch (const cv::Exception&) {
    return std::nullopt;
  }
  if (!(std::isfinite(r.size.width) && std::isfinite(r.size.height) && r.size.width > 0 && r.size.height > 0 &&
        std::isfinite(r.center.x) && std::isfinite(r.center.y)))
    return std::nullopt;
  try {
    return make_ellipse<double>(Vec2<double>(double(r.center.x) + points[0][0], double(r.center.y) + points[0][1]),
                                double(r.angle) * std::numbers::pi / 180, Vec2<double>(r.size.width / 2.0, r.size.height / 2.0));
  } catch (const InputError&) {
    return std::nullopt;
  }
}
cv::RotatedRect fit_plain(cv::InputArray p) { return cv::fitEllipse(p); }
cv::RotatedRect fit_ams(cv::InputArray p) { return cv::fitEllipseAMS(p); }
cv::RotatedRect fit_direct(cv::InputArray p) { return cv::fitEllipseDirect(p); }
#endif

void fit_case(benchmark::State& state, Method method, std::string kind, int m) {
  const auto& cases = cases_of(kind, m);
  std::size_t i = 0;
  for (auto _ : state) {
    auto e = method(cases[i++ % cases.size()].points);
    benchmark::DoNotOptimize(e);
  }
  int far = 0, refused = 0, below = 0, answered = 0, near_where_far = 0;
  double rms = 0;
  for (const auto& k : cases) {
    const auto e = method(k.points);
    const auto ours = ellipsect_fit(k.points);
    if (!e) {
      ++refused;
      continue;
    }
    ++answered;
    const double r = rms_of(*e, k.points);
    rms += r;
    const bool is_far = !k.ellipse || (e->center() - k.center).norm() > 0.1 * k.size;
    far += is_far;
    if (!is_far && ours && (!k.ellipse || (ours->center() - k.center).norm() > 0.1 * k.size)) ++near_where_far;
    if (ours && r < rms_of(*ours, k.points) * (1 - 1e-9)) ++below;
  }
  state.counters["far"] = far;
  state.counters["refused"] = refused;
  state.counters["rms"] = answered ? rms / answered : std::nan("");
  state.counters["below_ellipsect"] = below;
  state.counters["near_where_ellipsect_far"] = near_where_far;
  state.counters["clouds"] = double(cases.size());
}

void register_all() {
  std::vector<std::pair<std::string, Method>> methods{{"ellipsect", ellipsect_fit}};
#ifdef ELLIPSECT_HAVE_OPENCV
  methods.emplace_back("opencv_fitEllipse", opencv_fit<fit_plain>);
  methods.emplace_back("opencv_fitEllipseAMS", opencv_fit<fit_ams>);
  methods.emplace_back("opencv_fitEllipseDirect", opencv_fit<fit_direct>);
#endif
  const std::vector<std::pair<std::string, int>> clouds{{"ellipse", 1000},    {"near_circle", 1000}, {"near_circle", 10000},
                                                        {"near_circle", 100000}, {"arc30", 200},     {"hyperbola", 400}};
  for (const auto& [kind, m] : clouds)
    for (const auto& [name, method] : methods)
      benchmark::RegisterBenchmark(("fit/" + name + "/" + kind + "/" + std::to_string(m)).c_str(), fit_case, method, kind, m)
          ->Unit(benchmark::kMicrosecond);
}

}  // namespace

int main(int argc, char** argv) {
  register_all();
  benchmark::Initialize(&argc, argv);
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
