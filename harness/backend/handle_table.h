// A backend's objects of one kind by handle: what every backend's targets, meshes, textures and
// programs live in, so that look-up, its error and destruction are written once.
//
// Ids count up from 1 and are never given out twice, so a handle kept after its object was
// destroyed is refused ("no such ...") rather than reaching an object made later.
#pragma once

#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <utility>

#include "base/result.h"
#include "harness/backend/backend.h"

namespace xshade::harness {

template <class HandleType, class Object>
class HandleTable {
 public:
  // `kind` names the objects in errors: "target", "mesh", "texture", "program".
  explicit HandleTable(const char* kind) : kind_(kind) {}

  // The handle the next insert returns, for names given before the object exists.
  HandleType next_handle() const { return HandleType{next_id_}; }

  HandleType insert(std::unique_ptr<Object> object) {
    const uint32_t id = next_id_++;
    objects_.emplace(id, std::move(object));
    return HandleType{id};
  }

  // The object, or null when the handle is empty, never given out or destroyed.
  Object* get(HandleType handle) const {
    auto found = objects_.find(handle.id);
    return found == objects_.end() ? nullptr : found->second.get();
  }

  // The object, or an error "<where>: no such <kind> (handle <id>)".
  Result<Object*> find(HandleType handle, const std::string& where) const {
    if (Object* object = get(handle)) return object;
    return fail(ErrorKind::Internal, unknown(handle, where));
  }

  // Destroys the object now. An empty, unknown or already destroyed handle is an error, so that a
  // caller who frees a resource twice hears of it.
  Result<void> erase(HandleType handle, const std::string& where) {
    auto found = objects_.find(handle.id);
    if (found == objects_.end()) return fail(ErrorKind::Internal, unknown(handle, where));
    objects_.erase(found);
    return {};
  }

  void clear() { objects_.clear(); }
  size_t size() const { return objects_.size(); }

 private:
  std::string unknown(HandleType handle, const std::string& where) const {
    return where + ": no such " + kind_ + " (handle " + std::to_string(handle.id) + ")";
  }

  const char* kind_;
  std::map<uint32_t, std::unique_ptr<Object>> objects_;
  uint32_t next_id_ = 1;
};

// A backend's four tables. Declared in teardown order reversed: programs go first, targets last.
template <class Target, class Mesh, class Texture, class Program>
struct BackendObjects {
  HandleTable<TargetHandle, Target> targets{"target"};
  HandleTable<MeshHandle, Mesh> meshes{"mesh"};
  HandleTable<TextureHandle, Texture> textures{"texture"};
  HandleTable<ProgramHandle, Program> programs{"program"};

  void clear() {
    programs.clear();
    textures.clear();
    meshes.clear();
    targets.clear();
  }
};

}  // namespace xshade::harness
