// The resources one piece of work made on a backend, destroyed together when the set goes out of
// scope (newest first), so that every early return of a render frees what it created.
#pragma once

#include <variant>
#include <vector>

#include "harness/backend/backend.h"

namespace xshade::harness {

class ResourceSet {
 public:
  explicit ResourceSet(Backend& backend) : backend_(backend) {}
  ~ResourceSet() { release(); }
  ResourceSet(const ResourceSet&) = delete;
  ResourceSet& operator=(const ResourceSet&) = delete;

  // Each creates on the backend and keeps the handle for destruction.
  Result<TargetHandle> create_target(const TargetDesc& desc);
  Result<MeshHandle> upload_mesh(const MeshData& mesh);
  Result<TextureHandle> upload_texture(const TextureData& texture);
  Result<ProgramHandle> create_program(const ProgramDesc& desc);

  // Destroys everything in the set now, newest first. Errors are dropped: each handle was made
  // here and is destroyed once, so the backend refuses none of them.
  void release();

 private:
  // Keeps what was made, for release.
  template <class Handle>
  Result<Handle> keep(Result<Handle> created) {
    if (created) handles_.emplace_back(*created);
    return created;
  }

  Backend& backend_;
  std::vector<std::variant<TargetHandle, MeshHandle, TextureHandle, ProgramHandle>> handles_;
};

}  // namespace xshade::harness
