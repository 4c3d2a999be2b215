// MuJoCo scenes shared by tests/engines, bench/bench_mujoco.cpp and examples/mujoco_scenes.cpp:
// MJCF text, and a model and its data loaded from it.
#pragma once

#include <mujoco/mujoco.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <memory>
#include <stdexcept>
#include <string>

namespace ellipsect::scenarios {

// A compiled model and its data; throws std::runtime_error with MuJoCo's message when the
// MJCF does not compile. mj_loadXML reads a file: the text is written to `path` first.
struct MujocoScene {
  MujocoScene(const std::string& mjcf, const std::string& path) {
    std::ofstream(path) << mjcf;
    std::array<char, 1000> error{};
    m.reset(mj_loadXML(path.c_str(), nullptr, error.data(), static_cast<int>(error.size())));
    if (!m) throw std::runtime_error("mj_loadXML: " + std::string(error.data()));
    d.reset(mj_makeData(m.get()));
  }
  int geom(const std::string& name) const { return mj_name2id(m.get(), mjOBJ_GEOM, name.c_str()); }
  int body(const std::string& name) const { return mj_name2id(m.get(), mjOBJ_BODY, name.c_str()); }
  void step(int steps) {
    for (int i = 0; i < steps; ++i) mj_step(m.get(), d.get());
  }

  std::unique_ptr<mjModel, decltype(&mj_deleteModel)> m{nullptr, mj_deleteModel};
  std::unique_ptr<mjData, decltype(&mj_deleteData)> d{nullptr, mj_deleteData};
};

// Walls of the pile's box: static boxes whose inner faces are at |x|, |y| = pile_half_width.
inline constexpr double pile_half_width = 0.55;

// side x side x layers ellipsoids (radii 0.1, 0.075, 0.05, mass 0.1, geoms "e0", "e1", ...) on
// a lattice of spacing 0.22, each turned by its own angles, above a floor plane ("floor") in a
// box of four static walls ("w0" .. "w3"); MuJoCo's default contact parameters, timestep
// 2 ms, angles in radians.
inline std::string pile_mjcf(int side, int layers) {
  std::string xml = R"(<mujoco><compiler angle="radian"/><option timestep="0.002"/><size nconmax="2000" njmax="6000"/><worldbody>
      <geom name="floor" type="plane" size="0 0 1"/>
      <geom name="w0" type="box" pos="0.6 0 0.5" size="0.05 0.65 0.5"/>
      <geom name="w1" type="box" pos="-0.6 0 0.5" size="0.05 0.65 0.5"/>
      <geom name="w2" type="box" pos="0 0.6 0.5" size="0.65 0.05 0.5"/>
      <geom name="w3" type="box" pos="0 -0.6 0.5" size="0.65 0.05 0.5"/>)";
  int n = 0;
  for (int k = 0; k < layers; ++k)
    for (int i = 0; i < side; ++i)
      for (int j = 0; j < side; ++j, ++n) {
        std::array<char, 300> b{};
        std::snprintf(b.data(), b.size(),
                      R"(<body pos="%g %g %g" euler="%g %g 0"><freejoint/><geom name="e%d" type="ellipsoid" size="0.1 0.075 0.05" mass="0.1"/></body>)",
                      0.22 * (i - 0.5 * (side - 1)), 0.22 * (j - 0.5 * (side - 1)), 0.2 + 0.22 * k, 0.3 * (i + k),
                      0.5 * j, n);
        xml += b.data();
      }
  return xml + "</worldbody></mujoco>";
}

// A prolate spheroid (radii a, a, c; geom and body "spheroid", mass 1) on a floor plane, its long
// axis tilted by `tilt` radians about y from the vertical, its lowest point on the floor, at rest;
// and a ball of radius a and mass 1 ("ball") resting on the floor far from it. Timestep 1 ms.
inline std::string spheroid_mjcf(double a, double c, double tilt) {
  const double s = std::sin(tilt), co = std::cos(tilt);
  const double h = std::sqrt(a * a * s * s + c * c * co * co);
  std::array<char, 1200> xml{};
  std::snprintf(xml.data(), xml.size(), R"(<mujoco><compiler angle="radian"/><option timestep="0.001"/><worldbody>
      <geom name="floor" type="plane" size="0 0 1"/>
      <body name="spheroid" pos="0 0 %.17g" euler="0 %.17g 0"><freejoint/>
        <geom name="spheroid" type="ellipsoid" size="%.17g %.17g %.17g" mass="1"/></body>
      <body name="ball" pos="5 0 %.17g"><freejoint/><geom name="ball" type="sphere" size="%.17g" mass="1"/></body>
      </worldbody></mujoco>)",
                h, tilt, a, a, c, a, a);
  return xml.data();
}

}  // namespace ellipsect::scenarios
