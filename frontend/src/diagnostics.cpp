#include "semo/frontend/diagnostics.hpp"

#include <algorithm>
#include <cctype>
#include <tuple>
#include <ostream>

namespace semo {

namespace {

const char* severityName(Severity s) {
  switch (s) {
    case Severity::Note: return "note";
    case Severity::Warning: return "warning";
    case Severity::Error: return "error";
  }
  return "error";
}

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
    out += "semo-verify: ";
  }
  out += severityName(d.severity);
  out += ": ";
  out += d.message;
  out += '\n';
  if (!at.hasPosition()) return;
  std::string_view line = sources_->lineText(at.file, at.line);
  if (line.empty()) return;
  out.append(line);
  out += '\n';
  std::uint32_t column = std::max<std::uint32_t>(at.column, 1);
  // Keep tabs so that the caret lines up under the same columns as the source line.
  for (std::uint32_t i = 1; i < column && i - 1 < line.size(); ++i) out += line[i - 1] == '\t' ? '\t' : ' ';
  out += '^';
  std::size_t room = column - 1 < line.size() ? line.size() - column : 0;
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
