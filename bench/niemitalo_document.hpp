// A faithful port of the ellipse-circle test of Niemitalo's document (2012, public domain;
// docs/niemitalo.md): `iterate` and the axis-aligned `collide(x0, y0, w, h, x1, y1, r)`,
// templated on the scalar and with the coefficient tables in std::vector. Only the
// benchmark uses it, as the peer of polygonal_overlap: it returns false when out of
// iterations and chooses sub-triangles by the document's shortcuts.
#pragma once

#include <cmath>
#include <vector>

namespace ellipsect::bench {

template <class T>
class DocumentEllipseCircle {
 public:
  explicit DocumentEllipseCircle(int max_iterations) : max_iterations_(max_iterations) {
    for (int t = 0; t <= max_iterations; ++t) {
      const int nodes = 4 << t;
      inner_.push_back(T(0.5 / std::cos(4 * std::acos(0.0) / nodes)));
      outer_.push_back(T(0.5 / (std::cos(2 * std::acos(0.0) / nodes) * std::cos(2 * std::acos(0.0) / nodes))));
    }
  }

  // Ellipse of horizontal radius w and vertical radius h at (x0, y0), circle of radius r at (x1, y1).
  bool collide(T x0, T y0, T w, T h, T x1, T y1, T r) const {
    const T x = std::abs(x1 - x0), y = std::abs(y1 - y0);
    if (x * x + (h - y) * (h - y) <= r * r || (w - x) * (w - x) + y * y <= r * r || x * h + y * w <= w * h ||
        ((x * h + y * w - w * h) * (x * h + y * w - w * h) <= r * r * (w * w + h * h) && x * w - y * h >= -h * h &&
         x * w - y * h <= w * w))
      return true;
    if ((x - w) * (x - w) + (y - h) * (y - h) <= r * r || (x <= w && y - r <= h) || (y <= h && x - r <= w))
      return iterate(x, y, w, 0, 0, h, r * r);
    return false;
  }

 private:
  bool iterate(T x, T y, T c0x, T c0y, T c2x, T c2y, T rr) const {
    for (int t = 1; t <= max_iterations_; t++) {
      const T c1x = (c0x + c2x) * inner_[t];
      const T c1y = (c0y + c2y) * inner_[t];
      const T tx = x - c1x;
      const T ty = y - c1y;
      if (tx * tx + ty * ty <= rr) return true;
      const T t2x = c2x - c1x;
      const T t2y = c2y - c1y;
      if (tx * t2x + ty * t2y >= 0 && tx * t2x + ty * t2y <= t2x * t2x + t2y * t2y &&
          (ty * t2x - tx * t2y >= 0 || rr * (t2x * t2x + t2y * t2y) >= (ty * t2x - tx * t2y) * (ty * t2x - tx * t2y)))
        return true;
      const T t0x = c0x - c1x;
      const T t0y = c0y - c1y;
      if (tx * t0x + ty * t0y >= 0 && tx * t0x + ty * t0y <= t0x * t0x + t0y * t0y &&
          (ty * t0x - tx * t0y <= 0 || rr * (t0x * t0x + t0y * t0y) >= (ty * t0x - tx * t0y) * (ty * t0x - tx * t0y)))
        return true;
      const T c3x = (c0x + c1x) * outer_[t];
      const T c3y = (c0y + c1y) * outer_[t];
      if ((c3x - x) * (c3x - x) + (c3y - y) * (c3y - y) < rr) {
        c2x = c1x;
        c2y = c1y;
        continue;
      }
      const T c4x = c1x - c3x + c1x;
      const T c4y = c1y - c3y + c1y;
      if ((c4x - x) * (c4x - x) + (c4y - y) * (c4y - y) < rr) {
        c0x = c1x;
        c0y = c1y;
        continue;
      }
      const T t3x = c3x - c1x;
      const T t3y = c3y - c1y;
      if (ty * t3x - tx * t3y <= 0 || rr * (t3x * t3x + t3y * t3y) > (ty * t3x - tx * t3y) * (ty * t3x - tx * t3y)) {
        if (tx * t3x + ty * t3y > 0) {
          if (std::abs(tx * t3x + ty * t3y) <= t3x * t3x + t3y * t3y ||
              (x - c3x) * (c0x - c3x) + (y - c3y) * (c0y - c3y) >= 0) {
            c2x = c1x;
            c2y = c1y;
            continue;
          }
        } else if (-(tx * t3x + ty * t3y) <= t3x * t3x + t3y * t3y ||
                   (x - c4x) * (c2x - c4x) + (y - c4y) * (c2y - c4y) >= 0) {
          c0x = c1x;
          c0y = c1y;
          continue;
        }
      }
      return false;
    }
    return false;  // out of iterations
  }

  int max_iterations_;
  std::vector<T> inner_, outer_;
};

}  // namespace ellipsect::bench
