#include "semo/sdf/automorphisms.hpp"

#include <algorithm>
#include <array>
#include <iterator>
#include <map>
#include <numeric>
#include <tuple>
#include <unordered_map>

namespace semo::sdf {

namespace {

using Colours = std::vector<std::uint32_t>;

class Refiner {
 public:
  explicit Refiner(const Graph& g) : g_(g), incident_(g.actors.size()) {
    for (std::size_t c = 0; c < g.channels.size(); ++c) {
      incident_[g.channels[c].source].push_back(c);
      if (!g.channels[c].selfLoop()) incident_[g.channels[c].target].push_back(c);
    }
  }

  Colours initial() {
    Colours out(g_.actors.size());
    for (std::size_t a = 0; a < out.size(); ++a) out[a] = name(mix(mix(0x5eed) ^ static_cast<std::uint64_t>(g_.actors[a].executionTime)));
    return out;
  }

  std::uint32_t fresh() { return next_++; }

  // Refines both colourings, in lockstep (a colour names the same thing in both), until they stop
  // splitting; false when their colour counts differ (no automorphism maps one onto the other).
  bool refine(Colours& a, Colours& b) {
    names_.clear();  // names need only agree within one lockstep refinement; the counter keeps them new
    for (;;) {
      const std::size_t before = distinct(a);
      a = step(a);
      b = step(b);
      Colours sortedA = a, sortedB = b;
      std::sort(sortedA.begin(), sortedA.end());
      std::sort(sortedB.begin(), sortedB.end());
      if (sortedA != sortedB) return false;
      if (distinct(a) == before) return true;
    }
  }

 private:
  static std::size_t distinct(Colours c) {
    std::sort(c.begin(), c.end());
    return static_cast<std::size_t>(std::unique(c.begin(), c.end()) - c.begin());
  }

  static std::uint64_t mix(std::uint64_t x) {  // splitmix64's finaliser
    x += 0x9e3779b97f4a7c15ull;
    x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
    x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
    return x ^ (x >> 31);
  }

  std::uint32_t name(std::uint64_t signature) {
    auto [it, fresh] = names_.try_emplace(signature, next_);
    if (fresh) ++next_;
    return it->second;
  }

  // Each actor's new colour: its colour and the multiset of its channels (direction, rates, tokens,
  // the colour at the other end), hashed (a sum over the channels: the order does not matter). Two
  // different neighbourhoods that collide only merge colours, which can lose an automorphism but
  // never admit a wrong one: every candidate is checked channel by channel.
  Colours step(const Colours& colours) {
    Colours out(colours.size());
    for (std::size_t a = 0; a < colours.size(); ++a) {
      std::uint64_t around = 0;
      for (std::size_t c : incident_[a]) {
        const Channel& ch = g_.channels[c];
        const std::uint64_t direction = ch.selfLoop() ? 0 : ch.source == a ? 1 : 2;
        const std::uint64_t other = colours[ch.source == a ? ch.target : ch.source];
        std::uint64_t h = mix(direction);
        for (std::uint64_t x : {static_cast<std::uint64_t>(ch.production), static_cast<std::uint64_t>(ch.consumption),
                                static_cast<std::uint64_t>(ch.initialTokens), other}) {
          h = mix(h ^ x);
        }
        around += h;
      }
      out[a] = name(mix(mix(colours[a]) ^ around));
    }
    return out;
  }

  const Graph& g_;
  std::vector<std::vector<std::size_t>> incident_;
  std::unordered_map<std::uint64_t, std::uint32_t> names_;
  std::uint32_t next_ = 0;
};

class Search {
 public:
  Search(const Graph& g, std::size_t budget) : g_(g), refiner_(g), budget_(budget) {}

  std::vector<Automorphism> run() {
    std::vector<Automorphism> found;
    Colours base = refiner_.initial(), copy = base;
    refiner_.refine(base, copy);
    std::vector<ActorId> orbit(g_.actors.size());
    std::iota(orbit.begin(), orbit.end(), 0);
    auto root = [&](ActorId a) {
      while (orbit[a] != a) a = orbit[a] = orbit[orbit[a]];
      return a;
    };
    for (ActorId u = 0; u < g_.actors.size(); ++u) {
      for (ActorId v = u + 1; v < g_.actors.size(); ++v) {
        if (base[u] != base[v] || root(u) == root(v) || budget_ == 0) continue;
        Colours a = base, b = base;
        a[u] = b[v] = refiner_.fresh();
        Automorphism sigma;
        if (!extend(a, b, sigma)) continue;
        for (ActorId x = 0; x < g_.actors.size(); ++x) orbit[root(x)] = root(sigma.actor[x]);
        found.push_back(std::move(sigma));
      }
    }
    return found;
  }

