#include "allocation_counter.hpp"

#include <atomic>
#include <cerrno>
#include <cstddef>
#include <cstdlib>

// Two hooks, chosen at build time (test code, not task code):
// - sanitizer builds: the allocator is the sanitizer's (ASan, TSan), which offers malloc hooks;
// - plain builds: malloc & co. are interposed here and forwarded to glibc's __libc_* entry
//   points. libstdc++'s operator new calls malloc, so `new` is counted as well.

namespace {
// initial-exec TLS: touching it never allocates (a must inside malloc).
__attribute__((tls_model("initial-exec"))) thread_local bool t_armed = false;
__attribute__((tls_model("initial-exec"))) thread_local std::uint64_t t_count = 0;
// Every thread: armed by how many all-thread counters are alive (lock-free, so safe in malloc).
std::atomic<int> g_armed{0};
std::atomic<std::uint64_t> g_count{0};

// Set COLAG_ALLOC_ABORT=1 to abort at the first counted allocation (then read the backtrace
// in a debugger: that is the allocation to remove).
bool g_abort_on_allocation = false;

inline void note_allocation() {
  const bool all = g_armed.load(std::memory_order_relaxed) > 0;
  if (all) g_count.fetch_add(1, std::memory_order_relaxed);
  if (t_armed) ++t_count;
  if ((all || t_armed) && g_abort_on_allocation) __builtin_trap();
}
}  // namespace

#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)

extern "C" int __sanitizer_install_malloc_and_free_hooks(void (*malloc_hook)(const volatile void*,
                                                                             std::size_t),
                                                         void (*free_hook)(const volatile void*));

namespace {
void on_malloc(const volatile void*, std::size_t) {
  note_allocation();
}
void on_free(const volatile void*) {}
const int g_hooks_installed = __sanitizer_install_malloc_and_free_hooks(on_malloc, on_free);
}  // namespace

#else

extern "C" {
// glibc's own allocator entry points, which the replacements below forward to.
// NOLINTBEGIN(bugprone-reserved-identifier,readability-identifier-naming)
void* __libc_malloc(std::size_t size);
void* __libc_calloc(std::size_t nmemb, std::size_t size);
void* __libc_realloc(void* ptr, std::size_t size);
void* __libc_memalign(std::size_t alignment, std::size_t size);
// NOLINTEND(bugprone-reserved-identifier,readability-identifier-naming)

void* malloc(std::size_t size) {
  note_allocation();
  return __libc_malloc(size);
}
void* calloc(std::size_t nmemb, std::size_t size) {
  note_allocation();
  return __libc_calloc(nmemb, size);
}
void* realloc(void* ptr, std::size_t size) {
  note_allocation();
  return __libc_realloc(ptr, size);
}
void* aligned_alloc(std::size_t alignment, std::size_t size) {
  note_allocation();
  return __libc_memalign(alignment, size);
}
void* memalign(std::size_t alignment, std::size_t size) {
  note_allocation();
  return __libc_memalign(alignment, size);
}
int posix_memalign(void** memptr, std::size_t alignment, std::size_t size) {
  note_allocation();
  if (alignment % sizeof(void*) != 0 || (alignment & (alignment - 1)) != 0) return EINVAL;
  void* p = __libc_memalign(alignment, size);
  if (p == nullptr) return ENOMEM;
  *memptr = p;
  return 0;
}
}

#endif

namespace colag::test {

AllocationCounter::AllocationCounter(Threads threads) : threads_(threads) {
  static const bool abort_requested = [] {
    const char* v = std::getenv("COLAG_ALLOC_ABORT");
    return v != nullptr && v[0] == '1';
  }();
  g_abort_on_allocation = abort_requested;
  if (threads_ == Threads::kAll) {
    start_ = g_count.load();
    g_armed.fetch_add(1);
  } else {
    t_count = 0;
    t_armed = true;
  }
}
AllocationCounter::~AllocationCounter() {
  if (threads_ == Threads::kAll) {
    g_armed.fetch_sub(1);
  } else {
    t_armed = false;
  }
}
std::uint64_t AllocationCounter::count() const {
  return threads_ == Threads::kAll ? g_count.load() - start_ : t_count;
}

}  // namespace colag::test
