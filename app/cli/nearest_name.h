// "Did you mean": the valid name nearest a mistyped one, by edit distance.
#pragma once

#include <string>
#include <vector>

namespace tessera {

// Insertions, deletions, substitutions and swaps of two neighbours ("widht" -> "width": 1),
// each costing one (the optimal string alignment distance).
int edit_distance(const std::string& a, const std::string& b);

// The candidate nearest `typed`, when near enough to be what was meant (at most a third of
// its letters, and at least 1, changed); empty when none is.
std::string nearest_name(const std::string& typed, const std::vector<std::string>& candidates);

}  // namespace tessera
