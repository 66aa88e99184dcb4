#include "hlsl_like/semantics.h"

#include <cctype>
#include <string_view>

namespace xshade::hlsl {

namespace {

// A name HLSL takes as a user-defined semantic: an identifier (its trailing digits the index)
// that no system value's SV_ prefix claims. Anything else is Unknown.
ParsedSemantic user_semantic(const std::string& text) {
  std::string upper;
  for (char c : text) {
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '_') return {};
    upper += char(std::toupper(static_cast<unsigned char>(c)));
  }
  size_t digits = upper.size();
  while (digits > 0 && std::isdigit(static_cast<unsigned char>(upper[digits - 1]))) --digits;
  if (digits == 0 || upper.size() - digits > 2 || upper.rfind("SV_", 0) == 0) return {};
  const uint32_t index = digits == upper.size() ? 0 : uint32_t(std::stoul(upper.substr(digits)));
  return {SemanticKind::User, index, upper.substr(0, digits)};
}

}  // namespace

ParsedSemantic parse_semantic(const std::string& text) {
  // No known semantic is longer than 14 letters and a 2-digit index: anything longer is Unknown,
  // and the rest fits a buffer on the stack (every entry point parameter and field comes here).
  constexpr size_t kLongest = 16;
  if (text.size() > kLongest) return user_semantic(text);
  char upper[kLongest];
  for (size_t i = 0; i < text.size(); ++i) upper[i] = char(std::toupper(static_cast<unsigned char>(text[i])));
  // Split a trailing decimal index.
  size_t digits = text.size();
  while (digits > 0 && std::isdigit(static_cast<unsigned char>(upper[digits - 1]))) --digits;
  const std::string_view base(upper, digits);
  const size_t number_length = text.size() - digits;
  if (number_length > 2) return {};
  uint32_t index = 0;
  for (size_t i = digits; i < text.size(); ++i) index = index * 10 + uint32_t(upper[i] - '0');
  struct Known {
    std::string_view name;
    SemanticKind kind;
    uint32_t max_index;  // 0: no index allowed
  };
  static constexpr Known kKnown[] = {
      {"POSITION", SemanticKind::Position, 15},
      {"NORMAL", SemanticKind::Normal, 15},
      {"TANGENT", SemanticKind::Tangent, 15},
      {"BINORMAL", SemanticKind::Binormal, 15},
      {"TEXCOORD", SemanticKind::Texcoord, 31},
      {"COLOR", SemanticKind::Color, 15},
      {"SV_POSITION", SemanticKind::SvPosition, 0},
      {"SV_TARGET", SemanticKind::SvTarget, 7},
      {"SV_DEPTH", SemanticKind::SvDepth, 0},
      {"SV_ISFRONTFACE", SemanticKind::SvIsFrontFace, 0},
      {"SV_VERTEXID", SemanticKind::SvVertexId, 0},
      {"SV_INSTANCEID", SemanticKind::SvInstanceId, 0},
      {"SV_CLIPDISTANCE", SemanticKind::SvClipDistance, 1},
      {"SV_CULLDISTANCE", SemanticKind::SvCullDistance, 1},
      {"SV_SHADINGRATE", SemanticKind::SvShadingRate, 0},
      // DX9's names, which Unity's HLSLSupport.cginc defines SV_Depth as on some APIs.
      {"DEPTH", SemanticKind::SvDepth, 0},
      {"VPOS", SemanticKind::SvPosition, 0},
      {"VFACE", SemanticKind::Vface, 0},
  };
  for (const Known& known : kKnown) {
    if (base != known.name) continue;
    if (number_length != 0 && index > known.max_index) return {};
    if (number_length != 0 && known.max_index == 0 && index != 0) return {};
    return {known.kind, index};
  }
  return user_semantic(text);
}

std::string canonical_semantic(const ParsedSemantic& semantic) {
  const char* base = "?";
  switch (semantic.kind) {
    case SemanticKind::Unknown: base = "?"; break;
    case SemanticKind::Position: base = "POSITION"; break;
    case SemanticKind::Normal: base = "NORMAL"; break;
    case SemanticKind::Tangent: base = "TANGENT"; break;
    case SemanticKind::Binormal: base = "BINORMAL"; break;
    case SemanticKind::Texcoord: base = "TEXCOORD"; break;
    case SemanticKind::Color: base = "COLOR"; break;
    case SemanticKind::SvPosition: return "SV_Position";
    case SemanticKind::SvTarget: base = "SV_Target"; break;
    case SemanticKind::SvDepth: return "SV_Depth";
    case SemanticKind::SvIsFrontFace: return "SV_IsFrontFace";
    case SemanticKind::SvVertexId: return "SV_VertexID";
    case SemanticKind::SvInstanceId: return "SV_InstanceID";
    case SemanticKind::SvClipDistance: base = "SV_ClipDistance"; break;
    case SemanticKind::SvCullDistance: base = "SV_CullDistance"; break;
    case SemanticKind::SvShadingRate: return "SV_ShadingRate";
    case SemanticKind::Vface: return "VFACE";
    case SemanticKind::User: return semantic.user_name + std::to_string(semantic.index);
  }
  return base + std::to_string(semantic.index);
}

bool is_clip_position_alias(const ParsedSemantic& semantic, const Type& type) {
  return semantic.kind == SemanticKind::Position && semantic.index == 0 && type.is_vector() && type.cols() == 4 &&
         type.is_floating();
}

}  // namespace xshade::hlsl
