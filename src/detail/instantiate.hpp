// The scalar types and dimensions every public query is compiled for.
#pragma once

// Expand INSTANTIATE(T) for float and double, and INSTANTIATE(T, N) for float and double in 2
// and 3 dimensions. A build that answers in double alone (the demo page's, which defines
// ELLIPSECT_DOUBLE_ONLY) compiles the double ones only.
#ifdef ELLIPSECT_DOUBLE_ONLY
#define ELLIPSECT_FOR_EACH_TYPE(INSTANTIATE) INSTANTIATE(double)
#define ELLIPSECT_FOR_EACH_TYPE_AND_DIM(INSTANTIATE) \
  INSTANTIATE(double, 2)                             \
  INSTANTIATE(double, 3)
#else
#define ELLIPSECT_FOR_EACH_TYPE(INSTANTIATE) \
  INSTANTIATE(float)                         \
  INSTANTIATE(double)
#define ELLIPSECT_FOR_EACH_TYPE_AND_DIM(INSTANTIATE) \
  INSTANTIATE(float, 2)                              \
  INSTANTIATE(float, 3)                              \
  INSTANTIATE(double, 2)                             \
  INSTANTIATE(double, 3)
#endif
