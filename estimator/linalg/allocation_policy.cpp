#include "estimator/linalg/allocation_policy.hpp"

#include <climits>
#include <cstdlib>
#include <cstring>
#if defined(__GLIBC__)
#include <malloc.h>
#endif
#if defined(__linux__) && defined(__GLIBC__)
#include <limits.h>
#include <sys/auxv.h>
#include <unistd.h>
#endif

namespace ssid::estimator {

bool keep_freed_memory() {
#if defined(__GLIBC__)
  return mallopt(M_MMAP_MAX, 0) == 1 && mallopt(M_TRIM_THRESHOLD, INT_MAX) == 1 && mallopt(M_ARENA_MAX, 1) == 1;
#else
  return false;
#endif
}

bool restart_with_huge_page_heap(char** argv) {
#if defined(__linux__) && defined(__GLIBC__)
  if (argv == nullptr || argv[0] == nullptr || std::getenv("GLIBC_TUNABLES") != nullptr) return false;
  const char* opt = std::getenv("SSID_HUGE_PAGE_HEAP");
  if (opt != nullptr && std::strcmp(opt, "0") == 0) return false;
  // Not when started through the dynamic loader by hand (no interpreter then:
  // /proc/self/exe is the loader, which would take argv[1] for the program), nor
  // for a secure-execution program (glibc drops GLIBC_TUNABLES there: the restart
  // would never see it set, and restart again).
  if (getauxval(AT_BASE) == 0 || getauxval(AT_SECURE) != 0) return false;
  // The resolved path, not /proc/self/exe itself: a process is named after the
  // file it was started from ("exe" otherwise, for ps, top and pgrep).
  char path[PATH_MAX];
  const ssize_t len = readlink("/proc/self/exe", path, sizeof(path) - 1);
  if (len <= 0) return false;
  path[len] = '\0';
  if (setenv("GLIBC_TUNABLES", "glibc.malloc.hugetlb=1", 1) != 0) return false;
  execv(path, argv);  // returns only if it failed: carry on as we are
  unsetenv("GLIBC_TUNABLES");
#else
  (void)argv;
#endif
  return false;
}

}  // namespace ssid::estimator
