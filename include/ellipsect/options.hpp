// Tolerances and iteration caps: the one place they are defined.
//
// Tolerance model. Every query reduces the pair to the frame in which one body (the
// "sphere body", chosen by a rule that does not depend on argument order) is the unit
// ball. Gaps measured there are dimensionless: a gap g means the sphere body would have to
// be scaled by (1 + g) about its center to just touch the other body. Scaling a whole
// scene, or moving it rigidly, leaves these numbers unchanged, so the answers do not
// depend on units. `tolerance` is that relative gap below which two bodies count as
// touching (and containment within which counts as tangent from inside).
//
// Range. The model holds at every scale: a pair whose largest radius lies outside 2^+-64 is
// rescaled by a power of two (exact) before the query, so scaling a scene by 2^k changes no
// answer beyond multiplying lengths by exactly 2^k. Within one pair, radii within a ratio
// of 2^160 and coordinates within 2^340 times the largest radius are computed in double;
// pairs beyond that in long double (docs/method.md, section 7).
#pragma once

namespace ellipsect {

struct Options {
  // Relative tangency band (see above). Pairs whose gap lies within it are reported as
  // touching; outside it, answers are exact up to the accuracy stated per query.
  double tolerance = 1e-12;
  // Cap on the outer (contact-time) iteration. Reaching it is reported as a status
  // (ContactStatus::did_not_converge), never returned as an answer.
  int max_iterations = 64;
  // Cap on the advancement steps of first_contact under rigid motion (contact.hpp), where
  // each step costs one signed distance. Reaching it is reported as did_not_converge, with
  // a certified lower bound on the contact time.
  int max_motion_steps = 10000;
};

}  // namespace ellipsect
