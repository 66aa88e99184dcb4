#include "harness/backend/resource_set.h"

namespace xshade::harness {

Result<TargetHandle> ResourceSet::create_target(const TargetDesc& desc) { return keep(backend_.create_target(desc)); }

Result<MeshHandle> ResourceSet::upload_mesh(const MeshData& mesh) { return keep(backend_.upload_mesh(mesh)); }

Result<TextureHandle> ResourceSet::upload_texture(const TextureData& texture) {
  return keep(backend_.upload_texture(texture));
}

Result<ProgramHandle> ResourceSet::create_program(const ProgramDesc& desc) {
  return keep(backend_.create_program(desc));
}

void ResourceSet::release() {
  while (!handles_.empty()) {
    std::visit([this](auto handle) { (void)backend_.destroy(handle); }, handles_.back());
    handles_.pop_back();
  }
}

}  // namespace xshade::harness
