#include "harness/backend.h"

#include <algorithm>
#include <cctype>
#include <type_traits>

namespace xshade::harness {

size_t bytes_per_texel(TextureFormat format) {
  switch (format) {
    case TextureFormat::Rgba8Unorm:
    case TextureFormat::Rgba8Srgb: return 4;
    case TextureFormat::Rgba32Float: return 16;
  }
  return 0;
}

namespace {

// Fills `matched` (one entry per slot) from `bindings`, by name.
template <class Slot, class Binding>
Result<void> match_by_name(const std::vector<Slot>& slots, const std::vector<Binding>& bindings,
                           std::vector<const Binding*>& matched, const char* kind,
                           const std::string& where) {
  matched.assign(slots.size(), nullptr);
  for (const Binding& binding : bindings) {
    auto slot = std::find_if(slots.begin(), slots.end(), [&](const Slot& s) { return s.name == binding.name; });
    if (slot == slots.end())
      return fail(where + ": the program has no " + kind + " named '" + binding.name + "'");
    if constexpr (std::is_same_v<Binding, UniformBinding>) {
      if (binding.bytes.size() != slot->size)
        return fail(where + ": " + kind + " '" + binding.name + "' needs " + std::to_string(slot->size) +
                    " bytes but " + std::to_string(binding.bytes.size()) + " were bound");
    }
    const auto index = size_t(slot - slots.begin());
    if (matched[index]) return fail(where + ": " + kind + " '" + binding.name + "' is bound twice");
    matched[index] = &binding;
  }
  for (size_t i = 0; i < slots.size(); ++i)
    if (!matched[i]) return fail(where + ": " + kind + " '" + slots[i].name + "' is not bound");
  return {};
}

}  // namespace

Result<void> validate_mesh(const MeshData& mesh) {
  if (mesh.vertices.empty() || mesh.indices.empty())
    return fail("upload_mesh: the mesh is empty (" + std::to_string(mesh.vertices.size()) + " vertices, " +
                std::to_string(mesh.indices.size()) + " indices)");
  if (mesh.indices.size() % 3 != 0)
    return fail("upload_mesh: " + std::to_string(mesh.indices.size()) + " indices is not a whole number of triangles");
  for (size_t i = 0; i < mesh.indices.size(); ++i)
    if (mesh.indices[i] >= mesh.vertices.size())
      return fail("upload_mesh: index " + std::to_string(mesh.indices[i]) + " (at position " + std::to_string(i) +
                  ") is out of range for " + std::to_string(mesh.vertices.size()) + " vertices");
  return {};
}

Result<MatchedBindings> match_bindings(const ProgramLayout& layout, const DrawItem& draw,
                                       const std::string& where) {
  MatchedBindings matched;
  if (auto ok = match_by_name(layout.uniform_blocks, draw.uniforms, matched.uniforms, "uniform block", where); !ok)
    return fail(ok.error());
  if (auto ok = match_by_name(layout.textures, draw.textures, matched.textures, "texture", where); !ok)
    return fail(ok.error());
  return matched;
}

std::string llvm_version_of(const std::string& renderer) {
  const size_t at = renderer.find("LLVM ");
  if (at == std::string::npos) return {};
  size_t end = at + 5;
  while (end < renderer.size() &&
         (std::isdigit(static_cast<unsigned char>(renderer[end])) || renderer[end] == '.'))
    ++end;
  std::string version = renderer.substr(at + 5, end - at - 5);
  while (!version.empty() && version.back() == '.') version.pop_back();
  return version;
}

}  // namespace xshade::harness
