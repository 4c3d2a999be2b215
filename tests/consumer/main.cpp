// Two unit circles 10 apart closing at speed 2 first touch at t = (10 - 2) / 2 = 4; the
// batch function (which links Highway) gives the same answer.
#include <ellipsect/ellipsect.hpp>

#include <cstdio>

int main() {
  using namespace ellipsect;
  const auto a = make_ball<double, 2>({0, 0}, 1);
  const auto b = make_ball<double, 2>({10, 0}, 1);
  const auto c = first_contact<double, 2>(a, {1, 0}, b, {-1, 0}, 100);
  Pairs<double, 2> pairs;
  pairs.push_back(a, {1, 0}, b, {-1, 0}, 100);
  Contact<double, 2> batch[1];
  first_contact(pairs, std::span<Contact<double, 2>>(batch));
  std::printf("%s %.15g (batch %.15g, %s)\n", to_string(c.status).data(), c.time, batch[0].time, simd_target().c_str());
  return c.status == ContactStatus::hit && batch[0].time == c.time ? 0 : 1;
}
