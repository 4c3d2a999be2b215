// ellipsect's queries in MuJoCo's collision table (include/ellipsect/mujoco.hpp).
#include <ellipsect/mujoco.hpp>

#include <ellipsect/box.hpp>
#include <ellipsect/capsule.hpp>
#include <ellipsect/distance.hpp>
#include <ellipsect/half_space.hpp>
#include <ellipsect/margin.hpp>
#include <ellipsect/shapes.hpp>

#include <array>
#include <atomic>
#include <cstdio>
#include <exception>
#include <optional>
#include <utility>

namespace ellipsect::mujoco {
namespace {

using Body = Ellipsoid3<double>;
using Vec3d = Vec3<double>;
using Mat3d = Mat3<double>;

// The types whose pairs with the ellipsoid collide() answers.
constexpr std::array<int, 5> partner_types = {mjGEOM_ELLIPSOID, mjGEOM_SPHERE, mjGEOM_PLANE, mjGEOM_CAPSULE,
                                              mjGEOM_BOX};

struct Saved {
  bool installed = false;
  std::array<mjfCollision, partner_types.size()> forward{}, backward{};  // [ELLIPSOID][t], [t][ELLIPSOID]
};
Saved saved;

std::atomic<std::uint64_t> calls{0}, contacts{0}, not_converged{0};

Vec3d position(const mjData* d, int g) { return Vec3d(d->geom_xpos[3 * g], d->geom_xpos[3 * g + 1], d->geom_xpos[3 * g + 2]); }
// geom_xmat is row-major, its columns the geom's local axes in the world frame.
Mat3d orientation(const mjData* d, int g) { return Eigen::Map<const Eigen::Matrix<mjtNum, 3, 3, Eigen::RowMajor>>(d->geom_xmat + 9 * g); }
Vec3d size(const mjModel* m, int g) { return Vec3d(m->geom_size[3 * g], m->geom_size[3 * g + 1], m->geom_size[3 * g + 2]); }

// The ellipsoid geom ge and geom go (of a partner type) as ellipsect's shapes, given to f.
template <class F>
auto with_shapes(const mjModel* m, const mjData* d, int ge, int go, F&& f) {
  const Body a = make_ellipsoid(position(d, ge), orientation(d, ge), size(m, ge));
  const Vec3d c = position(d, go);
  const Mat3d r = orientation(d, go);
  const Vec3d s = size(m, go);
  switch (m->geom_type[go]) {
    case mjGEOM_ELLIPSOID: return f(a, make_ellipsoid(c, r, s));
    case mjGEOM_SPHERE: return f(a, make_ball(c, s[0]));
    // A plane geom is the half-space below its local xy plane; its normal is the local z axis.
    case mjGEOM_PLANE: return f(a, make_half_space<double, 3>(c, r.col(2)));
    // A capsule's segment runs along its local z axis, half-length size[1], radius size[0].
    case mjGEOM_CAPSULE: return f(a, make_capsule<double, 3>(c - s[1] * r.col(2), c + s[1] * r.col(2), s[0]));
    case mjGEOM_BOX: return f(a, make_box(c, r, s));
    default: break;
  }
  throw InputError("geom type", "not a type collide() answers");
}

const char* geom_name(const mjModel* m, int g) {
  const char* name = m->names + m->name_geomadr[g];
  return *name ? name : "(unnamed)";
}

}  // namespace

int collide(const mjModel* m, const mjData* d, mjContact* con, int g1, int g2, mjtNum margin) {
  calls.fetch_add(1, std::memory_order_relaxed);
  // The ellipsoid is a; the normal is turned to run from g1 to g2 when it is g2.
  const bool ellipsoid_first = m->geom_type[g1] == mjGEOM_ELLIPSOID;
  const int ge = ellipsoid_first ? g1 : g2, go = ellipsoid_first ? g2 : g1;
  std::optional<Distance<double, 3>> found;
  try {
    found = with_shapes(m, d, ge, go, [margin](const Body& a, const auto& b) { return signed_distance_within(a, b, margin); });
  } catch (const std::exception& e) {
    // mju_error does not return unless the user's handler does (MuJoCo's Python bindings
    // throw from it): no contact then.
    std::array<char, 512> message{};
    std::snprintf(message.data(), message.size(), "ellipsect::mujoco::collide: geoms %d '%s' and %d '%s': %s", g1,
                  geom_name(m, g1), g2, geom_name(m, g2), e.what());
    mju_error(message.data());
    return 0;
  }
  if (!found) return 0;
  const Distance<double, 3>& r = *found;
  if (r.status == DistanceStatus::did_not_converge) not_converged.fetch_add(1, std::memory_order_relaxed);
  if (!(r.distance <= margin)) return 0;
  const double sign = ellipsoid_first ? 1.0 : -1.0;
  con->dist = r.distance;
  for (int i = 0; i < 3; ++i) {
    con->pos[i] = 0.5 * (r.point_a[i] + r.point_b[i]);
    con->frame[i] = sign * r.normal[i];
    con->frame[i + 3] = 0;
    con->frame[i + 6] = 0;
  }
  contacts.fetch_add(1, std::memory_order_relaxed);
  return 1;
}

void install() noexcept {
  if (saved.installed) return;
  for (std::size_t i = 0; i < partner_types.size(); ++i) {
    const int t = partner_types[i];
    saved.forward[i] = std::exchange(mjCOLLISIONFUNC[mjGEOM_ELLIPSOID][t], collide);
    saved.backward[i] = std::exchange(mjCOLLISIONFUNC[t][mjGEOM_ELLIPSOID], collide);
  }
  saved.installed = true;
}

void uninstall() noexcept {
  if (!saved.installed) return;
  // In reverse order: [ELLIPSOID][ELLIPSOID] was saved twice, first with MuJoCo's entry.
  for (std::size_t i = partner_types.size(); i-- > 0;) {
    const int t = partner_types[i];
    mjCOLLISIONFUNC[t][mjGEOM_ELLIPSOID] = saved.backward[i];
    mjCOLLISIONFUNC[mjGEOM_ELLIPSOID][t] = saved.forward[i];
  }
  saved.installed = false;
}

bool installed() noexcept { return saved.installed; }

Counters counters() noexcept {
  return {calls.load(std::memory_order_relaxed), contacts.load(std::memory_order_relaxed),
          not_converged.load(std::memory_order_relaxed)};
}

void reset_counters() noexcept {
  calls.store(0, std::memory_order_relaxed);
  contacts.store(0, std::memory_order_relaxed);
  not_converged.store(0, std::memory_order_relaxed);
}

}  // namespace ellipsect::mujoco
