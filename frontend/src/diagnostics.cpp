#include "semo/frontend/diagnostics.hpp"

#include <algorithm>
#include <cctype>
#include <tuple>
#include <ostream>

namespace semo {

namespace {

std::string& programNameStore() {
  static std::string name = "semo-verify";
  return name;
}

const char* severityName(Severity s) {
  switch (s) {
    case Severity::Note: return "note";
    case Severity::Warning: return "warning";
    case Severity::Error: return "error";
  }
  return "error";
}

// Source lines longer than this are shown as a window of this many bytes, from this many before the caret.
constexpr std::size_t kShownLine = 200;
constexpr std::size_t kShownBefore = 80;

std::size_t editDistance(const std::string& a, const std::string& b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diagonal = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      std::size_t above = row[j];
      bool same = std::tolower(static_cast<unsigned char>(a[i - 1])) ==
                  std::tolower(static_cast<unsigned char>(b[j - 1]));
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (same ? 0 : 1)});
      diagonal = above;
    }
  }
  return row[b.size()];
}

}  // namespace

Diagnostic& DiagnosticEngine::error(SourceRange range, std::string message) {
  ++errors_;
  diagnostics_.push_back({Severity::Error, range, std::move(message), {}});
  return diagnostics_.back();
}

Diagnostic& DiagnosticEngine::warning(SourceRange range, std::string message) {
  ++warnings_;
  diagnostics_.push_back({Severity::Warning, range, std::move(message), {}});
  return diagnostics_.back();
}

void setProgramName(std::string name) { programNameStore() = std::move(name); }

const std::string& programName() { return programNameStore(); }

void DiagnosticEngine::note(Diagnostic& to, SourceRange range, std::string message) {
  to.notes.push_back({Severity::Note, range, std::move(message), {}});
}

void DiagnosticEngine::formatOne(std::string& out, const Diagnostic& d) const {
  const SourceLocation& at = d.range.begin;
  if (at.valid()) {
    out += sources_->path(at.file);
    if (at.line != 0) {
      out += ':' + std::to_string(at.line) + ':' + std::to_string(std::max<std::uint32_t>(at.column, 1));
    }
    out += ": ";
  } else {
    out += programName() + ": ";
  }
  out += severityName(d.severity);
  out += ": ";
  out += d.message;
  out += '\n';
  if (!at.hasPosition()) return;
  std::string_view line = sources_->lineText(at.file, at.line);
  if (line.empty()) return;
  std::size_t column = std::max<std::uint32_t>(at.column, 1);
  // A long line is shown as a window around the caret, "..." where it is cut: printed whole, one
  // line of a megabyte under each of its thousands of errors would make the output quadratic.
  std::string shown;
  if (line.size() <= kShownLine) {
    shown = line;
  } else {
    std::size_t begin = column - 1 > kShownBefore ? std::min(column - 1, line.size()) - kShownBefore : 0;
    std::size_t end = std::min(line.size(), begin + kShownLine);
    // Cut between characters, not inside a UTF-8 sequence.
    while (begin > 0 && (static_cast<unsigned char>(line[begin]) & 0xC0) == 0x80) --begin;
    while (end < line.size() && end > begin && (static_cast<unsigned char>(line[end]) & 0xC0) == 0x80) --end;
    const std::string lead = begin > 0 ? "..." : "";
    shown = lead + std::string(line.substr(begin, end - begin)) + (end < line.size() ? "..." : "");
    column = lead.size() + column - begin;
  }
  out += shown;
  out += '\n';
  // Keep tabs so that the caret lines up under the same columns as the source line.
  for (std::size_t i = 1; i < column && i - 1 < shown.size(); ++i) out += shown[i - 1] == '\t' ? '\t' : ' ';
  out += '^';
  std::size_t room = column - 1 < shown.size() ? shown.size() - column : 0;
  std::size_t tildes = std::min<std::size_t>(d.range.length > 0 ? d.range.length - 1 : 0, room);
  out.append(tildes, '~');
  out += '\n';
}

std::string DiagnosticEngine::format(const Diagnostic& d) const {
  std::string out;
  formatOne(out, d);
  for (const Diagnostic& n : d.notes) formatOne(out, n);
  return out;
}

void DiagnosticEngine::sortByPosition() {
  auto key = [](const Diagnostic& d) {
    const SourceLocation& at = d.range.begin;
    return std::tuple(at.valid() ? at.file + 1 : 0u, at.line, at.column);
  };
  std::stable_sort(diagnostics_.begin(), diagnostics_.end(),
                   [&](const Diagnostic& a, const Diagnostic& b) { return key(a) < key(b); });
}

void DiagnosticEngine::print(std::ostream& out) const {
  for (const Diagnostic& d : diagnostics_) out << format(d);
}

std::string suggestClosest(const std::string& name, const std::vector<std::string>& candidates) {
  const std::string* best = nullptr;
  std::size_t bestDistance = 0;
  for (const std::string& c : candidates) {
    std::size_t d = editDistance(name, c);
    if (best == nullptr || d < bestDistance) {
      best = &c;
      bestDistance = d;
    }
  }
  // Only suggest when the typo is small relative to the name.
  if (best == nullptr || bestDistance == 0 || bestDistance > std::max<std::size_t>(1, name.size() / 3)) return "";
  return "did you mean '" + *best + "'?";
}

}  // namespace semo
