// The semantics of entry point signatures (POSITION, TEXCOORD3, SV_Target1, DX9's VFACE ...):
// what each names, read case-insensitively as HLSL does. Sema checks them against the stage,
// reflection places them, and the GLSL emitter maps them to built-ins and locations.
#pragma once

#include <cstdint>
#include <string>

#include "hlsl_like/types.h"

namespace xshade::hlsl {

enum class SemanticKind : uint8_t {
  Unknown,
  Position,
  Normal,
  Tangent,
  Binormal,
  Texcoord,
  Color,
  SvPosition,
  SvTarget,
  SvDepth,
  SvIsFrontFace,
  SvVertexId,
  SvInstanceId,
  // Distances to user clip planes (a primitive is clipped where one is negative) and cull
  // distances (a primitive is dropped where every vertex's is negative): a float or floatN out of
  // the vertex stage, readable in the fragment stage; SV_ClipDistance0 and 1 (and the cull ones)
  // share eight components, packed in the order of their index (GLSL's gl_ClipDistance[]).
  SvClipDistance,
  SvCullDistance,
  // A fragment input: the rate the fragment is shaded at, Direct3D's D3D12_SHADING_RATE (log2 of
  // the width in bits 2-3, of the height in bits 0-1), which Vulkan's gl_ShadingRateEXT encodes alike.
  SvShadingRate,
  Vface,  // DX9's VFACE: a float, positive for a front face
  // Any other name that is not a system value (SV_...): HLSL's user-defined semantics
  // (PREVPOSITION, BITANGENT, VECTOR0), which name varyings and vertex inputs.
  User,
};
struct ParsedSemantic {
  SemanticKind kind = SemanticKind::Unknown;
  uint32_t index = 0;
  std::string user_name = {};  // User: the name in capitals, without its index
};
ParsedSemantic parse_semantic(const std::string& text);
// DX9's POSITION out of a vertex shader or into a fragment shader is the clip position
// (SV_Position) where it is POSITION0 of a float4, as fxc's compatibility mode reads it; any
// other POSITIONn there (a float, POSITION1) is an ordinary varying, as DXC reads it.
bool is_clip_position_alias(const ParsedSemantic& semantic, const Type& type);
std::string canonical_semantic(const ParsedSemantic& semantic);  // "TEXCOORD0", "SV_Target0"

}  // namespace xshade::hlsl
