#pragma once
// Source files and positions. Every diagnostic and every AST node points into a SourceManager.
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace semo {

using FileId = std::uint32_t;
inline constexpr FileId kNoFile = 0xffffffffu;

// 1-based line and column (columns count bytes). line == 0 means "no position in this file".
struct SourceLocation {
  FileId file = kNoFile;
  std::uint32_t line = 0;
  std::uint32_t column = 0;
  [[nodiscard]] bool valid() const { return file != kNoFile; }
  [[nodiscard]] bool hasPosition() const { return file != kNoFile && line != 0; }
};

// A range on one line; length counts bytes from begin (at least 1 for a caret).
struct SourceRange {
  SourceLocation begin;
  std::uint32_t length = 1;
};

// The offset of the first byte of `text` that is not part of well-formed UTF-8 (RFC 3629: no
// overlong form, no surrogate, nothing past U+10FFFF), or std::string_view::npos.
std::size_t firstInvalidUtf8(std::string_view text);

class SourceManager {
 public:
  // Registers text read from `path`; the manager owns a copy.
  FileId add(std::string path, std::string text);
  // Reads a file from disk; returns kNoFile if it cannot be read (errorMessage says why).
  FileId load(const std::string& path, std::string& errorMessage);

  [[nodiscard]] const std::string& path(FileId id) const { return files_.at(id).path; }
  [[nodiscard]] const std::string& text(FileId id) const { return files_.at(id).text; }
  // The text of a 1-based line without its line terminator; empty if out of range.
  [[nodiscard]] std::string_view lineText(FileId id, std::uint32_t line) const;
  [[nodiscard]] std::uint32_t lineCount(FileId id) const;
  // The line and column of a byte offset of the file's text (an offset past its end: the end), in
  // log time: readers that know offsets (JSON) place each element without scanning from the start.
  [[nodiscard]] SourceLocation locationAt(FileId id, std::size_t offset) const;
  [[nodiscard]] std::size_t fileCount() const { return files_.size(); }

 private:
  struct File {
    std::string path;
    std::string text;
    std::vector<std::uint32_t> lineStarts;
  };
  std::vector<File> files_;
};

}  // namespace semo
