// The counting operator new/delete of the runtime test executable (allocation_counter.hpp).
// Counters are thread-local with constant initialization: reading them needs no allocation and no
// lock, and a thread gtest or the library might start elsewhere does not disturb a measurement.
#include "allocation_counter.hpp"

#include <cstdlib>
#include <new>

namespace semo::runtime::test_support {
namespace {

constinit thread_local std::uint64_t allocations = 0;
constinit thread_local std::uint64_t deallocations = 0;

void* allocate(std::size_t size) {
  ++allocations;
  // malloc(0) may return null; operator new must return a distinct pointer.
  return std::malloc(size == 0 ? 1 : size);
}

void* allocateAligned(std::size_t size, std::align_val_t alignment) {
  ++allocations;
  auto align = static_cast<std::size_t>(alignment);
  if (align < sizeof(void*)) align = sizeof(void*);  // posix_memalign's minimum
  void* p = nullptr;
  return posix_memalign(&p, align, size == 0 ? 1 : size) == 0 ? p : nullptr;
}

void release(void* p) noexcept {
  if (p == nullptr) return;
  ++deallocations;
  std::free(p);
}

void* orThrow(void* p) {
  if (p == nullptr) throw std::bad_alloc();
  return p;
}

}  // namespace

std::uint64_t allocationsSoFar() { return allocations; }
std::uint64_t deallocationsSoFar() { return deallocations; }

}  // namespace semo::runtime::test_support

namespace ts = semo::runtime::test_support;

// Every replaceable allocation form: libstdc++'s defaults of the array, nothrow and aligned forms
// do not all route through operator new(size_t), so each one is replaced.
void* operator new(std::size_t size) { return ts::orThrow(ts::allocate(size)); }
void* operator new[](std::size_t size) { return ts::orThrow(ts::allocate(size)); }
void* operator new(std::size_t size, const std::nothrow_t&) noexcept { return ts::allocate(size); }
void* operator new[](std::size_t size, const std::nothrow_t&) noexcept { return ts::allocate(size); }
void* operator new(std::size_t size, std::align_val_t a) { return ts::orThrow(ts::allocateAligned(size, a)); }
void* operator new[](std::size_t size, std::align_val_t a) { return ts::orThrow(ts::allocateAligned(size, a)); }
void* operator new(std::size_t size, std::align_val_t a, const std::nothrow_t&) noexcept {
  return ts::allocateAligned(size, a);
}
void* operator new[](std::size_t size, std::align_val_t a, const std::nothrow_t&) noexcept {
  return ts::allocateAligned(size, a);
}

void operator delete(void* p) noexcept { ts::release(p); }
void operator delete[](void* p) noexcept { ts::release(p); }
void operator delete(void* p, std::size_t) noexcept { ts::release(p); }
void operator delete[](void* p, std::size_t) noexcept { ts::release(p); }
void operator delete(void* p, const std::nothrow_t&) noexcept { ts::release(p); }
void operator delete[](void* p, const std::nothrow_t&) noexcept { ts::release(p); }
void operator delete(void* p, std::align_val_t) noexcept { ts::release(p); }
void operator delete[](void* p, std::align_val_t) noexcept { ts::release(p); }
void operator delete(void* p, std::size_t, std::align_val_t) noexcept { ts::release(p); }
void operator delete[](void* p, std::size_t, std::align_val_t) noexcept { ts::release(p); }
void operator delete(void* p, std::align_val_t, const std::nothrow_t&) noexcept { ts::release(p); }
void operator delete[](void* p, std::align_val_t, const std::nothrow_t&) noexcept { ts::release(p); }
