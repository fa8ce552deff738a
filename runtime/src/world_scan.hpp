#pragma once
// The text-level half of the world reader (world_scan.cpp): positions of byte offsets, and the scan
// that runs before the JSON parser for what the parser cannot report with a position.
#include <cstddef>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "semo/runtime/world.hpp"

namespace semo::runtime::detail {

inline constexpr std::size_t kMaxWorldDepth = 64;

// Members whose key starts with '_' are comments.
inline bool isComment(const std::string& key) { return !key.empty() && key.front() == '_'; }

// Where each line of the text starts (for errorAt: the line of an offset in log time).
std::vector<std::size_t> lineStarts(std::string_view text);
// An error at a byte offset of the text, with its line, column and the line's text (a window of it
// around the column when the line is long).
WorldError errorAt(std::string_view text, const std::vector<std::size_t>& lineStarts, const std::string& path, std::size_t offset,
                   std::string message);
// The same, the lines found anew: for one error.
WorldError errorAt(std::string_view text, const std::string& path, std::size_t offset, std::string message);

struct PreScan {
  std::vector<std::pair<std::size_t, std::string>> problems;  // offset, message
  bool tooDeep = false;  // then `problems` holds that one problem, and the text must not be parsed
};
PreScan preScan(std::string_view text);

}  // namespace semo::runtime::detail
