#include "shaderlab/compile_environment.h"

#include <algorithm>
#include <cctype>

namespace xshade::shaderlab {
namespace {

std::string_view skip_blanks(std::string_view text) {
  while (!text.empty() && (text.front() == ' ' || text.front() == '\t')) text.remove_prefix(1);
  return text;
}

bool take_word(std::string_view& text, std::string_view word) {
  if (!text.starts_with(word)) return false;
  const std::string_view rest = text.substr(word.size());
  if (!rest.empty() && (std::isalnum(static_cast<unsigned char>(rest.front())) || rest.front() == '_')) return false;
  text = skip_blanks(rest);
  return true;
}

bool names_renderer(std::string_view renderers, std::string_view renderer) {
  while (!(renderers = skip_blanks(renderers)).empty()) {
    const size_t end = std::min(renderers.find_first_of(" \t\r/"), renderers.size());
    if (renderers.substr(0, end) == renderer) return true;
    if (end < renderers.size() && renderers[end] == '/') break;  // a comment
    renderers.remove_prefix(end);
  }
  return false;
}

}  // namespace

std::vector<std::string_view> pragma_arguments(std::string_view text, std::string_view name) {
  std::vector<std::string_view> found;
  size_t line_start = 0;
  while (line_start < text.size()) {
    size_t line_end = text.find('\n', line_start);
    if (line_end == std::string_view::npos) line_end = text.size();
    std::string_view line = skip_blanks(text.substr(line_start, line_end - line_start));
    line_start = line_end + 1;
    if (line.empty() || line.front() != '#') continue;
    line = skip_blanks(line.substr(1));
    if (take_word(line, "pragma") && take_word(line, name)) found.push_back(line);
  }
  return found;
}

int shader_target(std::string_view program_text) {
  int highest = 0;
  for (std::string_view target : pragma_arguments(program_text, "target"))
    // X.Y: a digit, a point, a digit.
    if (target.size() >= 3 && std::isdigit(static_cast<unsigned char>(target[0])) && target[1] == '.' &&
        std::isdigit(static_cast<unsigned char>(target[2])))
      highest = std::max(highest, (target[0] - '0') * 10 + (target[2] - '0'));
  return highest > 0 ? highest : kDefaultShaderTarget;
}

std::string_view renderer_name(UnityPlatform platform) {
  switch (platform) {
    case UnityPlatform::GLCore: return "glcore";
    case UnityPlatform::D3D11: return "d3d11";
    case UnityPlatform::Vulkan: return "vulkan";
  }
  return "glcore";
}

std::optional<UnityPlatform> parse_unity_platform(std::string_view name) {
  for (UnityPlatform platform : {UnityPlatform::GLCore, UnityPlatform::D3D11, UnityPlatform::Vulkan})
    if (renderer_name(platform) == name) return platform;
  return std::nullopt;
}

bool direct3d_conventions(UnityPlatform platform) { return platform != UnityPlatform::GLCore; }

bool compiles_for_platform(std::string_view program_text, UnityPlatform platform) {
  const std::string_view renderer = renderer_name(platform);
  for (std::string_view only : pragma_arguments(program_text, "only_renderers"))
    if (!names_renderer(only, renderer)) return false;
  for (std::string_view excluded : pragma_arguments(program_text, "exclude_renderers"))
    if (names_renderer(excluded, renderer)) return false;
  return true;
}

std::vector<Define> unity_defines(std::string_view program_text, UnityPlatform platform) {
  // The platform, the target and the version; then the tier-3 desktop's graphics settings as
  // Unity's Graphics Settings have them by default (Standard shader quality High: BRDF1, box
  // projection and blending of reflection probes, detail normal maps, light probe proxy volumes,
  // full-HDR lightmaps). UNITY_COLORSPACE_GAMMA stays undefined: the renderer works in linear
  // colour, as a project set to Linear does.
  const char* api = platform == UnityPlatform::D3D11    ? "SHADER_API_D3D11"
                    : platform == UnityPlatform::Vulkan ? "SHADER_API_VULKAN"
                                                        : "SHADER_API_GLCORE";
  std::vector<Define> defines{{api, "1"},
                              {"SHADER_API_DESKTOP", "1"},
                              {"SHADER_TARGET", std::to_string(shader_target(program_text))},
                              {"UNITY_VERSION", std::to_string(kUnityVersion)},
                              {"UNITY_HARDWARE_TIER3", "1"},
                              {"UNITY_PBS_USE_BRDF1", "1"},
                              {"UNITY_SPECCUBE_BOX_PROJECTION", "1"},
                              {"UNITY_SPECCUBE_BLENDING", "1"},
                              {"UNITY_ENABLE_DETAIL_NORMALMAP", "1"},
                              {"UNITY_ENABLE_REFLECTION_BUFFERS", "1"},
                              {"UNITY_USE_DITHER_MASK_FOR_ALPHABLENDED_SHADOWS", "1"},
                              {"UNITY_LIGHT_PROBE_PROXY_VOLUME", "1"},
                              {"UNITY_LIGHTMAP_FULL_HDR", "1"},
                              // The main light's shadow is read from its shadow map at the pixel's world position, as
                              // Unity does where screen-space shadows are off, rather than collected from the camera's
                              // depth into a screen-space texture first (docs/unity.md, "Shadows").
                              {"UNITY_NO_SCREENSPACE_SHADOWS", "1"}};
  // Unity's compiler for Vulkan (HLSLcc) reads a texture type with a precision suffix
  // (Texture2D_half, sampler2D_float) as the type, its samples at that precision; HLSLSupport.cginc
  // defines them away only for the other platforms. Both are float here, as every half is.
  if (platform == UnityPlatform::Vulkan)
    for (const char* type : {"Texture2D", "Texture2DArray", "Texture2DMS", "TextureCube", "TextureCubeArray",
                             "Texture3D", "sampler2D", "samplerCUBE", "sampler3D"})
      for (const char* precision : {"_half", "_float"}) defines.push_back({std::string(type) + precision, type});
  return defines;
}

}  // namespace xshade::shaderlab