 private:
  bool extend(Colours& a, Colours& b, Automorphism& out) {
    if (budget_ == 0) return false;
    --budget_;
    if (!refiner_.refine(a, b)) return false;
    std::map<std::uint32_t, std::vector<ActorId>> cellsA, cellsB;
    for (ActorId x = 0; x < a.size(); ++x) {
      cellsA[a[x]].push_back(x);
      cellsB[b[x]].push_back(x);
    }
    // First guess: within each colour, the actors in both colourings stay, the others pair off in
    // order (cheap, and right when the rest of the graph is untouched, as for a swap of two branches).
    std::vector<ActorId> guess(a.size());
    bool guessed = true;
    for (const auto& [colour, members] : cellsA) {
      const std::vector<ActorId>& others = cellsB[colour];
      if (members.size() != others.size()) {
        guessed = false;
        break;
      }
      std::vector<ActorId> onlyA, onlyB;
      std::set_difference(members.begin(), members.end(), others.begin(), others.end(), std::back_inserter(onlyA));
      std::set_difference(others.begin(), others.end(), members.begin(), members.end(), std::back_inserter(onlyB));
      for (ActorId x : members) guess[x] = x;
      for (std::size_t i = 0; i < onlyA.size(); ++i) guess[onlyA[i]] = onlyB[i];
    }
    if (guessed && completeAutomorphism(g_, guess, out)) return true;
    auto split = std::find_if(cellsA.begin(), cellsA.end(), [](const auto& cell) { return cell.second.size() > 1; });
    if (split == cellsA.end()) {
      std::vector<ActorId> image(a.size());
      for (ActorId x = 0; x < a.size(); ++x) image[x] = cellsB[a[x]].front();
      return completeAutomorphism(g_, image, out);
    }
    const ActorId x = split->second.front();
    for (ActorId y : cellsB[split->first]) {
      Colours nextA = a, nextB = b;
      nextA[x] = nextB[y] = refiner_.fresh();
      if (extend(nextA, nextB, out)) return true;
    }
    return false;
  }

  const Graph& g_;
  Refiner refiner_;
  std::size_t budget_;
};

}  // namespace

bool completeAutomorphism(const Graph& g, const std::vector<ActorId>& actorImage, Automorphism& out) {
  const std::size_t n = g.actors.size();
  if (actorImage.size() != n) return false;
  std::vector<char> hit(n, 0);
  for (ActorId a = 0; a < n; ++a) {
    if (actorImage[a] >= n || hit[actorImage[a]] || g.actors[actorImage[a]].executionTime != g.actors[a].executionTime) return false;
    hit[actorImage[a]] = 1;
  }
  using Key = std::tuple<ActorId, ActorId, std::int64_t, std::int64_t, std::int64_t>;
  std::map<Key, std::vector<std::size_t>> free;  // channels not yet an image, by ends and figures
  for (std::size_t c = g.channels.size(); c-- > 0;) {
    const Channel& ch = g.channels[c];
    free[{ch.source, ch.target, ch.production, ch.consumption, ch.initialTokens}].push_back(c);  // reversed: taken from the back
  }
  out.actor = actorImage;
  out.channel.assign(g.channels.size(), 0);
  for (std::size_t c = 0; c < g.channels.size(); ++c) {
    const Channel& ch = g.channels[c];
    auto it = free.find({actorImage[ch.source], actorImage[ch.target], ch.production, ch.consumption, ch.initialTokens});
    if (it == free.end() || it->second.empty()) return false;
    out.channel[c] = it->second.back();
    it->second.pop_back();
  }
  return true;
}

std::vector<Automorphism> findAutomorphisms(const Graph& g, std::size_t budget) { return Search(g, budget).run(); }

}  // namespace semo::sdf
