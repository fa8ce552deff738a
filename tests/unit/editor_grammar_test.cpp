// tools/editors/semo.tmLanguage.json: the syntax-highlighting grammar is valid JSON, its patterns
// compile, and every reserved word of the language (specs/language.md) is given a scope.
#include <gtest/gtest.h>

#include <fstream>
#include <regex>
#include <sstream>

#include <nlohmann/json.hpp>

namespace {

void collect(const nlohmann::json& j, std::vector<std::string>& out) {
  if (j.is_object()) {
    for (auto it = j.begin(); it != j.end(); ++it) {
      if ((it.key() == "match" || it.key() == "begin") && it->is_string()) out.push_back(it->get<std::string>());
      collect(*it, out);
    }
  } else if (j.is_array()) {
    for (const nlohmann::json& v : j) collect(v, out);
  }
}

TEST(EditorGrammar, EveryReservedWordHasAScope) {
  std::ifstream in(std::string(SEMO_SOURCE_DIR) + "/tools/editors/semo.tmLanguage.json");
  ASSERT_TRUE(in.good());
  std::stringstream text;
  text << in.rdbuf();
  const nlohmann::json grammar = nlohmann::json::parse(text.str());
  EXPECT_EQ(grammar.at("scopeName"), "source.semo");
  EXPECT_EQ(grammar.at("fileTypes").at(0), "semo");
  std::vector<std::string> patterns;
  collect(grammar.at("repository"), patterns);
  ASSERT_GE(patterns.size(), 15u);
  std::vector<std::regex> compiled;
  for (const std::string& p : patterns) compiled.emplace_back(p);  // throws on a pattern ECMAScript cannot read
  auto scoped = [&](const std::string& word) {
    for (const std::regex& r : compiled) {
      std::smatch m;
      if (std::regex_search(word, m, r) && m.position(0) == 0 && m.length(0) == static_cast<std::ptrdiff_t>(word.size())) return true;
    }
    return false;
  };
  for (const char* word : {"leader", "group", "others", "throw", "loop", "if", "else", "publish", "subscribe", "send", "receive", "wait",
                           "set", "main", "case", "catch", "default", "repeat", "not", "and", "or", "true", "false", "verify", "assume",
                           "check", "property", "always", "eventually", "crash", "loss", "mode_agreement", "2 SEC", "\"", "# note",
                           "[[", "]]", "=="}) {
    EXPECT_TRUE(scoped(word)) << word;
  }
  EXPECT_FALSE(scoped("leaderboard")) << "keywords match whole words only";
}

}  // namespace
