// SVG pictures for the examples: bodies in a periodic box, and side views of scenes.
#pragma once

#include <ellipsect/broad_phase.hpp>
#include <ellipsect/shapes.hpp>

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <string>
#include <vector>

namespace picture {

using namespace ellipsect;

// One ellipse of the picture: center, semi-axes and angle (degrees), depth for the order.
struct Shadow {
  double x, y, rx, ry, degrees, depth;
};

// The shadow of an ellipsoid on the xy plane: the ellipse of the upper-left 2x2 block of
// A diag(r^2) A^T (for N = 2 the ellipse itself).
template <int N>
Shadow shadow(const Ellipsoid<double, N>& e) {
  const Mat<double, N> A = e.axes();
  const Mat<double, N> S = A * e.radii().cwiseProduct(e.radii()).asDiagonal() * A.transpose();
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eig(S.template topLeftCorner<2, 2>());
  const Eigen::Vector2d major = eig.eigenvectors().col(1);
  return {e.center().x(), e.center().y(), std::sqrt(eig.eigenvalues()[1]), std::sqrt(eig.eigenvalues()[0]),
          std::atan2(major.y(), major.x()) * 180.0 / M_PI, N == 3 ? double(e.center()[N - 1]) : 0.0};
}

// The bodies of a periodic box as SVG (2D: the ellipses; 3D: their shadows on the xy plane,
// far ones first, lighter), with the periodic images that reach into the picture.
template <int N>
void write_picture(const std::string& path, const std::vector<Ellipsoid<double, N>>& bodies, const PeriodicBox<N>& box) {
  const double w = box.size[0], h = box.size[1];
  double far = 1.0;
  if constexpr (N == 3) far = box.size[2];
  std::vector<Shadow> shadows;
  for (const auto& e : bodies) shadows.push_back(shadow(e));
  std::sort(shadows.begin(), shadows.end(), [](const Shadow& a, const Shadow& b) { return a.depth < b.depth; });
  std::ofstream out(path);
  out << "<svg xmlns=\"http://www.w3.org/2000/svg\" viewBox=\"0 0 " << w << ' ' << h << "\" width=\"600\" height=\""
      << 600.0 * h / w << "\">\n<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n<g transform=\"translate(0 " << h
      << ") scale(1 -1)\" stroke=\"#222\" stroke-width=\"" << 0.003 * w << "\">\n";
  for (const Shadow& s : shadows) {
    const int shade = int(80 + 150 * s.depth / far);
    for (int dx = -1; dx <= 1; ++dx)  // the periodic images that reach into the picture
      for (int dy = -1; dy <= 1; ++dy) {
        const double x = s.x + dx * w, y = s.y + dy * h;
        if (x + s.rx < 0 || x - s.rx > w || y + s.rx < 0 || y - s.rx > h) continue;
        out << "<ellipse cx=\"" << x << "\" cy=\"" << y << "\" rx=\"" << s.rx << "\" ry=\"" << s.ry
            << "\" transform=\"rotate(" << s.degrees << ' ' << x << ' ' << y << ")\" fill=\"rgb(" << shade << ','
            << shade << ",255)\"/>\n";
      }
  }
  out << "</g>\n</svg>\n";
}

// An axis-aligned box of a side view: center and half extents.
struct Block {
  Vec3<double> center, half;
};

// The side view (looking along +y: x to the right, z up) of ellipsoids and axis-aligned boxes
// over x in [-half_width, half_width], z in [0, height], the floor z = 0 as a line: the boxes
// grey behind, the ellipsoids' shadows on the xz plane, far ones (large y) first.
inline void write_side_view(const std::string& path, const std::vector<Ellipsoid3<double>>& bodies,
                            const std::vector<Block>& blocks, double half_width, double height) {
  // (x, y, z) -> (x + half_width, z, -y): the view's xy plane is the world's xz plane.
  Mat3<double> q;
  q << 1, 0, 0, 0, 0, 1, 0, -1, 0;
  std::vector<Shadow> shadows;
  for (const auto& e : bodies)
    shadows.push_back(shadow(make_ellipsoid<double>(q * e.center() + Vec3<double>(half_width, 0, 0), q * e.axes(), e.radii())));
  std::sort(shadows.begin(), shadows.end(), [](const Shadow& a, const Shadow& b) { return a.depth < b.depth; });
  const double w = 2 * half_width;
  std::ofstream out(path);
  out << "<svg xmlns=\"http://www.w3.org/2000/svg\" viewBox=\"0 0 " << w << ' ' << height << "\" width=\"600\" height=\""
      << 600.0 * height / w << "\">\n<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n<g transform=\"translate(0 "
      << height << ") scale(1 -1)\" stroke=\"#222\" stroke-width=\"" << 0.002 * w << "\">\n";
  for (const Block& b : blocks)
    out << "<rect x=\"" << b.center.x() - b.half.x() + half_width << "\" y=\"" << b.center.z() - b.half.z() << "\" width=\""
        << 2 * b.half.x() << "\" height=\"" << 2 * b.half.z() << "\" fill=\"#ccc\" fill-opacity=\"0.5\"/>\n";
  out << "<line x1=\"0\" y1=\"0\" x2=\"" << w << "\" y2=\"0\" stroke-width=\"" << 0.006 * w << "\"/>\n";
  for (const Shadow& s : shadows) {
    const int shade = std::clamp(int(160 + 200 * s.depth), 60, 230);
    out << "<ellipse cx=\"" << s.x << "\" cy=\"" << s.y << "\" rx=\"" << s.rx << "\" ry=\"" << s.ry
        << "\" transform=\"rotate(" << s.degrees << ' ' << s.x << ' ' << s.y << ")\" fill=\"rgb(" << shade << ','
        << shade << ",255)\"/>\n";
  }
  out << "</g>\n</svg>\n";
}

}  // namespace picture
