#pragma once
// One robot's copy of one knowledge item of a group service (specs/runtime.md, "Knowledge"): which
// of the item's facts it holds, each with the Lamport stamp of the copy it keeps. Facts are the
// strategy's values, referred to by index; storage is fixed when the store is made, so discovering
// and merging never allocate.
//
// Merging follows the strategy's `merge`: "newest" keeps, per fact, the copy with the newest stamp
// (last writer wins); "union" keeps the first copy ever made (first writer). Either way a merge is
// commutative, associative and idempotent on the set of facts held, and the robot's Lamport clock
// moves past every stamp it has seen.
#include <cstdint>
#include <string>
#include <vector>

namespace semo::runtime {

struct FactStamp {
  std::uint64_t lamport = 0;
  std::uint32_t robot = 0;
  friend bool operator<(const FactStamp& a, const FactStamp& b) {
    return a.lamport != b.lamport ? a.lamport < b.lamport : a.robot < b.robot;
  }
  friend bool operator==(const FactStamp& a, const FactStamp& b) = default;
};

class KnowledgeStore {
 public:
  enum class Merge { Newest, Union };
  KnowledgeStore(std::vector<std::string> facts, Merge merge);

  // The robot finds `fact` now: a new copy stamped clock + 1 (an older copy is replaced under
  // "newest", kept under "union"). Returns whether the fact was new to this store.
  bool discover(std::uint32_t fact, std::uint32_t robot, std::uint64_t& lamportClock);
  // Takes what `from` holds; returns how many facts were new.
  int merge(const KnowledgeStore& from, std::uint64_t& lamportClock);
  // Takes one fact with its stamp, as a peer's packet carries it (the same rule as merge, fact by
  // fact); returns whether it was new to this store.
  bool mergeFact(std::uint32_t fact, FactStamp stamp, std::uint64_t& lamportClock);

  [[nodiscard]] int count() const { return count_; }
  [[nodiscard]] bool holds(std::uint32_t fact) const { return fact < held_.size() && held_[fact] != 0; }
  [[nodiscard]] FactStamp stamp(std::uint32_t fact) const { return stamps_[fact]; }
  [[nodiscard]] bool sameFactsAs(const KnowledgeStore& other) const { return held_ == other.held_; }
  [[nodiscard]] const std::vector<std::string>& facts() const { return facts_; }
  [[nodiscard]] Merge policy() const { return merge_; }
  void clear();

 private:
  std::vector<std::string> facts_;
  Merge merge_;
  std::vector<std::uint8_t> held_;
  std::vector<FactStamp> stamps_;
  int count_ = 0;
};

}  // namespace semo::runtime
