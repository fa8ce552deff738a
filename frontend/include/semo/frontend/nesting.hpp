#pragma once
// How deep a reader lets its input nest (statements, conditions, formulas, expressions), as
// compilers limit bracket depth (clang's -fbracket-depth is 256 too): past it, a positioned error,
// never a stack overflow of the recursive descent. Used by the mission parser and the IR reader.
#include <cstddef>

namespace semo {

inline constexpr std::size_t kMaxNesting = 256;

// One level deeper in `depth` for as long as it lives. At the limit it calls `tooDeep` first,
// which must not return (a reader's error that throws); the depth is then left as it was.
class NestingGuard {
 public:
  template <typename TooDeep>
  NestingGuard(std::size_t& depth, TooDeep&& tooDeep) : depth_(depth) {
    if (depth_ >= kMaxNesting) tooDeep();
    ++depth_;
  }
  ~NestingGuard() { --depth_; }
  NestingGuard(const NestingGuard&) = delete;
  NestingGuard& operator=(const NestingGuard&) = delete;

 private:
  std::size_t& depth_;
};

}  // namespace semo
