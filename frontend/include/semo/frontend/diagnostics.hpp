#pragma once
// Clang-style diagnostics: "file:line:col: error: message", the source line and a caret.
#include <deque>
#include <iosfwd>
#include <string>
#include <vector>

#include "semo/frontend/source.hpp"

namespace semo {

enum class Severity { Note, Warning, Error };

struct Diagnostic {
  Severity severity = Severity::Error;
  SourceRange range;  // range.begin.file may be kNoFile for diagnostics about no file
  std::string message;
  std::vector<Diagnostic> notes;
};

class DiagnosticEngine {
 public:
  explicit DiagnosticEngine(const SourceManager& sources) : sources_(&sources) {}

  // Returns the new diagnostic so that notes can be attached to it.
  Diagnostic& error(SourceRange range, std::string message);
  Diagnostic& warning(SourceRange range, std::string message);
  static void note(Diagnostic& to, SourceRange range, std::string message);

  [[nodiscard]] std::size_t errorCount() const { return errors_; }
  [[nodiscard]] std::size_t warningCount() const { return warnings_; }
  [[nodiscard]] bool hasErrors() const { return errors_ != 0; }
  [[nodiscard]] const std::deque<Diagnostic>& diagnostics() const { return diagnostics_; }
  [[nodiscard]] const SourceManager& sources() const { return *sources_; }

  // Orders diagnostics by file, line and column (stable; those without a position first), so that a
  // user reads them top to bottom whatever pass found them.
  void sortByPosition();
  // Prints every diagnostic in the order reported, each with its line and caret.
  void print(std::ostream& out) const;
  [[nodiscard]] std::string format(const Diagnostic& d) const;

 private:
  void formatOne(std::string& out, const Diagnostic& d) const;

  const SourceManager* sources_;
  std::deque<Diagnostic> diagnostics_;  // deque: returned references stay valid
  std::size_t errors_ = 0;
  std::size_t warnings_ = 0;
};

// What a diagnostic without a file starts with: the program and its command ("semo-verify check"),
// so that a message read in a log says which command said it. Set once by the program, before any
// diagnostic; "semo-verify" until then.
void setProgramName(std::string name);
const std::string& programName();

// "did you mean 'X'?" for the closest of `candidates` to `name`, or "" if none is close.
std::string suggestClosest(const std::string& name, const std::vector<std::string>& candidates);

}  // namespace semo
