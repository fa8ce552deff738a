// --prop: choosing which properties a run decides (verify.hpp).
#include <stdexcept>
#include <utility>

#include "semo/checker/verify.hpp"

namespace semo::checker {

bool globMatches(std::string_view glob, std::string_view name) {
  // The usual greedy match with one backtrack point (the last `*`): linear in practice, at most
  // glob size times name size.
  std::size_t g = 0, n = 0, star = std::string_view::npos, resume = 0;
  while (n < name.size()) {
    if (g < glob.size() && (glob[g] == '?' || glob[g] == name[n])) {
      ++g, ++n;
    } else if (g < glob.size() && glob[g] == '*') {
      star = g++, resume = n;
    } else if (star != std::string_view::npos) {
      g = star + 1, n = ++resume;
    } else {
      return false;
    }
  }
  while (g < glob.size() && glob[g] == '*') ++g;
  return g == glob.size();
}

namespace {

// A glob without a bracket names a family too, as the verify block's `check unique_leader` does:
// `unique_leader` matches unique_leader[ReportPapers].
bool matchesWithFamily(std::string_view glob, std::string_view name) {
  return globMatches(glob, name) || (glob.find('[') == std::string_view::npos && globMatches(std::string(glob) + "[*]", name));
}

// A --prop glob without its leading `!`, and whether it had one (it leaves out what it matches).
std::pair<std::string_view, bool> withoutNegation(const std::string& g) {
  const bool leavesOut = !g.empty() && g[0] == '!';
  return {std::string_view(g).substr(leavesOut ? 1 : 0), leavesOut};
}

}  // namespace

bool propertySelected(const std::vector<std::string>& globs, const std::vector<std::string>& names) {
  bool anyChoosing = false, chosen = false;
  for (const std::string& g : globs) {
    const auto [glob, leavesOut] = withoutNegation(g);
    bool matches = false;
    for (const std::string& name : names) matches = matches || matchesWithFamily(glob, name);
    if (leavesOut && matches) return false;
    anyChoosing = anyChoosing || !leavesOut;
    chosen = chosen || (!leavesOut && matches);
  }
  return chosen || !anyChoosing;
}

std::vector<std::string> selectProperties(ir::Model& model, const std::vector<std::string>& globs) {
  std::vector<std::string> all, kept;
  for (const ir::Invariant& i : model.invariants) all.push_back(i.name);
  if (model.validEnd) all.push_back("deadlock_freedom");
  for (const ir::Property& p : model.properties) all.push_back(p.name);
  auto refuse = [&](const std::string& why) {
    std::string names;
    for (const std::string& name : all) names += (names.empty() ? "" : ", ") + name;
    throw std::invalid_argument(why + "; its properties: " + (names.empty() ? std::string("none") : names));
  };
  for (const std::string& g : globs) {
    const std::string_view glob = withoutNegation(g).first;
    bool any = false;
    for (const std::string& name : all) any = any || matchesWithFamily(glob, name);
    if (!any) refuse("--prop '" + g + "' matches no property of the model");
  }
  auto chosen = [&](const std::string& name) { return propertySelected(globs, {name}); };
  std::erase_if(model.invariants, [&](const ir::Invariant& i) { return !chosen(i.name); });
  std::erase_if(model.properties, [&](const ir::Property& p) { return !chosen(p.name); });
  if (model.validEnd && !chosen("deadlock_freedom")) model.validEnd.reset();
  for (const std::string& name : all) {
    if (chosen(name)) kept.push_back(name);
  }
  if (kept.empty()) refuse("--prop leaves out every property of the model");
  return kept;
}

}  // namespace semo::checker
