// Unity's compile environment: the macros Unity's shader compiler defines for every program of a
// .shader before its text, for the platform and hardware tier it builds for. A scene chooses the
// platform (GLCore by default; D3D11 or Vulkan, whose conventions Unity makes the same: reversed
// depth, render targets drawn upside down); the renderer then gives Unity's built-in variables the
// values a shader compiled for that platform expects (docs/unity.md).
#pragma once

#include <optional>
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

// The Unity platforms a scene can compile its .shader files for.
enum class UnityPlatform { GLCore, D3D11, Vulkan };
// The platform as `#pragma only_renderers` and `exclude_renderers` name it: "glcore", "d3d11",
// "vulkan"; also what a scene writes.
std::string_view renderer_name(UnityPlatform platform);
std::optional<UnityPlatform> parse_unity_platform(std::string_view name);
// Whether Unity's HLSLSupport.cginc defines UNITY_REVERSED_Z and UNITY_UV_STARTS_AT_TOP for the
// platform (D3D11 and Vulkan; not GLCore): depth is 1 at the near plane, and Unity draws into a
// render target with the projection flipped (_ProjectionParams.x = -1), so that its rows are
// stored bottom first as OpenGL stores them.
bool direct3d_conventions(UnityPlatform platform);

// What follows `#pragma <name>` on each line of `text` that says so, in order: views into `text`,
// each to the end of its line.
std::vector<std::string_view> pragma_arguments(std::string_view text, std::string_view name);

// Whether Unity compiles a program with that text for the platform: no `#pragma only_renderers`
// leaves it out, no `#pragma exclude_renderers` names it.
bool compiles_for_platform(std::string_view program_text, UnityPlatform platform = UnityPlatform::GLCore);

// SHADER_TARGET for a program's text: the highest `#pragma target X.Y` it holds as XY, else
// Unity's default. A target Unity names by feature ("gl4.1", "es3.0") leaves the default.
int shader_target(std::string_view program_text);

// The macros for a program with that text, in the order Unity's compiler would define them.
std::vector<Define> unity_defines(std::string_view program_text, UnityPlatform platform = UnityPlatform::GLCore);

}  // namespace xshade::shaderlab
