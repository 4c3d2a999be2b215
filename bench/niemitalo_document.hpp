// A faithful port of the collision tests of Niemitalo's document (2012, public domain;
// docs/niemitalo.md): `iterate`, the axis-aligned ellipse-circle `collide(x0, y0, w, h, x1,
// y1, r)` and the ellipse-ellipse `collide(x0, y0, wx0, wy0, hw0, x1, y1, wx1, wy1, hw1)`
// with its float intermediates, templated on the scalar and with the coefficient tables in
// std::vector. Only the benchmark uses it, as the peer of polygonal_overlap: it returns
// false when out of iterations and chooses sub-triangles by the document's shortcuts.
#pragma once

#include <cmath>
#include <vector>

namespace ellipsect::bench {

template <class T>
class DocumentTests {
 public:
  explicit DocumentTests(int max_iterations) : max_iterations_(max_iterations) {
    for (int t = 0; t <= max_iterations; ++t) {
      const int nodes = 4 << t;
      inner_.push_back(T(0.5 / std::cos(4 * std::acos(0.0) / nodes)));
      outer_.push_back(T(0.5 / (std::cos(2 * std::acos(0.0) / nodes) * std::cos(2 * std::acos(0.0) / nodes))));
    }
  }

  // Ellipses "0" and "1": ellipse at (x, y) with the radius vector (wx, wy) and the other
  // radius perpendicular to it, hw times as long.
  bool collide(T x0, T y0, T wx0, T wy0, T hw0, T x1, T y1, T wx1, T wy1, T hw1) const {
    float rr = hw1 * hw1 * (wx1 * wx1 + wy1 * wy1) * (wx1 * wx1 + wy1 * wy1) * (wx1 * wx1 + wy1 * wy1);
    float x = hw1 * wx1 * (wy1 * (y1 - y0) + wx1 * (x1 - x0)) - wy1 * (wx1 * (y1 - y0) - wy1 * (x1 - x0));
    float y = hw1 * wy1 * (wy1 * (y1 - y0) + wx1 * (x1 - x0)) + wx1 * (wx1 * (y1 - y0) - wy1 * (x1 - x0));
    float temp = wx0;
    wx0 = hw1 * wx1 * (wy1 * wy0 + wx1 * wx0) - wy1 * (wx1 * wy0 - wy1 * wx0);
    float temp2 = wy0;
    wy0 = hw1 * wy1 * (wy1 * wy0 + wx1 * temp) + wx1 * (wx1 * wy0 - wy1 * temp);
    float hx0 = hw1 * wx1 * (wy1 * (temp * hw0) - wx1 * temp2 * hw0) - wy1 * (wx1 * (temp * hw0) + wy1 * temp2 * hw0);
    float hy0 = hw1 * wy1 * (wy1 * (temp * hw0) - wx1 * temp2 * hw0) + wx1 * (wx1 * (temp * hw0) + wy1 * temp2 * hw0);
    if (wx0 * y - wy0 * x < 0) {
      x = -x;
      y = -y;
    }
    if ((wx0 - x) * (wx0 - x) + (wy0 - y) * (wy0 - y) <= rr) return true;
    if ((wx0 + x) * (wx0 + x) + (wy0 + y) * (wy0 + y) <= rr) return true;
    if ((hx0 - x) * (hx0 - x) + (hy0 - y) * (hy0 - y) <= rr) return true;
    if ((hx0 + x) * (hx0 + x) + (hy0 + y) * (hy0 + y) <= rr) return true;
    if (x * (hy0 - wy0) + y * (wx0 - hx0) <= hy0 * wx0 - hx0 * wy0 &&
        y * (wx0 + hx0) - x * (wy0 + hy0) <= hy0 * wx0 - hx0 * wy0)
      return true;
    if (x * (wx0 - hx0) - y * (hy0 - wy0) > hx0 * (wx0 - hx0) - hy0 * (hy0 - wy0) &&
        x * (wx0 - hx0) - y * (hy0 - wy0) < wx0 * (wx0 - hx0) - wy0 * (hy0 - wy0) &&
        (x * (hy0 - wy0) + y * (wx0 - hx0) - hy0 * wx0 + hx0 * wy0) *
                (x * (hy0 - wy0) + y * (wx0 - hx0) - hy0 * wx0 + hx0 * wy0) <=
            rr * ((wx0 - hx0) * (wx0 - hx0) + (wy0 - hy0) * (wy0 - hy0)))
      return true;
    if (x * (wx0 + hx0) + y * (wy0 + hy0) > -wx0 * (wx0 + hx0) - wy0 * (wy0 + hy0) &&
        x * (wx0 + hx0) + y * (wy0 + hy0) < hx0 * (wx0 + hx0) + hy0 * (wy0 + hy0) &&
        (y * (wx0 + hx0) - x * (wy0 + hy0) - hy0 * wx0 + hx0 * wy0) *
                (y * (wx0 + hx0) - x * (wy0 + hy0) - hy0 * wx0 + hx0 * wy0) <=
            rr * ((wx0 + hx0) * (wx0 + hx0) + (wy0 + hy0) * (wy0 + hy0)))
      return true;
    if ((hx0 - wx0 - x) * (hx0 - wx0 - x) + (hy0 - wy0 - y) * (hy0 - wy0 - y) <= rr)
      return iterate(x, y, hx0, hy0, -wx0, -wy0, rr);
    if ((hx0 + wx0 - x) * (hx0 + wx0 - x) + (hy0 + wy0 - y) * (hy0 + wy0 - y) <= rr)
      return iterate(x, y, wx0, wy0, hx0, hy0, rr);
    if ((wx0 - hx0 - x) * (wx0 - hx0 - x) + (wy0 - hy0 - y) * (wy0 - hy0 - y) <= rr)
      return iterate(x, y, -hx0, -hy0, wx0, wy0, rr);
    if ((-wx0 - hx0 - x) * (-wx0 - hx0 - x) + (-wy0 - hy0 - y) * (-wy0 - hy0 - y) <= rr)
      return iterate(x, y, -wx0, -wy0, -hx0, -hy0, rr);
    if (wx0 * y - wy0 * x < wx0 * hy0 - wy0 * hx0 && std::abs(hx0 * y - hy0 * x) < hy0 * wx0 - hx0 * wy0) {
      if (hx0 * y - hy0 * x > 0) return iterate(x, y, hx0, hy0, -wx0, -wy0, rr);
      return iterate(x, y, wx0, wy0, hx0, hy0, rr);
    }
    if (wx0 * x + wy0 * y > wx0 * (hx0 - wx0) + wy0 * (hy0 - wy0) &&
        wx0 * x + wy0 * y < wx0 * (hx0 + wx0) + wy0 * (hy0 + wy0) &&
        (wx0 * y - wy0 * x - hy0 * wx0 + hx0 * wy0) * (wx0 * y - wy0 * x - hy0 * wx0 + hx0 * wy0) <
            rr * (wx0 * wx0 + wy0 * wy0)) {
      if (wx0 * x + wy0 * y > wx0 * hx0 + wy0 * hy0) return iterate(x, y, wx0, wy0, hx0, hy0, rr);
      return iterate(x, y, hx0, hy0, -wx0, -wy0, rr);
    }
    if (hx0 * y - hy0 * x < 0) {
      x = -x;
      y = -y;
    }
    if (hx0 * x + hy0 * y > -hx0 * (wx0 + hx0) - hy0 * (wy0 + hy0) &&
        hx0 * x + hy0 * y < hx0 * (hx0 - wx0) + hy0 * (hy0 - wy0) &&
        (hx0 * y - hy0 * x - hy0 * wx0 + hx0 * wy0) * (hx0 * y - hy0 * x - hy0 * wx0 + hx0 * wy0) <
            rr * (hx0 * hx0 + hy0 * hy0)) {
      if (hx0 * x + hy0 * y > -hx0 * wx0 - hy0 * wy0) return iterate(x, y, hx0, hy0, -wx0, -wy0, rr);
      return iterate(x, y, -wx0, -wy0, -hx0, -hy0, rr);
    }
    return false;
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
