// keep_freed_memory: after it, a large block comes from the heap (no mmap of its
// own) and is reused when freed and allocated again, and threads share one heap.
// What the allocator did before the call (arenas of threads other tests started,
// freed chunks) changes what these probes see, so each probe runs in a fresh
// process: the case re-runs this executable on itself alone (SSID_ALLOC_PROBE=1)
// and checks its exit status. Order-independent, and the cases that run after it
// keep the allocator they had.
#include "estimator/linalg/allocation_policy.hpp"

#include <catch2/catch.hpp>

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <thread>
#include <vector>

// Under AddressSanitizer malloc is the sanitizer's allocator and its mallopt accepts
// no option: keep_freed_memory() must then say it did nothing, as with a C library
// other than glibc (GCC defines __SANITIZE_ADDRESS__, clang has the feature test).
#if defined(__GLIBC__) && !defined(__SANITIZE_ADDRESS__)
#define SSID_GLIBC_MALLOC 1
#if defined(__has_feature)
#if __has_feature(address_sanitizer)
#undef SSID_GLIBC_MALLOC
#endif
#endif
#endif

#if defined(SSID_GLIBC_MALLOC)
#include <malloc.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

extern char** environ;
#endif

namespace {

#if defined(SSID_GLIBC_MALLOC)
bool in_probe() { return std::getenv("SSID_ALLOC_PROBE") != nullptr; }

/// Runs this test executable on the case `name` alone, in a fresh process with
/// SSID_ALLOC_PROBE=1; returns its exit status (-1 when it could not run).
int run_probe(const std::string& name) {
  std::vector<std::string> env_text{"SSID_ALLOC_PROBE=1"};
  for (char** e = environ; *e != nullptr; ++e) env_text.emplace_back(*e);
  std::vector<char*> env;
  for (auto& e : env_text) env.push_back(e.data());
  env.push_back(nullptr);
  std::string exe = "/proc/self/exe", filter = name;
  std::vector<char*> argv{exe.data(), filter.data(), nullptr};
  pid_t pid = 0;
  if (posix_spawn(&pid, exe.c_str(), nullptr, nullptr, argv.data(), env.data()) != 0) return -1;
  int status = 0;
  if (waitpid(pid, &status, 0) != pid || !WIFEXITED(status)) return -1;
  return WEXITSTATUS(status);
}
#endif

}  // namespace

TEST_CASE("keep_freed_memory serves large blocks from the heap", "[alloc]") {
#if defined(SSID_GLIBC_MALLOC)
  if (!in_probe()) {
    CHECK(run_probe("keep_freed_memory serves large blocks from the heap") == 0);
    return;
  }
  REQUIRE(ssid::estimator::keep_freed_memory());
  const size_t mapped_before = mallinfo2().hblkhd;  // bytes in mmap'ed blocks
  const size_t big = 96u << 20;                     // far above glibc's 32 MB mmap threshold
  char* p = static_cast<char*>(std::malloc(big));
  REQUIRE(p != nullptr);
  std::memset(p, 1, big);
  CHECK(mallinfo2().hblkhd == mapped_before);  // not an mmap of its own: from the heap
  const size_t heap = mallinfo2().arena;
  CHECK(heap >= big);
  std::free(p);
  CHECK(mallinfo2().arena == heap);  // kept in the heap, not trimmed
  char* q = static_cast<char*>(std::malloc(big));
  REQUIRE(q != nullptr);
  CHECK(mallinfo2().arena == heap);  // reused: the heap did not grow
  std::free(q);
#else
  CHECK_FALSE(ssid::estimator::keep_freed_memory());
#endif
}

TEST_CASE("keep_freed_memory shares one heap among threads", "[alloc]") {
#if defined(SSID_GLIBC_MALLOC)
  if (!in_probe()) {
    CHECK(run_probe("keep_freed_memory shares one heap among threads") == 0);
    return;
  }
  REQUIRE(ssid::estimator::keep_freed_memory());
  // Another thread's allocations come from the one heap (glibc's malloc_info lists
  // each arena as a <heap>): with a heap per thread, memory a worker freed would
  // not be reused by the main thread's next allocation.
  std::thread worker([] {
    char* p = static_cast<char*>(std::malloc(16u << 20));
    if (p != nullptr) std::memset(p, 1, 16u << 20);
    std::free(p);
  });
  worker.join();
  char* buf = nullptr;
  size_t len = 0;
  FILE* f = open_memstream(&buf, &len);
  REQUIRE(f != nullptr);
  REQUIRE(malloc_info(0, f) == 0);
  std::fclose(f);
  const std::string xml(buf, len);
  std::free(buf);
  size_t heaps = 0;
  for (size_t at = xml.find("<heap nr="); at != std::string::npos; at = xml.find("<heap nr=", at + 1)) ++heaps;
  CHECK(heaps == 1);
#else
  CHECK_FALSE(ssid::estimator::keep_freed_memory());
#endif
}

TEST_CASE("restart_with_huge_page_heap leaves the process alone when told to", "[alloc]") {
  // Were it to re-execute here, the test binary would restart with an option Catch
  // refuses, and the run would fail.
  char name[] = "test_estimator", bad[] = "--no-such-option-from-a-re-execution";
  char* args[] = {name, bad, nullptr};
  const char* had = std::getenv("GLIBC_TUNABLES");
  const std::string saved = had ? had : "";
  const char* had_opt = std::getenv("SSID_HUGE_PAGE_HEAP");
  const std::string saved_opt = had_opt ? had_opt : "";
  // Opted out.
  unsetenv("GLIBC_TUNABLES");
  setenv("SSID_HUGE_PAGE_HEAP", "0", 1);
  CHECK_FALSE(ssid::estimator::restart_with_huge_page_heap(args));
  CHECK(std::getenv("GLIBC_TUNABLES") == nullptr);
  unsetenv("SSID_HUGE_PAGE_HEAP");
  // The caller's own tunables win (and are what the re-executed program sees).
  setenv("GLIBC_TUNABLES", "glibc.malloc.check=0", 1);
  CHECK_FALSE(ssid::estimator::restart_with_huge_page_heap(args));
  CHECK(std::string(std::getenv("GLIBC_TUNABLES")) == "glibc.malloc.check=0");
  if (had) setenv("GLIBC_TUNABLES", saved.c_str(), 1);
  else unsetenv("GLIBC_TUNABLES");
  if (had_opt) setenv("SSID_HUGE_PAGE_HEAP", saved_opt.c_str(), 1);
}
