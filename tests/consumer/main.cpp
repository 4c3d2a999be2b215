// Two unit circles 10 apart closing at speed 2 first touch at t = (10 - 2) / 2 = 4.
#include <ellipsect/ellipsect.hpp>

#include <cstdio>

int main() {
  using namespace ellipsect;
  const auto a = make_ball<double, 2>({0, 0}, 1);
  const auto b = make_ball<double, 2>({10, 0}, 1);
  const auto c = first_contact<double, 2>(a, {1, 0}, b, {-1, 0}, 100);
  std::printf("%s %.15g\n", to_string(c.status).data(), c.time);
  return c.status == ContactStatus::hit ? 0 : 1;
}
