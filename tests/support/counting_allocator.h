// A counting global allocator for the no-allocation tests: include this header in exactly one
// source file of a test program (it replaces operator new and delete for the whole program).
#pragma once

#include <atomic>
#include <cstdlib>
#include <new>
#include <vector>

namespace wirerig::testing {
inline std::atomic<long> g_allocations{0};  // every operator new since the program started

// The allocations a std::vector made on the heap and freed again counts (2: the vector, its
// buffer): each test program's proof that the counting allocator is in place. The pointer goes
// through a volatile object so that the optimiser cannot elide the new/delete pair.
inline long CountedAllocationsOfAHeapVector() {
  static std::vector<int>* volatile sink = nullptr;
  const long before = g_allocations;
  sink = new std::vector<int>(100);
  delete sink;
  return g_allocations - before;
}
}  // namespace wirerig::testing

void* operator new(std::size_t size) {
  ++wirerig::testing::g_allocations;
  if (void* p = std::malloc(size == 0 ? 1 : size)) return p;
  throw std::bad_alloc();
}
void* operator new[](std::size_t size) { return operator new(size); }
void operator delete(void* p) noexcept { std::free(p); }
void operator delete[](void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t) noexcept { std::free(p); }
