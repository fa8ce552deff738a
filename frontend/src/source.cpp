#include "semo/frontend/source.hpp"

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

}  // namespace semo
