#pragma once
// Where each value of a JSON text starts, by JSON pointer ("/tasks/3/name"), so that errors found
// after nlohmann::json has parsed (and validated) the text can point at the offending value.
// The scan expects the text to be valid JSON (it runs after a successful parse) but stays within
// bounds whatever the text holds.
#include <cstddef>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

namespace semo::runtime {

class JsonPositions {
 public:
  explicit JsonPositions(std::string_view text) { scan(text); }
  // Byte offset of the value at `pointer`, or of the closest enclosing value that was recorded.
  [[nodiscard]] std::size_t offsetOf(std::string pointer) const {
    for (;;) {
      auto it = offsets_.find(pointer);
      if (it != offsets_.end()) return it->second;
      const auto slash = pointer.rfind('/');
      if (slash == std::string::npos || pointer.empty()) return 0;
      pointer.resize(slash);
    }
  }

 private:
  std::unordered_map<std::string, std::size_t> offsets_;

  struct Frame {
    std::string pointer;
    bool array = false;
    std::size_t index = 0;
    std::string key;
  };

  static std::string escapeKey(const std::string& key) {
    std::string out;
    for (char c : key) out += c == '~' ? std::string("~0") : c == '/' ? std::string("~1") : std::string(1, c);
    return out;
  }

  void scan(std::string_view t) {
    std::vector<Frame> stack;
    bool expectKey = false;
    auto valuePointer = [&]() -> std::string {
      if (stack.empty()) return "";
      const Frame& f = stack.back();
      return f.pointer + "/" + (f.array ? std::to_string(f.index) : escapeKey(f.key));
    };
    for (std::size_t i = 0; i < t.size(); ++i) {
      const char c = t[i];
      if (c == ' ' || c == '\n' || c == '\r' || c == '\t' || c == ':') continue;
      if (c == ',') {
        if (!stack.empty() && stack.back().array) ++stack.back().index;
        if (!stack.empty() && !stack.back().array) expectKey = true;
        continue;
      }
      if (c == '}' || c == ']') {
        if (!stack.empty()) stack.pop_back();
        continue;
      }
      if (c == '"') {
        std::size_t j = i + 1;
        std::string s;
        while (j < t.size() && t[j] != '"') {
          if (t[j] == '\\' && j + 1 < t.size()) s += t[++j];  // good enough for keys: escapes are rare there
          else s += t[j];
          ++j;
        }
        if (expectKey && !stack.empty()) {
          stack.back().key = s;
          expectKey = false;
        } else {
          offsets_.emplace(valuePointer(), i);
        }
        i = j;
        continue;
      }
      const std::string here = valuePointer();
      offsets_.emplace(here, i);
      if (c == '{' || c == '[') {
        stack.push_back({here, c == '[', 0, ""});
        expectKey = c == '{';
        continue;
      }
      while (i + 1 < t.size() && std::string_view(",]} \n\r\t").find(t[i + 1]) == std::string_view::npos) ++i;  // a scalar
    }
  }
};

}  // namespace semo::runtime
