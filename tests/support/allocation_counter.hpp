#pragma once
// Counts heap allocations (malloc, calloc, realloc, aligned allocations and therefore every
// operator new) made by the calling thread while a counter is alive. Used to prove that a
// task's step() allocates nothing. Other threads (DDS, gtest) are not counted.
#include <cstdint>

namespace colag::test {

class AllocationCounter {
 public:
  AllocationCounter();   // starts counting from zero on this thread
  ~AllocationCounter();  // stops counting
  AllocationCounter(const AllocationCounter&) = delete;
  AllocationCounter& operator=(const AllocationCounter&) = delete;

  std::uint64_t count() const;
};

}  // namespace colag::test
