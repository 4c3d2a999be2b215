// Two unit circles 10 apart closing at speed 2 first touch at t = (10 - 2) / 2 = 4; the
// batch function (which links Highway) gives the same answer; and so does the packing
// module (ellipsect::packing), whose hard bodies collide then.
#include <ellipsect/ellipsect.hpp>
#include <ellipsect/packing.hpp>

#include <cstdio>
#include <vector>

int main() {
  using namespace ellipsect;
  const auto a = make_ball<double, 2>({0, 0}, 1);
  const auto b = make_ball<double, 2>({10, 0}, 1);
  const auto c = first_contact<double, 2>(a, {1, 0}, b, {-1, 0}, 100);
  Pairs<double, 2> pairs;
  pairs.push_back(a, {1, 0}, b, {-1, 0}, 100);
  Contact<double, 2> batch[1];
  first_contact(pairs, std::span<Contact<double, 2>>(batch));
  const std::vector<Ellipsoid<double, 2>> bodies = {a.translated({5, 5}), b.translated({5, 5})};
  std::vector<RigidMotion<double, 2>> motions(2);
  motions[0].velocity = {1, 0};
  motions[1].velocity = {-1, 0};
  HardBodies<2> system(bodies, motions, PeriodicBox<2>{{40.0, 40.0}});
  const HardStep<2> step = system.step();
  std::printf("%s %.15g (batch %.15g, %s; hard bodies %s %.15g)\n", to_string(c.status).data(), c.time,
              batch[0].time, simd_target().c_str(), to_string(step.status).data(), step.event.time);
  return c.status == ContactStatus::hit && batch[0].time == c.time && step.status == HardStatus::collided &&
                 step.event.time == c.time
             ? 0
             : 1;
}
