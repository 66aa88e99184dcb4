// Unity's keyword pragmas in all their forms: `multi_compile` and `shader_feature` with their
// scope suffixes (`_local`, `_vertex`, `_fragment`, ...), which declare the same sets, and the
// built-in shortcuts (`multi_compile_fwdbase`, `_fog`, `_shadowcaster`, ...), which stand for
// Unity's own keyword lists (the manual's "Shader directive shortcuts" table).
#pragma once

#include <optional>
#include <string_view>
#include <vector>

#include "hlsl_like/reflection.h"

namespace xshade::hlsl {

// What a pragma name declares: `multi_compile` and `shader_feature` (plain or with a scope
// suffix) take their keywords from the line; nothing for any other name.
enum class KeywordPragma { MultiCompile, ShaderFeature };
std::optional<KeywordPragma> keyword_pragma(std::string_view name);

// A shortcut's keyword sets, each with the keyword xshade's renderer draws for first (so that a
// scene that names none gets the variant its lighting matches: a directional light, the
// environment's spherical harmonics, no lightmap, no shadow, no fog). nullopt for a name that is
// not one of Unity's shortcuts.
std::optional<std::vector<KeywordSet>> keyword_shortcut(std::string_view name);

}  // namespace xshade::hlsl
