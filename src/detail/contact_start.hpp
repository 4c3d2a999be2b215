// What every first_contact starts from: the answer before anything is known (status
// invalid_input, NaN time, point and normal: contact.hpp) and the check of its motion input.
#pragma once

#include <ellipsect/contact.hpp>

#include <limits>

namespace ellipsect::detail {

template <class T, int N>
Vec<T, N> nan_vec() noexcept {
  return Vec<T, N>::Constant(std::numeric_limits<T>::quiet_NaN());
}

template <class T, int N>
Contact<T, N> unanswered_contact() noexcept {
  Contact<T, N> c;
  c.time = std::numeric_limits<T>::quiet_NaN();
  c.point = c.normal = nan_vec<T, N>();
  return c;
}

// Finite velocities and a t_max that is not NaN or negative.
template <class T, int N>
bool valid_motion(const VecArg<T, N>& velocity_a, const VecArg<T, N>& velocity_b, T t_max) noexcept {
  return velocity_a.allFinite() && velocity_b.allFinite() && t_max >= T(0);
}

}  // namespace ellipsect::detail
