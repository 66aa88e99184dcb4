// Suggestions for misspelt names: the candidate a typo most likely meant, for "did you mean"
// in every message that rejects a name (a scene key, a shader property, a command-line verb).
#pragma once

#include <initializer_list>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace xshade {

// Optimal string alignment distance (Levenshtein plus adjacent transpositions), ignoring case:
// the usual typos are one letter wrong, missing, doubled or swapped.
size_t edit_distance(std::string_view a, std::string_view b);

// The closest candidate when it is close enough to be a typo of `word`: one edit in words of up
// to five letters, two up to eleven, a third of the length beyond (`_RampTexture` for `_RampTex`).
std::optional<std::string_view> nearest(std::string_view word, std::span<const std::string_view> candidates);
inline std::optional<std::string_view> nearest(std::string_view word,
                                               std::initializer_list<std::string_view> candidates) {
  return nearest(word, std::span<const std::string_view>(candidates.begin(), candidates.size()));
}
std::optional<std::string> nearest(std::string_view word, const std::vector<std::string>& candidates);

}  // namespace xshade
