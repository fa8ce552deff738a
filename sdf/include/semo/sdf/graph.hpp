#pragma once
// A synchronous dataflow graph: actors that fire atomically, consuming and producing fixed numbers
// of tokens on channels (FIFO buffers). The same structure serves semo's per-robot task graphs and
// graphs read from SDF3's XML format (sdf3_xml.hpp).
#include <cstdint>
#include <string>
#include <vector>

#include "semo/frontend/source.hpp"

namespace semo::sdf {

using ActorId = std::uint32_t;

struct Actor {
  std::string name;
  std::int64_t executionTime = 0;  // in the graph's time unit
  SourceRange at;                  // where it was read from, if it was
};

struct Channel {
  std::string name;
  ActorId source = 0, target = 0;
  std::int64_t production = 1;     // tokens the source produces per firing
  std::int64_t consumption = 1;    // tokens the target consumes per firing
  std::int64_t initialTokens = 0;
  SourceRange at;
  [[nodiscard]] bool selfLoop() const { return source == target; }
};

struct Graph {
  std::string name;
  std::vector<Actor> actors;
  std::vector<Channel> channels;
};

}  // namespace semo::sdf
