#include "estimator/allocation_policy.hpp"

#include <climits>
#if defined(__GLIBC__)
#include <malloc.h>
#endif

namespace ssid::estimator {

bool keep_freed_memory() {
#if defined(__GLIBC__)
  return mallopt(M_MMAP_MAX, 0) == 1 && mallopt(M_TRIM_THRESHOLD, INT_MAX) == 1;
#else
  return false;
#endif
}

}  // namespace ssid::estimator
