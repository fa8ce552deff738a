#include "semo/frontend/source.hpp"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace semo {

FileId SourceManager::add(std::string path, std::string text) {
  File file{std::move(path), std::move(text), {0}};
  for (std::uint32_t i = 0; i < file.text.size(); ++i) {
    if (file.text[i] == '\n') file.lineStarts.push_back(i + 1);
  }
  files_.push_back(std::move(file));
  return static_cast<FileId>(files_.size() - 1);
}

FileId SourceManager::load(const std::string& path, std::string& errorMessage) {
  // A folder opens as a stream on Linux and then reads as an empty file: say what it is instead.
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) {
    errorMessage = "cannot read '" + path + "': it is a folder, not a file";
    return kNoFile;
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    errorMessage = "cannot open '" + path + "'";
    return kNoFile;
  }
  std::ostringstream buffer;
  buffer << in.rdbuf();
  if (in.bad()) {
    errorMessage = "cannot read '" + path + "'";
    return kNoFile;
  }
  return add(path, buffer.str());
}

std::string_view SourceManager::lineText(FileId id, std::uint32_t line) const {
  if (id >= files_.size()) return {};
  const File& file = files_[id];
  if (line == 0 || line > file.lineStarts.size()) return {};
  std::size_t begin = file.lineStarts[line - 1];
  std::size_t end = line < file.lineStarts.size() ? file.lineStarts[line] - 1 : file.text.size();
  std::string_view view(file.text);
  view = view.substr(begin, end - begin);
  if (!view.empty() && view.back() == '\r') view.remove_suffix(1);
  return view;
}

std::uint32_t SourceManager::lineCount(FileId id) const {
  return id < files_.size() ? static_cast<std::uint32_t>(files_[id].lineStarts.size()) : 0;
}

std::size_t firstInvalidUtf8(std::string_view text) {
  for (std::size_t i = 0; i < text.size();) {
    const auto b = static_cast<unsigned char>(text[i]);
    if (b < 0x80) {
      ++i;
      continue;
    }
    // The length of the sequence and the range of its second byte (which rules out overlong forms,
    // surrogates and code points past U+10FFFF); the others are 0x80..0xBF.
    std::size_t length = 0;
    unsigned char low = 0x80, high = 0xBF;
    if (b >= 0xC2 && b <= 0xDF) length = 2;
    else if (b == 0xE0) length = 3, low = 0xA0;
    else if (b == 0xED) length = 3, high = 0x9F;
    else if (b >= 0xE1 && b <= 0xEF) length = 3;
    else if (b == 0xF0) length = 4, low = 0x90;
    else if (b >= 0xF1 && b <= 0xF3) length = 4;
    else if (b == 0xF4) length = 4, high = 0x8F;
    else return i;
    if (i + length > text.size()) return i;
    for (std::size_t k = 1; k < length; ++k) {
      const auto c = static_cast<unsigned char>(text[i + k]);
      if (c < (k == 1 ? low : 0x80) || c > (k == 1 ? high : 0xBF)) return i;
    }
    i += length;
  }
  return std::string_view::npos;
}

SourceLocation SourceManager::locationAt(FileId id, std::size_t offset) const {
  const File& file = files_.at(id);
  offset = std::min(offset, file.text.size());
  const auto next = std::upper_bound(file.lineStarts.begin(), file.lineStarts.end(), offset);
  const auto line = static_cast<std::uint32_t>(next - file.lineStarts.begin());
  return {id, line, static_cast<std::uint32_t>(offset - file.lineStarts[line - 1] + 1)};
}

}  // namespace semo
