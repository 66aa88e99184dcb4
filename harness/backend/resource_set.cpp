#include "harness/backend/resource_set.h"

namespace xshade::harness {

Result<TargetHandle> ResourceSet::create_target(const TargetDesc& desc) {
  auto created = backend_.create_target(desc);
  if (created) handles_.emplace_back(*created);
  return created;
}

Result<MeshHandle> ResourceSet::upload_mesh(const MeshData& mesh) {
  auto created = backend_.upload_mesh(mesh);
  if (created) handles_.emplace_back(*created);
  return created;
}

Result<TextureHandle> ResourceSet::upload_texture(const TextureData& texture) {
  auto created = backend_.upload_texture(texture);
  if (created) handles_.emplace_back(*created);
  return created;
}

Result<ProgramHandle> ResourceSet::create_program(const ProgramDesc& desc) {
  auto created = backend_.create_program(desc);
  if (created) handles_.emplace_back(*created);
  return created;
}

void ResourceSet::release() {
  while (!handles_.empty()) {
    std::visit([this](auto handle) { (void)backend_.destroy(handle); }, handles_.back());
    handles_.pop_back();
  }
}

}  // namespace xshade::harness
