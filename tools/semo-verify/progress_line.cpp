#include "progress_line.hpp"

#include <unistd.h>

#include <algorithm>
#include <iostream>
#include <regex>

#include <fmt/format.h>

#include "commands.hpp"

namespace semo::cli {

namespace {

constexpr double kQuietSeconds = 2.0;      // a run shorter than this prints nothing
constexpr double kTerminalRepeat = 1.0;    // the rewritten line's clock ticks every second
constexpr double kLogRepeat = 10.0;        // a log gets a line after ten silent seconds, or a tenth
                                           // of the run's time so far: a long run's log stays short

// On a terminal, a phase that says how far it is ("depth 4 of 5", "(3 of 7)") gets a bar for it:
// "[######----] ".
std::string progressBar(const std::string& what) {
  static const std::regex fraction(R"(([0-9]+) of ([0-9]+))");
  std::smatch m;
  if (!std::regex_search(what, m, fraction)) return {};
  const double done = std::stod(m[1].str()), all = std::stod(m[2].str());
  if (!(all > 0)) return {};
  const auto filled = static_cast<std::size_t>(std::clamp(10.0 * done / all, 0.0, 10.0));
  return "[" + std::string(filled, '#') + std::string(10 - filled, '-') + "] ";
}

}  // namespace

ProgressLine::ProgressLine(bool enabled) : enabled_(enabled), terminal_(enabled && isatty(STDERR_FILENO) != 0) {
  if (enabled_) thread_ = std::thread([this] { heartbeat(); });
}

ProgressLine::~ProgressLine() { stop(); }

double ProgressLine::secondsSinceStart() const {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - started_).count();
}

void ProgressLine::phase(const std::string& what) {
  if (!enabled_) return;
  const std::lock_guard<std::mutex> hold(lock_);
  phase_ = what;
  counts_.clear();
  phasePrinted_ = false;
  if (secondsSinceStart() >= kQuietSeconds) printLocked(phase_);
}

void ProgressLine::searched(const checker::Progress& p) {
  if (!enabled_) return;
  const std::lock_guard<std::mutex> hold(lock_);
  counts_ = p.counted ? fmt::format("{} states (counted, decision diagrams), round {}, {} MiB", withThousands(p.states), p.depth, p.bytes >> 20)
                      : fmt::format("{} states, {} states/s, depth {}, {} MiB", withThousands(p.states),
                                    withThousands(static_cast<std::uint64_t>(p.seconds > 0 ? static_cast<double>(p.states) / p.seconds : 0.0)),
                                    p.depth, p.bytes >> 20);
  const double repeat = terminal_ ? 0.0 : kLogRepeat;
  if (secondsSinceStart() >= kQuietSeconds && secondsSinceStart() - lastPrinted_ >= repeat) {
    printLocked(phase_.empty() ? counts_ : phase_ + ": " + counts_);
  }
}

void ProgressLine::say(const std::string& line) {
  if (!enabled_) return;
  const std::lock_guard<std::mutex> hold(lock_);
  std::cerr << (lineOpen_ ? "\r\x1b[K" : "") << line << "\n" << std::flush;
  lineOpen_ = false;
  lastPrinted_ = secondsSinceStart();
}

void ProgressLine::pause() {
  if (!enabled_) return;
  const std::lock_guard<std::mutex> hold(lock_);
  phase_.clear();
  counts_.clear();
  if (lineOpen_) std::cerr << "\n" << std::flush;
  lineOpen_ = false;
}

void ProgressLine::sayIfLong(const std::string& line) {
  if (!enabled_) return;
  const std::lock_guard<std::mutex> hold(lock_);
  preamble_ = line;
}

void ProgressLine::printLocked(const std::string& text) {
  const double seconds = secondsSinceStart();
  if (!preamble_.empty()) {
    std::cerr << (lineOpen_ ? "\r\x1b[K" : "") << preamble_ << "\n";
    lineOpen_ = false;
    preamble_.clear();
  }
  const std::string line = fmt::format("[{} s] {}", static_cast<long long>(seconds), text);
  if (terminal_) {
    std::cerr << "\r\x1b[K" << progressBar(text) << line << std::flush;
    lineOpen_ = true;
  } else {
    std::cerr << line << "\n" << std::flush;
  }
  lastPrinted_ = seconds;
  phasePrinted_ = true;
}

void ProgressLine::heartbeat() {
  std::unique_lock<std::mutex> hold(lock_);
  while (!stopping_) {
    wake_.wait_for(hold, std::chrono::milliseconds(250));
    if (stopping_ || phase_.empty()) continue;
    const double seconds = secondsSinceStart();
    if (seconds < kQuietSeconds) continue;
    // A phase not yet printed (it began in the quiet start) is printed as soon as the run is no
    // longer quick; then the line is repeated when nothing else was said for a while.
    const double repeat = terminal_ ? kTerminalRepeat : std::max(kLogRepeat, seconds / 10);
    if (phasePrinted_ && seconds - lastPrinted_ < repeat) continue;
    const std::string what = counts_.empty() ? phase_ : phase_ + ": " + counts_;
    printLocked(phasePrinted_ && !terminal_ ? what + " (still working)" : what);
  }
}

void ProgressLine::stop() {
  if (!enabled_) return;
  {
    const std::lock_guard<std::mutex> hold(lock_);
    if (stopping_) return;
    stopping_ = true;
  }
  wake_.notify_all();
  if (thread_.joinable()) thread_.join();
  if (lineOpen_) std::cerr << "\n" << std::flush;
  lineOpen_ = false;
}

}  // namespace semo::cli
