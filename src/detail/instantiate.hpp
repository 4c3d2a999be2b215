// The scalar types and dimensions every public query is compiled for.
#pragma once

// Expands INSTANTIATE(T, N) for float and double in 2 and 3 dimensions.
#define ELLIPSECT_FOR_EACH_TYPE_AND_DIM(INSTANTIATE) \
  INSTANTIATE(float, 2)                              \
  INSTANTIATE(float, 3)                              \
  INSTANTIATE(double, 2)                             \
  INSTANTIATE(double, 3)
