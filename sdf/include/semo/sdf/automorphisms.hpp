#pragma once
// Symmetries of an SDF graph: permutations of its actors and channels that map it onto itself
// exactly (execution times, rates, initial tokens, and each channel's ends). Under such a
// permutation every analysis gives the same answer for a buffer distribution and for its image, so
// what is learnt about one distribution holds for its images (buffers.cpp uses this for the
// identical branches of graphs like the mp3 decoder's granule branches).
//
// Found, not assumed: colour refinement (actors coloured by execution time, then repeatedly by the
// multiset of their channels' rates, tokens and neighbours' colours) separates actors no
// automorphism can exchange; for actors u and v of one colour, u and v are given a new colour of
// their own and the refinement continues, individualising further pairs of actors in lockstep until
// every colour is a single actor, which gives a candidate mapping; only candidates that map every
// channel onto a channel are kept. The permutations returned may generate only part of the
// automorphism group (the search has a budget); every one is exact.
#include <cstddef>
#include <cstdint>
#include <vector>

#include "semo/sdf/graph.hpp"

namespace semo::sdf {

struct Automorphism {
  std::vector<ActorId> actor;        // per actor, its image
  std::vector<std::size_t> channel;  // per channel, its image
};

// Whether `actorImage` maps the graph onto itself; if so, `out` gets the permutation with a channel
// map (parallel channels alike in every respect are paired in order).
bool completeAutomorphism(const Graph& g, const std::vector<ActorId>& actorImage, Automorphism& out);

// Automorphisms of `g`, none the identity, that together map each actor to every actor of its orbit
// the search finds (within `budget` refinement steps).
std::vector<Automorphism> findAutomorphisms(const Graph& g, std::size_t budget = 20'000);

}  // namespace semo::sdf
