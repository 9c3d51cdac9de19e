#pragma once
// Counts heap allocations (malloc, calloc, realloc, aligned allocations and therefore every
// operator new) while a counter is alive: by every thread of the process (the default: work a
// task hands to a worker pool counts too), or by the calling thread only (where threads of a
// library that allocate by design run beside it, such as Cyclone DDS's). Used to prove that a
// task's step() allocates nothing.
#include <cstdint>

namespace colag::test {

class AllocationCounter {
 public:
  enum class Threads { kAll, kThisOne };
  explicit AllocationCounter(Threads threads = Threads::kAll);  // starts counting from zero
  ~AllocationCounter();                                         // stops counting
  AllocationCounter(const AllocationCounter&) = delete;
  AllocationCounter& operator=(const AllocationCounter&) = delete;

  std::uint64_t count() const;

 private:
  Threads threads_;
  std::uint64_t start_ = 0;
};

}  // namespace colag::test
