#pragma once
// Inserting the successors of a block of states into the store on every thread, with the result a
// single thread would get: the new states numbered in the order of their first occurrence (by
// source state, then successor number), each with the parent and rule of that occurrence.
//
// 1. Claim (in parallel): each thread owns the store partitions p with p % threads == its number
//    and goes through all the block's successors in order, looking up those that fall into its
//    partitions. A successor not found claims a slot under a temporary number; a later equal one
//    finds the claim. Each partition sees its successors in the same order whatever the number of
//    threads, so which successor is first, and thus new, does not depend on it either. The new
//    ones are marked in a bitmap of the block's successors, one per thread.
// 2. Number (in parallel): each thread takes the next expansion run not taken; how many new
//    states the runs before it hold is known from step 1, so it can number the run's new states
//    (the bits set in the union of the bitmaps, 64 successors at a time), store them and give their
//    slots their final numbers.
#include <cstdint>
#include <functional>
#include <vector>

#include "state_store.hpp"
#include "successors.hpp"
#include "worker_pool.hpp"

namespace semo::checker::detail {

class BlockInserter {
 public:
  // Called on the threads once the new states are stored, for slices [first, end) of them that
  // cover them all: checks that need nothing but the state are done there, in parallel.
  using NewStates = std::function<void(unsigned thread, std::size_t first, std::size_t end)>;

  // Inserts the successors of `runs` (consecutive, non-empty) into the store.
  void insert(StateStore& store, const std::vector<Expansion>& runs, WorkerPool& pool, const NewStates& onNewStates);
  // The store's size once the successors of source state i (of the last block) are inserted.
  [[nodiscard]] std::size_t sizeAfter(std::size_t i) const { return sizeAfter_[i - firstSource_]; }
  // Forgets the states numbered n and above, all from the last block: a search that stops within
  // it keeps only what a state-by-state search would have stored by then.
  void truncate(StateStore& store, std::size_t n);

 private:
  struct Candidate {  // a successor in the partitions of the thread
    std::uint64_t hash;
    const std::uint64_t* data;
    std::uint32_t number;  // in the block, counting from 0
  };
  struct Claimed {  // a new state: its slot, and its number in the store once known
    std::uint32_t partition, slot, index;
  };
  // The thread's own; one cache line apart, since each thread updates its own as it goes.
  struct alignas(64) Owner {
    std::vector<Candidate> candidates;
    std::vector<std::uint64_t> isNew;     // bit k: successor k of the block was claimed here
    std::vector<Claimed> claimed;         // in the order of the successors
    std::vector<std::size_t> claimedBefore;  // per run: claims in the runs before it; one more at the end
    std::vector<std::size_t> cursor;  // while numbering a run: per owner, its next claim
  };
  void claim(unsigned thread, StateStore& store, const std::vector<Expansion>& runs);
  void number(unsigned thread, std::size_t run, StateStore& store, const Expansion& e, const NewStates& onNewStates);

  std::vector<Owner> owners_;
  std::vector<unsigned> ownerOf_;  // per store partition: the thread that owns it
  std::vector<std::size_t> firstOfRun_;  // per run: its first successor in the block; one more at the end
  std::vector<std::size_t> newBeforeRun_;  // per run: the new states of the runs before it; one more
  std::vector<std::size_t> sizeAfter_;
  std::size_t firstSource_ = 0;
};

}  // namespace semo::checker::detail
