#include "hlsl_like/vulkan_bindings.h"

#include <map>
#include <set>
#include <string>
#include <utility>

namespace xshade::hlsl {

const VulkanAttributes* given_binding(const Decl* decl) {
  const VulkanAttributes* vk = nullptr;
  if (decl && decl->kind == DeclKind::CBuffer) vk = &static_cast<const CBufferDecl*>(decl)->vk;
  if (decl && decl->kind == DeclKind::Var) vk = &static_cast<const VarDecl*>(decl)->vk;
  return vk && vk->binding ? vk : nullptr;
}

// DXC gives such a resource its binding and set outright; its register, if any, is Direct3D's.
void give_vulkan_bindings(Reflection& reflection, DiagnosticEngine& diagnostics) {
  enum Kind { kBuffer, kTexture, kSampler };
  struct Taken {
    std::string name;
    Kind kind;
    bool shared = false;
  };
  std::map<std::pair<uint32_t, uint32_t>, Taken> taken;
  auto give = [&](const Decl* decl, const std::string& name, Kind kind, bool used, uint32_t& binding, uint32_t& set) {
    const VulkanAttributes* vk = given_binding(decl);
    if (!vk) return;
    binding = *vk->binding;
    set = vk->set;
    if (!used) return;
    auto [known, inserted] = taken.emplace(std::pair{set, binding}, Taken{name, kind});
    if (inserted) return;
    if (known->second.kind == kTexture && kind == kSampler && !known->second.shared) {
      known->second.shared = true;
      return;
    }
    diagnostics.error(vk->loc, in_quotes(name) + " is at binding " + std::to_string(binding) + " of set " +
                                   std::to_string(set) + ", which " + in_quotes(known->second.name) +
                                   " already takes; give each resource a binding of its own");
  };
  for (ConstantBuffer& buffer : reflection.constant_buffers)
    give(buffer.decl, buffer.name, kBuffer, true, buffer.binding, buffer.set);
  for (TextureResource& texture : reflection.textures)
    give(texture.decl, texture.name, kTexture, texture.used, texture.binding, texture.set);
  for (SamplerResource& sampler : reflection.samplers)
    give(sampler.decl, sampler.name, kSampler, sampler.used, sampler.binding, sampler.set);
  for (StorageBufferResource& buffer : reflection.buffers)
    give(buffer.decl, buffer.name, kBuffer, buffer.used, buffer.binding, buffer.set);
  if (taken.empty()) return;
  // What has no [[vk::binding]] (a push-constant block's binding on gl, $Globals, a resource
  // without the attribute) moves off the numbers the attributes took in set 0.
  std::set<uint32_t> in_set_zero;
  for (const auto& [place, resource] : taken)
    if (place.first == 0) in_set_zero.insert(place.second);
  auto move_off = [&](const Decl* decl, uint32_t& binding) {
    if (given_binding(decl) || !in_set_zero.count(binding)) return;
    while (in_set_zero.count(binding)) ++binding;
    in_set_zero.insert(binding);
  };
  for (ConstantBuffer& buffer : reflection.constant_buffers) move_off(buffer.decl, buffer.binding);
  for (TextureResource& texture : reflection.textures) move_off(texture.decl, texture.binding);
  for (SamplerResource& sampler : reflection.samplers) move_off(sampler.decl, sampler.binding);
  for (StorageBufferResource& buffer : reflection.buffers) move_off(buffer.decl, buffer.binding);
}

}  // namespace xshade::hlsl
