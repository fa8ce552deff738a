#pragma once
// Counts heap allocations in the runtime test executable: allocation_counter.cpp replaces the
// global operator new and delete (every form) with ones that count, then call malloc and free. The
// runtime's steady-state paths (a robot's step, a message's loss, a gossip merge, a schedule
// iteration) must not allocate: a robot program runs for hours, and the simulator runs millions of
// steps; tests measure that with an AllocationMeter around the calls.
//
// malloc and free stay the C library's (or AddressSanitizer's, whose interceptors then still check
// every block); only operator new/delete are replaced, which the standard allows.
#include <cstdint>

namespace semo::runtime::test_support {

// Allocations (operator new of any form) made by this thread since it started.
std::uint64_t allocationsSoFar();
// Deallocations (operator delete of any form, of a non-null pointer) by this thread.
std::uint64_t deallocationsSoFar();

// Allocations made by this thread since the meter was constructed.
class AllocationMeter {
 public:
  AllocationMeter() : start_(allocationsSoFar()) {}
  [[nodiscard]] std::uint64_t allocations() const { return allocationsSoFar() - start_; }

 private:
  std::uint64_t start_;
};

}  // namespace semo::runtime::test_support
