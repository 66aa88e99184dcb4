// A RenderPass turned into resolved draws before any driver sees it, the same way on every backend:
// the target, each draw's program and mesh (none for a full-screen program), its bindings matched
// to the program's layout by name (match_bindings), and each texture source resolved to an
// uploaded texture or a target's colour or depth, checked against its slot (check_bound_texture).
// A backend supplies only its own object types and what is specific to its API (a callback per
// bound texture).
#pragma once

#include <string>
#include <vector>

#include "harness/backend/backend.h"
#include "harness/backend/handle_table.h"

namespace xshade::harness {

// "texture 3", "the colour of target 2", "the depth of target 2": how errors name a source.
std::string source_label(const TextureSource& source);

template <class Texture>
struct BoundTexture {
  Texture* texture = nullptr;
  SamplerDesc sampler;
  bool of_target = false;  // a target's colour or depth (rendered earlier), not an upload
};

template <class Program, class Mesh, class Texture>
struct ResolvedDraw {
  Program* program = nullptr;
  Mesh* mesh = nullptr;                                      // null for a full-screen program
  std::vector<const UniformBinding*> uniforms;               // per layout uniform block
  std::vector<BoundTexture<Texture>> textures;               // per layout texture slot
  std::vector<const StorageBufferBinding*> storage_buffers;  // per layout storage buffer
};

template <class Target, class Program, class Mesh, class Texture>
struct ResolvedPass {
  Target* target = nullptr;
  std::vector<ResolvedDraw<Program, Mesh, Texture>> draws;
};

// No extra check per bound texture.
struct NoTextureCheck {
  template <class... Args>
  Result<void> operator()(const Args&...) const {
    return {};
  }
};

// Resolves `pass` against a backend's objects. Program needs `name`, `layout`, `fullscreen`;
// Target needs `color` (a Texture) and `depth` (an optional Texture); `facts(texture)` gives a
// texture's shape and format as a std::pair. `check(layout, index, binding, bound, earlier, where)`
// runs after the shared checks of the texture bound to slot `index` of the program's layout,
// `earlier` being the draw's textures of the slots before it.
// `what` names the pass in every error ("render into target 3").
template <class Target, class Mesh, class Texture, class Program, class Facts, class Check = NoTextureCheck>
Result<ResolvedPass<Target, Program, Mesh, Texture>> resolve_pass(
    BackendObjects<Target, Mesh, Texture, Program>& objects, const RenderPass& pass, const std::string& what,
    Facts&& facts, Check&& check = {}) {
  ResolvedPass<Target, Program, Mesh, Texture> resolved;
  resolved.target = objects.targets.get(pass.target);
  if (!resolved.target) return fail(ErrorKind::Internal, what + ": no such target");
  for (size_t i = 0; i < pass.draws.size(); ++i) {
    const DrawItem& item = pass.draws[i];
    ResolvedDraw<Program, Mesh, Texture> draw;
    auto program = objects.programs.find(item.program, what + ": draw " + std::to_string(i));
    if (!program) return fail(program.error());
    draw.program = *program;
    const std::string where = what + ": draw " + std::to_string(i) + " (program '" + draw.program->name + "')";
    if (!draw.program->fullscreen) {
      auto mesh = objects.meshes.find(item.mesh, where);
      if (!mesh) return fail(mesh.error());
      draw.mesh = *mesh;
    }
    const ProgramLayout& layout = draw.program->layout;
    auto matched = match_bindings(layout, item, where);
    if (!matched) return fail(matched.error());
    draw.uniforms = std::move(matched->uniforms);
    draw.storage_buffers = std::move(matched->storage_buffers);

    for (size_t index = 0; index < layout.textures.size(); ++index) {
      const TextureBinding& binding = *matched->textures[index];
      const TextureSource& source = binding.source;
      const std::string bound_to = where + ": texture '" + binding.name + "'";
      const std::string handle = " (handle " + std::to_string(source.id) + ")";
      const std::string target_id = "target " + std::to_string(source.id);
      Texture* texture = nullptr;
      if (source.kind == TextureSource::Kind::Texture) {
        texture = objects.textures.get(TextureHandle{source.id});
        if (!texture) return fail(ErrorKind::Internal, bound_to + " is bound to a missing texture" + handle);
      } else {
        Target* sampled = objects.targets.get(TargetHandle{source.id});
        if (!sampled) return fail(ErrorKind::Internal, bound_to + " is bound to a missing target" + handle);
        if (sampled == resolved.target)
          return fail(ErrorKind::Internal, bound_to + " samples " + target_id +
                                               ", which the pass renders into: a pass cannot sample its own target");
        if (source.kind == TextureSource::Kind::TargetDepth && !sampled->depth)
          return fail(ErrorKind::Internal, bound_to + " samples the depth of " + target_id + ", which has no depth");
        texture = source.kind == TextureSource::Kind::TargetColor ? &sampled->color : &*sampled->depth;
      }
      const auto [shape, format] = facts(*texture);
      if (auto fits =
              check_bound_texture(layout.textures[index], {shape, format, source_label(source)}, source.sampler, where);
          !fits)
        return fail(fits.error());
      // A slot the shader filters itself is read nearest, whatever the filter asked for.
      SamplerDesc sampler = source.sampler;
      if (layout.textures[index].filtered_in_shader) sampler.filter = Filter::Nearest;
      const BoundTexture<Texture> bound{texture, sampler, source.kind != TextureSource::Kind::Texture};
      if (auto checked = check(layout, index, binding, bound, draw.textures, where); !checked)
        return fail(checked.error());
      draw.textures.push_back(bound);
    }
    resolved.draws.push_back(std::move(draw));
  }
  return resolved;
}

}  // namespace xshade::harness
