// Tables as C++ aggregate initializers (cpp_tables.hpp). Deterministic: members in declaration
// order, numbers in their shortest exact form, so the same tables always give the same text.
#include <algorithm>
#include <type_traits>

#include "semo/codegen/cpp_tables.hpp"
#include "table_schema.hpp"

namespace semo::codegen::cpp {

namespace {

using namespace semo::runtime;

using schema::IsPair;
using schema::IsVector;

constexpr int kWidth = 110;  // a nest that fits on one line stays on one

class Writer {
 public:
  explicit Writer(const RowComment* comment) : comment_(comment) {}

  // The value on one line.
  template <class T> std::string inlineText(const T& x) const {
    if constexpr (std::is_arithmetic_v<T> || std::is_enum_v<T> || std::is_same_v<T, std::string> || IsPair<T>::value) {
      return schema::scalarText(x);
    } else if constexpr (IsVector<T>::value) {
      std::string out = "{";
      for (std::size_t i = 0; i < x.size(); ++i) out += (i == 0 ? "" : ", ") + inlineText(x[i]);
      return out + "}";
    } else {
      std::string out = "{";
      for (const auto& [name, value] : members(x)) out += (out.size() == 1 ? "." : ", .") + name + " = " + value;
      return out + "}";
    }
  }

  // The value at column `indent`, on one line if it fits (or must: a row), else one member or
  // element per line. `member` is the name of the member it is the value of.
  template <class T> std::string block(const T& x, int indent, std::string_view member) const {
    if constexpr (IsVector<T>::value) {
      using E = typename T::value_type;
      const bool rows = std::is_same_v<E, Row>;
      std::string line = inlineText(x);
      if (!rows && indent + static_cast<int>(line.size()) <= kWidth) return line;
      if (x.empty()) return "{}";
      const std::string pad(static_cast<std::size_t>(indent) + 4, ' ');
      std::string out = "{\n";
      for (std::size_t i = 0; i < x.size(); ++i) {
        out += pad + (rows ? inlineText(x[i]) : block(x[i], indent + 4, {})) + ",";
        if constexpr (std::is_same_v<E, Row>) {
          const std::string c = comment_ != nullptr && *comment_ ? (*comment_)(x[i]) : std::string();
          if (!c.empty()) out += "  // " + c;
        } else if constexpr (std::is_same_v<E, PlanPoint>) {
          if (member == "points") out += "  // pc " + std::to_string(i);
        }
        out += "\n";
      }
      return out + std::string(static_cast<std::size_t>(indent), ' ') + "}";
    } else if constexpr (std::is_class_v<T> && !std::is_same_v<T, std::string> && !IsPair<T>::value) {
      std::string line = inlineText(x);
      if (indent + static_cast<int>(line.size()) <= kWidth) return line;
      const std::string pad(static_cast<std::size_t>(indent) + 4, ' ');
      std::string out = "{\n";
      BlockMembers v{*this, indent + 4, {}, members(x)};
      schema::describe(v, const_cast<T&>(x));  // describe only reads through the reference here
      for (const auto& [name, value] : v.out) out += pad + "." + name + " = " + value + ",\n";
      return out + std::string(static_cast<std::size_t>(indent), ' ') + "}";
    } else {
      return inlineText(x);
    }
  }

 private:
  // The members of x that differ from a default-constructed T, each as inline text.
  template <class T> std::vector<std::pair<std::string, std::string>> members(const T& x) const {
    Collect mine{*this, {}}, defaults{*this, {}};
    T def{};
    schema::describe(mine, const_cast<T&>(x));
    schema::describe(defaults, def);
    std::vector<std::pair<std::string, std::string>> out;
    for (std::size_t i = 0; i < mine.out.size(); ++i) {
      // A `kind` is written even at its default: a row's action reads `.kind = ActionRow::Kind::Call`.
      if (mine.out[i].second != defaults.out[i].second || mine.out[i].first == "kind") out.push_back(mine.out[i]);
    }
    return out;
  }

  struct Collect {
    const Writer& w;
    std::vector<std::pair<std::string, std::string>> out;
    template <class F> void field(const char* name, F& value) { out.emplace_back(name, w.inlineText(value)); }
  };

  // The members `keep` names (those not at their defaults), laid out at `indent`.
  struct BlockMembers {
    const Writer& w;
    int indent;
    std::vector<std::pair<std::string, std::string>> out;
    std::vector<std::pair<std::string, std::string>> keep;
    template <class F> void field(const char* name, F& value) {
      for (const auto& k : keep) {
        if (k.first == name) out.emplace_back(name, w.block(value, indent, name));
      }
    }
  };

  const RowComment* comment_;
};

}  // namespace

std::string missionInitializer(const MissionTables& shared, int indent) { return Writer(nullptr).block(shared, indent, {}); }

std::string robotInitializer(const RobotTable& robot, const RowComment& comment, int indent) {
  return Writer(&comment).block(robot, indent, {});
}

std::string rowText(const Row& row) { return Writer(nullptr).inlineText(row); }

std::vector<RowLine> rowLines(const RobotTable& robot, std::string_view text) {
  // Each row is one line of its own: find its exact text, plan by plan, in order.
  std::vector<RowLine> out;
  std::size_t at = 0;
  for (std::size_t p = 0; p < robot.plans.size(); ++p) {
    for (std::size_t r = 0; r < robot.plans[p].rows.size(); ++r) {
      const std::string needle = rowText(robot.plans[p].rows[r]) + ",";
      const std::size_t found = text.find(needle, at);
      if (found == std::string_view::npos) continue;
      at = found + needle.size();
      const auto line = static_cast<std::uint32_t>(std::count(text.begin(), text.begin() + static_cast<std::ptrdiff_t>(found), '\n') + 1);
      out.push_back({p, r, line});
    }
  }
  return out;
}

}  // namespace semo::codegen::cpp
