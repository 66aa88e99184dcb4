#include "hlsl_like/semantics.h"

#include <cctype>

namespace xshade::hlsl {

ParsedSemantic parse_semantic(const std::string& text) {
  std::string upper;
  for (char c : text) upper += char(std::toupper(static_cast<unsigned char>(c)));
  // Split a trailing decimal index.
  size_t digits = upper.size();
  while (digits > 0 && std::isdigit(static_cast<unsigned char>(upper[digits - 1]))) --digits;
  const std::string base = upper.substr(0, digits);
  const std::string number = upper.substr(digits);
  if (number.size() > 2) return {};
  const uint32_t index = number.empty() ? 0 : uint32_t(std::stoul(number));
  struct Known {
    const char* name;
    SemanticKind kind;
    uint32_t max_index;  // 0: no index allowed
  };
  static constexpr Known kKnown[] = {
      {"POSITION", SemanticKind::Position, 15},   {"NORMAL", SemanticKind::Normal, 15},
      {"TANGENT", SemanticKind::Tangent, 15},     {"BINORMAL", SemanticKind::Binormal, 15},
      {"TEXCOORD", SemanticKind::Texcoord, 31},   {"COLOR", SemanticKind::Color, 15},
      {"SV_POSITION", SemanticKind::SvPosition, 0}, {"SV_TARGET", SemanticKind::SvTarget, 7},
      {"SV_DEPTH", SemanticKind::SvDepth, 0},     {"SV_ISFRONTFACE", SemanticKind::SvIsFrontFace, 0},
      {"SV_VERTEXID", SemanticKind::SvVertexId, 0}, {"SV_INSTANCEID", SemanticKind::SvInstanceId, 0},
      // DX9's names, which Unity's HLSLSupport.cginc defines SV_Depth as on some APIs.
      {"DEPTH", SemanticKind::SvDepth, 0},        {"VPOS", SemanticKind::SvPosition, 0},
      {"VFACE", SemanticKind::Vface, 0},
  };
  for (const Known& known : kKnown) {
    if (base != known.name) continue;
    if (!number.empty() && index > known.max_index) return {};
    if (!number.empty() && known.max_index == 0 && index != 0) return {};
    return {known.kind, index};
  }
  return {};
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
    case SemanticKind::Vface: return "VFACE";
  }
  return base + std::to_string(semantic.index);
}

}  // namespace xshade::hlsl
