// Unity's compile environment: the macros Unity's shader compiler defines for every program of a
// .shader before its text, for the platform and hardware tier it builds for. xshade compiles every
// lane as Unity's GLCore platform on a desktop of tier 3 (docs/unity.md says why): its
// conventions are the renderer's (depth not reversed, 0 at the near plane; uv (0, 0) at the first
// row of a target; nothing flipped), so the values the renderer gives Unity's built-in variables
// are the ones a shader compiled so expects.
#pragma once

#include <string>
#include <string_view>
#include <vector>

namespace xshade::shaderlab {

struct Define {
  std::string name;
  std::string value;
  bool operator==(const Define&) const = default;
};

// Unity's default shader target, 2.5, as SHADER_TARGET spells it.
inline constexpr int kDefaultShaderTarget = 25;
// The Unity version the defines say (UNITY_VERSION): 2019.4, the built-in shaders' version the
// include files of its "Built-in shaders" download match. A shader that needs another gives
// UNITY_VERSION with -D.
inline constexpr int kUnityVersion = 201941;

// The platform as `#pragma only_renderers` and `exclude_renderers` name it.
inline constexpr std::string_view kUnityRenderer = "glcore";

// Whether Unity compiles a program with that text for the platform: no `#pragma only_renderers`
// leaves it out, no `#pragma exclude_renderers` names it.
bool compiles_for_platform(std::string_view program_text);

// SHADER_TARGET for a program's text: the highest `#pragma target X.Y` it holds as XY, else
// Unity's default. A target Unity names by feature ("gl4.1", "es3.0") leaves the default.
int shader_target(std::string_view program_text);

// The macros for a program with that text, in the order Unity's compiler would define them.
std::vector<Define> unity_defines(std::string_view program_text);

}  // namespace xshade::shaderlab
