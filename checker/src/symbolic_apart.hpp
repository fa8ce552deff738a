#pragma once
// A symbolic search in a child process of its own (symbolic_apart.cpp). BuDDy keeps one package
// per process, so in one process the symbolic searches of two properties take turns; in child
// processes they run side by side, each with its own node table.
#include <cstddef>
#include <cstdint>
#include <functional>
#include <optional>

#include "symbolic_liveness.hpp"

namespace semo::checker::detail {

// Runs `search` in a forked child and returns what it found; nullopt when no child could be made.
// The child reports progress and its outcome through a pipe; `limits.onProgress` is called here,
// on the caller's thread. A child that ends without an outcome (killed, out of memory) gives an
// outcome of GaveUp saying so. The child is a copy of this process with only the calling thread:
// `search` must use nothing another thread may have held at the fork (locks, BuDDy's package,
// which it must start afresh).
using SymbolicSearch = std::function<SymbolicOutcome(const SymbolicLimits&)>;
std::optional<SymbolicOutcome> searchInChildProcess(const SymbolicLimits& limits, const SymbolicSearch& search);

// How many searches this process has run in child processes (the tests look).
std::uint64_t searchesInChildProcesses();

}  // namespace semo::checker::detail
