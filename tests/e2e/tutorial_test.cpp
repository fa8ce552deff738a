// docs/tutorial.md, read as its reader reads it: every command it shows (a fenced block whose first
// line is `$ semo-verify ...`) is run from a folder that sees the repository's specs/ as the top
// folder does, and what the page shows under it must be what the command prints, line for line.
// A line `...` on the page stands for any number of lines; a duration ("2.38 ms") stands for any
// duration; the progress lines of a slow run ("[3 s] ...", stderr) are not compared. stderr comes
// first, as on a terminal, where the diagnostics are written before the report. The exit code is the
// one the page's `— exit N` says, else 0. A mission the page lists after "`specs/....semo`:" must be
// that file, but for its leading comment.
#include <gtest/gtest.h>

#include <cstdlib>
#include <optional>
#include <vector>

#include "cli_run.hpp"

namespace semo::e2e {
namespace {

const fs::path kPage = fs::path(SEMO_SOURCE_DIR) / "docs" / "tutorial.md";

struct Block {
  int line = 0;                    // of its first line after the fence, 1-based
  std::string introducedBy;        // the last non-blank line before the fence
  std::vector<std::string> lines;  // between the fences
};

std::vector<std::string> splitLines(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

std::vector<Block> fencedBlocks() {
  const std::vector<std::string> page = splitLines(slurp(kPage));
  std::vector<Block> blocks;
  std::string lastText;
  for (std::size_t i = 0; i < page.size(); ++i) {
    if (page[i].rfind("```", 0) != 0) {
      if (!page[i].empty()) lastText = page[i];
      continue;
    }
    Block b;
    b.line = static_cast<int>(i) + 2;
    b.introducedBy = lastText;
    for (++i; i < page.size() && page[i].rfind("```", 0) != 0; ++i) b.lines.push_back(page[i]);
    blocks.push_back(std::move(b));
    lastText.clear();
  }
  return blocks;
}

// A failing case names its block by its line, not its bytes.
void PrintTo(const Block& b, std::ostream* out) { *out << "docs/tutorial.md:" << b.line; }

bool isCommand(const Block& b) { return !b.lines.empty() && b.lines[0].rfind("$ semo-verify ", 0) == 0; }

// The path a block is introduced as, when the line before it ends with "`specs/...`:".
std::optional<std::string> listedFile(const Block& b) {
  static const std::regex listing(R"(`(specs/[^`]+)`:$)");
  std::smatch m;
  if (!std::regex_search(b.introducedBy, m, listing)) return std::nullopt;
  return m[1].str();
}

// A line of the page as a regular expression: itself, but for durations.
std::regex lineOfPage(const std::string& shown) {
  static const std::regex duration(R"([0-9]+(\.[0-9]+)? (ms|s|min)\b)");
  static const std::regex special(R"([.^$|()\[\]{}*+?\\])");
  std::string pattern;
  std::size_t from = 0;
  for (auto it = std::sregex_iterator(shown.begin(), shown.end(), duration); it != std::sregex_iterator(); ++it) {
    pattern += std::regex_replace(shown.substr(from, it->position() - from), special, R"(\$&)");
    pattern += R"([0-9]+(\.[0-9]+)? (ms|s|min))";
    from = it->position() + it->length();
  }
  pattern += std::regex_replace(shown.substr(from), special, R"(\$&)");
  return std::regex(pattern);
}

// Where `shown` (with its `...` lines) fails to describe `printed`: empty when it does. The parts
// between the `...` lines must appear in order, the first at the start unless the page begins with
// `...`, the last at the end unless it ends with one.
std::string mismatch(const std::vector<std::string>& shown, const std::vector<std::string>& printed) {
  std::vector<std::vector<std::string>> parts(1);
  for (const std::string& line : shown) {
    if (line == "...") parts.emplace_back();
    else parts.back().push_back(line);
  }
  auto matchesAt = [&](const std::vector<std::string>& part, std::size_t at) {
    if (at + part.size() > printed.size()) return false;
    for (std::size_t k = 0; k < part.size(); ++k) {
      if (!std::regex_match(printed[at + k], lineOfPage(part[k]))) return false;
    }
    return true;
  };
  auto firstDifference = [&](const std::vector<std::string>& part, std::size_t at) {
    for (std::size_t k = 0; k < part.size(); ++k) {
      if (at + k >= printed.size()) return "the page shows\n  " + part[k] + "\nafter the output's last line";
      if (!std::regex_match(printed[at + k], lineOfPage(part[k]))) {
        return "the page shows\n  " + part[k] + "\nwhere the output has\n  " + printed[at + k];
      }
    }
    return std::string();
  };
  const bool open = parts.size() > 1;
  std::size_t at = 0;
  // The first part is anchored at the start.
  if (!matchesAt(parts.front(), 0)) return firstDifference(parts.front(), 0);
  if (!open) {
    if (parts.front().size() != printed.size()) {
      return printed.size() > parts.front().size() ? "the output goes on after the page's last line:\n  " + printed[parts.front().size()]
                                                   : std::string("the output ends early");
    }
    return {};
  }
  at = parts.front().size();
  for (std::size_t p = 1; p + 1 < parts.size(); ++p) {
    std::size_t found = at;
    while (found <= printed.size() && !matchesAt(parts[p], found)) ++found;
    if (found > printed.size()) return "these lines of the page are not in the output, in this order:\n  " + parts[p].front();
    at = found + parts[p].size();
  }
  const std::vector<std::string>& last = parts.back();
  if (last.size() > printed.size() || printed.size() - last.size() < at || !matchesAt(last, printed.size() - last.size())) {
    return "the page's last lines are not the output's last lines: " +
           (printed.size() >= last.size() ? firstDifference(last, printed.size() - last.size()) : std::string("the output is shorter"));
  }
  return {};
}

std::string joined(const std::vector<std::string>& lines) {
  std::string text;
  for (const std::string& l : lines) text += l + "\n";
  return text;
}

class Tutorial : public ::testing::TestWithParam<Block> {};

TEST_P(Tutorial, ShowsWhatTheCommandPrints) {
  const Block& b = GetParam();
  const std::string where = "docs/tutorial.md:" + std::to_string(b.line);
  const fs::path dir = workDir("tutorial/line" + std::to_string(b.line));
  fs::create_directory_symlink(fs::path(SEMO_SOURCE_DIR) / "specs", dir / "specs");
  const std::string args = b.lines[0].substr(std::string("$ semo-verify ").size());
  const std::string command = "cd '" + dir.string() + "' && '" SEMO_VERIFY "' " + args + " >stdout.txt 2>stderr.txt";
  const int status = std::system(command.c_str());
  const int exit = WIFEXITED(status) ? WEXITSTATUS(status) : -1;

  std::vector<std::string> printed;
  static const std::regex progress(R"(^\[[0-9]+ s\] )");
  for (const std::string& line : splitLines(slurp(dir / "stderr.txt"))) {
    if (!std::regex_search(line, progress)) printed.push_back(line);
  }
  for (const std::string& line : splitLines(slurp(dir / "stdout.txt"))) printed.push_back(line);

  const std::vector<std::string> shown(b.lines.begin() + 1, b.lines.end());
  int expectedExit = 0;
  static const std::regex exitCode(R"(— exit ([0-9]+))");
  for (const std::string& line : shown) {
    std::smatch m;
    if (std::regex_search(line, m, exitCode)) expectedExit = std::stoi(m[1].str());
  }
  EXPECT_EQ(exit, expectedExit) << where << ": " << b.lines[0];
  const std::string why = mismatch(shown, printed);
  if (!why.empty()) {
    ADD_FAILURE() << where << ": " << b.lines[0] << "\n" << why << "\n--- the page shows\n" << joined(shown) << "--- the command printed\n"
                  << joined(printed);
  }
}

std::vector<Block> commandBlocks() {
  std::vector<Block> commands;
  for (const Block& b : fencedBlocks()) {
    if (isCommand(b)) commands.push_back(b);
  }
  return commands;
}

std::string blockName(const ::testing::TestParamInfo<Block>& info) {
  // "command2_check": the page's second command, a check (a failure names the page's line).
  const std::string args = info.param.lines[0].substr(std::string("$ semo-verify ").size());
  return "command" + std::to_string(info.index + 1) + "_" + args.substr(0, args.find(' '));
}

INSTANTIATE_TEST_SUITE_P(, Tutorial, ::testing::ValuesIn(commandBlocks()), blockName);

// The page's command blocks are found (a change of its layout must not leave nothing compared), and
// a mission it lists is the file, but for the file's leading comment.
TEST(TutorialPage, ListsItsMissionAsTheFileIs) {
  int listings = 0;
  for (const Block& b : fencedBlocks()) {
    const std::optional<std::string> path = listedFile(b);
    if (!path) continue;
    ++listings;
    std::vector<std::string> file = splitLines(slurp(fs::path(SEMO_SOURCE_DIR) / *path));
    std::size_t start = 0;
    while (start < file.size() && (file[start].empty() || file[start][0] == '#')) ++start;
    EXPECT_EQ(joined(b.lines), joined({file.begin() + static_cast<std::ptrdiff_t>(start), file.end()}))
        << "docs/tutorial.md:" << b.line << " lists " << *path;
  }
  EXPECT_GE(listings, 1) << "the tutorial lists its mission";
  EXPECT_GE(commandBlocks().size(), 5U) << "the tutorial's lint, check (twice), sdf and emit";
}

// The comparison itself: `...` stands for lines, a duration for a duration, and nothing else is
// loose.
TEST(TutorialPage, TheComparisonIsLooseOnlyWhereItSays) {
  const std::vector<std::string> printed{"model: m", "explored: 3 states, 2.38 ms", "x", "y", "result: 1 proven"};
  EXPECT_EQ(mismatch({"model: m", "explored: 3 states, 0.08 s", "x", "y", "result: 1 proven"}, printed), "");
  EXPECT_EQ(mismatch({"model: m", "explored: 3 states, 12 ms", "x", "y", "result: 1 proven"}, printed), "");
  EXPECT_EQ(mismatch({"model: m", "...", "result: 1 proven"}, printed), "");
  EXPECT_EQ(mismatch({"...", "x", "...", "result: 1 proven"}, printed), "");
  EXPECT_NE(mismatch({"model: m", "explored: 4 states, 0.08 s", "x", "y", "result: 1 proven"}, printed), "");
  EXPECT_NE(mismatch({"model: m", "explored: 3 states, 0.08 s", "x", "y"}, printed), "") << "a line left out without `...`";
  EXPECT_NE(mismatch({"model: m", "...", "result: 2 proven"}, printed), "");
  EXPECT_NE(mismatch({"model: m", "...", "y", "x", "..."}, printed), "") << "out of order";
  EXPECT_NE(mismatch({"model: m", "...", "result: 1 proven", "z"}, printed), "");
  EXPECT_NE(mismatch({"model: (m)"}, {"model: m"}), "") << "parentheses are literal";
  EXPECT_NE(mismatch({"explored: 4 ms"}, {"explored: 4 states"}), "") << "a duration stands only for a duration";
}

}  // namespace
}  // namespace semo::e2e
