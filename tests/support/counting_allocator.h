// A counting global allocator for the no-allocation tests: include this header in exactly one
// source file of a test program (it replaces operator new and delete for the whole program).
#pragma once

#include <atomic>
#include <cstdlib>
#include <new>

namespace wirerig::testing {
inline std::atomic<long> g_allocations{0};  // every operator new since the program started
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
