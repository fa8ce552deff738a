#include "semo/runtime/knowledge.hpp"

#include <algorithm>

namespace semo::runtime {

KnowledgeStore::KnowledgeStore(std::vector<std::string> facts, Merge merge)
    : facts_(std::move(facts)), merge_(merge), held_(facts_.size(), 0), stamps_(facts_.size()) {}

bool KnowledgeStore::discover(std::uint32_t fact, std::uint32_t robot, std::uint64_t& lamportClock) {
  if (fact >= held_.size()) return false;
  const FactStamp mine{++lamportClock, robot};
  const bool isNew = held_[fact] == 0;
  if (isNew) {
    held_[fact] = 1;
    stamps_[fact] = mine;
    ++count_;
  } else if (merge_ == Merge::Newest) {
    stamps_[fact] = mine;  // a fresh sighting is the newest copy
  }
  return isNew;
}

int KnowledgeStore::merge(const KnowledgeStore& from, std::uint64_t& lamportClock) {
  int added = 0;
  const std::size_t n = std::min(held_.size(), from.held_.size());
  std::uint64_t seen = lamportClock;
  for (std::size_t f = 0; f < n; ++f) {
    if (from.held_[f] == 0) continue;
    const FactStamp theirs = from.stamps_[f];
    seen = std::max(seen, theirs.lamport);
    if (held_[f] == 0) {
      held_[f] = 1;
      stamps_[f] = theirs;
      ++count_;
      ++added;
    } else if (merge_ == Merge::Newest ? stamps_[f] < theirs : theirs < stamps_[f]) {
      stamps_[f] = theirs;
    }
  }
  lamportClock = seen;  // Lamport's receive rule (the next event of this robot counts from here)
  return added;
}

bool KnowledgeStore::mergeFact(std::uint32_t fact, FactStamp stamp, std::uint64_t& lamportClock) {
  if (fact >= held_.size()) return false;
  lamportClock = std::max(lamportClock, stamp.lamport);
  if (held_[fact] == 0) {
    held_[fact] = 1;
    stamps_[fact] = stamp;
    ++count_;
    return true;
  }
  if (merge_ == Merge::Newest ? stamps_[fact] < stamp : stamp < stamps_[fact]) stamps_[fact] = stamp;
  return false;
}

void KnowledgeStore::clear() {
  std::fill(held_.begin(), held_.end(), std::uint8_t{0});
  std::fill(stamps_.begin(), stamps_.end(), FactStamp{});
  count_ = 0;
}

}  // namespace semo::runtime
