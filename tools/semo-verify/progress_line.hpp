#pragma once
// What a long command is doing, on stderr: the phase it is in and how far it got, so that a run
// never sits silent. Quick runs stay quiet: nothing is printed before the run has lasted two
// seconds. After that the current phase is printed as it starts, and a heartbeat repeats it
// (with the last counts a search gave) whenever nothing else was said for a while: every second on
// a terminal, where the line is rewritten in place, every ten seconds in a log. A phase that
// reports nothing itself (symmetry detection, translating a large team, one long BDD round) is
// still seen to be alive.
#include <chrono>
#include <condition_variable>
#include <mutex>
#include <string>
#include <thread>

#include "semo/checker/explicit_search.hpp"

namespace semo::cli {

class ProgressLine {
 public:
  // Disabled (--json), it prints nothing and starts no thread.
  explicit ProgressLine(bool enabled);
  ~ProgressLine();
  ProgressLine(const ProgressLine&) = delete;
  ProgressLine& operator=(const ProgressLine&) = delete;

  // A phase starts ("symmetry: ...", "liveness: p (2 of 5): searching"). Any thread.
  void phase(const std::string& what);
  // The explicit search's counts, shown with the phase. Any thread.
  void searched(const checker::Progress& p);
  // A line printed at once, whatever the time (the model's size before a long search).
  void say(const std::string& line);
  // A line printed before anything else, should the run last long enough to print anything (the
  // model's size before a search that may or may not take long).
  void sayIfLong(const std::string& line);
  // No phase running (until the next): the heartbeat stays silent and a rewritten line is ended,
  // so that what is printed next (diagnostics) stands on its own lines.
  void pause();
  // Ends the heartbeat and, on a terminal, the rewritten line: what follows starts on a line of its
  // own. Idempotent.
  void stop();

 private:
  void heartbeat();
  void printLocked(const std::string& text);
  [[nodiscard]] double secondsSinceStart() const;

  const bool enabled_;
  const bool terminal_;
  const std::chrono::steady_clock::time_point started_ = std::chrono::steady_clock::now();
  std::mutex lock_;
  std::condition_variable wake_;
  std::string phase_;      // the current phase, as said
  std::string counts_;     // the last search counts, "" when the phase gave none
  std::string preamble_;   // sayIfLong's line, until printed
  bool phasePrinted_ = true;
  bool lineOpen_ = false;  // on a terminal: a line was written without its newline
  bool stopping_ = false;
  double lastPrinted_ = 0;  // seconds since start
  std::thread thread_;
};

}  // namespace semo::cli
