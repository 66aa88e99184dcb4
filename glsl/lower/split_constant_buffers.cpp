// Constant-buffer members read as scalars (split_constant_buffers.h).
#include "glsl/lower/split_constant_buffers.h"

namespace xshade::glsl::lower {

using namespace hlsl;

ConstantBufferMembers split_constant_buffers(const Module& module) {
  ConstantBufferMembers members;
  // Constant-buffer members that std140 cannot place as vectors are read as scalars.
  for (const auto& decl : module.unit.decls) {
    if (!decl) continue;
    if (decl->kind == DeclKind::Var) members.by_name.emplace(decl->name, static_cast<const VarDecl*>(decl.get()));
    if (decl->kind == DeclKind::CBuffer)
      for (const auto& member : static_cast<const CBufferDecl&>(*decl).members)
        if (member) members.by_name.emplace(member->name, member.get());
  }
  for (const ConstantBuffer& buffer : module.reflection.constant_buffers) {
    for (const ConstantBufferMember& member : buffer.members) {
      if (!member.split_into_scalars) continue;
      if (auto it = members.by_name.find(member.name); it != members.by_name.end())
        members.split[it->second] = {member.type.scalar_type(), member.type.cols()};
    }
  }
  return members;
}

}  // namespace xshade::glsl::lower
