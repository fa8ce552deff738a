#pragma once
// Safety on the IR with Z3 (checker/src/smt_encoding.hpp has the encoding): bounded model checking
// finds every violation reachable within K steps, with a shortest counterexample in the explicit
// engine's trace format; k-induction then tries to prove the invariants that were not violated for
// every depth. A property is "proven" only by a successful induction; otherwise it holds on every
// path of up to K steps and is reported unknown, bounded (never "proven").
#include <cstdint>
#include <string>
#include <vector>

#include "semo/checker/explicit_search.hpp"

namespace semo::checker {

struct SmtOptions {
  std::uint32_t maxDepth = 20;  // K: BMC explores every path of up to K steps; induction tries k <= K + 1
  bool induction = true;
  unsigned timeoutMs = 0;       // per solver call; 0: none
};

struct SmtResult {
  SearchResult search;                        // properties as the explicit engine reports them
  std::vector<std::uint32_t> inductionDepth;  // per property: k of its proof, or 0
  std::uint32_t bmcDepth = 0;                 // every path of up to this many steps was covered
  std::string note;                           // why an induction stopped, if it did
};

SmtResult checkSafetySmt(const ir::Model& model, const SmtOptions& options);

}  // namespace semo::checker
