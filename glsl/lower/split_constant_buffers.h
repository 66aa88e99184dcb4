// Lowering: constant-buffer members split into scalars. HLSL packs a vector wherever it fits in a
// 16-byte register (a float2 at offset 4, after a float); std140 aligns a vec2 to 8 bytes, so
// such a member is declared as scalars (_Offset_0, _Offset_1) and read back into a vector
// (reflection's ConstantBufferMember::split_into_scalars says which).
#pragma once

#include <cstdint>
#include <string_view>
#include <unordered_map>

#include "hlsl_like/compiler.h"

namespace xshade::glsl::lower {

struct SplitMember {
  hlsl::ScalarType scalar;
  uint32_t count;  // the vector's components, one scalar member each
};

struct ConstantBufferMembers {
  // Every constant-buffer member and loose global by name, viewing the tree's strings.
  std::unordered_map<std::string_view, const hlsl::VarDecl*> by_name;
  // The members read as scalars.
  std::unordered_map<const hlsl::Decl*, SplitMember> split;
};

ConstantBufferMembers split_constant_buffers(const hlsl::Module& module);

}  // namespace xshade::glsl::lower
