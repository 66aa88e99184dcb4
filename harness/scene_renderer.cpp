#include "harness/scene_renderer.h"

#include <chrono>
#include <map>

#include <glm/gtc/matrix_transform.hpp>

#include "harness/meshes.h"
#include "harness/obj_mesh.h"
#include "harness/scene_textures.h"

namespace xshade::harness {
namespace {

using Values = std::map<std::string, std::vector<float>>;

// HLSL component order (row by row) of a GLM matrix: HLSL M[r][c] is GLM m[c][r], so that
// mul(M, v) in a shader is m * v on the host.
std::vector<float> hlsl_components(const glm::mat4& m) {
  std::vector<float> out;
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c) out.push_back(m[c][r]);
  return out;
}

std::vector<float> components(glm::vec4 v) { return {v.x, v.y, v.z, v.w}; }

// The renderer's own values, looked up first, then the scene's, then the shader's defaults.
class UniformValues {
 public:
  UniformValues(const Values& engine, const std::map<std::string, PropertyValue>& scene, const ShaderInterface& interface)
      : engine_(engine), interface_(interface) {
    for (const auto& [name, value] : scene)
      scene_[name] = std::vector<float>(value.components.begin(), value.components.begin() + value.count);
  }

  const std::vector<float>* operator()(const std::string& name) const {
    if (auto it = engine_.find(name); it != engine_.end()) return &it->second;
    if (auto it = scene_.find(name); it != scene_.end()) return &it->second;
    const PropertyDefault* property = interface_.find_property(name);
    if (property && !property->value.empty()) return &property->value;
    // X_TexelSize of a texture this pass does not read: it has no size, and the shader does not
    // use it (several passes of one effect share the buffer that declares it).
    static const std::vector<float> kNoTexture(4, 0.0f);
    if (name.ends_with("_TexelSize")) return &kNoTexture;
    return nullptr;
  }

 private:
  const Values& engine_;
  Values scene_;
  const ShaderInterface& interface_;
};

Result<std::vector<UniformBinding>> uniform_bindings(const CompiledVariant& variant, const UniformValues& values,
                                                     const std::string& where) {
  std::vector<UniformBinding> bindings;
  for (const UniformBlock& block : variant.interface.uniform_blocks) {
    auto bytes = build_uniform_block(block, [&values](const std::string& name) { return values(name); });
    if (!bytes) return fail(where + ": " + bytes.error().message);
    bindings.push_back({block.slot_name, std::move(*bytes)});
  }
  return bindings;
}

Result<MeshData> mesh_data(const MeshRef& mesh) {
  switch (mesh.kind) {
    case MeshKind::Sphere: return sphere_mesh();
    case MeshKind::Torus: return torus_mesh();
    case MeshKind::Plane: return plane_mesh();
    case MeshKind::Cube: return cube_mesh();
    case MeshKind::ObjFile: return load_obj(mesh.file);
  }
  return fail("unknown mesh kind");
}

class SceneRenderer {
 public:
  SceneRenderer(Backend& backend, const Scene& scene, const Plan& plan, const std::vector<CompiledVariant>& variants,
                const Environment& environment, const RenderOptions& options)
      : backend_(backend), scene_(scene), plan_(plan), variants_(variants), environment_(environment), options_(options) {}

  Result<RenderedScene> render() {
    auto target = backend_.create_target({scene_.width, scene_.height, true});
    if (!target) return fail(target.error());
    scene_target_ = *target;
    target_sizes_[target->id] = {scene_.width, scene_.height};
    // Every frame runs every pass; programs, meshes, textures and targets are made in the first.
    std::vector<double> frame_milliseconds;
    for (uint32_t frame = 0; frame < std::max(1u, options_.frames); ++frame) {
      timings_.clear();
      pass_images_.clear();
      color_ = scene_target_;
      current_effect_ = SIZE_MAX;
      for (size_t p = 0; p < plan_.passes.size(); ++p) {
        const PlannedPass& pass = plan_.passes[p];
        auto rendered = pass.kind == PlannedPass::Kind::Scene ? scene_pass() : post_pass(p);
        if (!rendered) return fail(rendered.error());
        if (options_.keep_pass_images) {
          auto image = backend_.read_color(color_);
          if (!image) return fail(image.error());
          pass_images_.emplace_back(pass.name, std::move(*image));
        }
      }
      double total = 0.0;
      for (const PassTiming& timing : timings_) total += timing.milliseconds;
      frame_milliseconds.push_back(total);
    }
    auto image = backend_.read_color(color_);
    if (!image) return fail(image.error());
    return RenderedScene{std::move(*image), std::move(timings_), std::move(pass_images_), std::move(frame_milliseconds)};
  }

 private:
  Result<ProgramHandle> program(size_t variant) {
    if (auto it = programs_.find(variant); it != programs_.end()) return it->second;
    auto created = backend_.create_program(variants_[variant].program);
    if (!created) return fail(created.error());
    programs_[variant] = *created;
    return *created;
  }

  Result<MeshHandle> mesh(const MeshRef& ref) {
    for (const auto& [known, handle] : meshes_)
      if (known == ref) return handle;
    auto data = mesh_data(ref);
    if (!data) return fail(data.error());
    auto handle = backend_.upload_mesh(*data);
    if (!handle) return fail(handle.error());
    meshes_.emplace_back(ref, *handle);
    return *handle;
  }

  Result<TextureHandle> texture(const TextureRef& ref) {
    for (const auto& [known, handle] : textures_)
      if (known == ref) return handle;
    auto image = texture_image(ref);
    if (!image) return fail(image.error());
    auto handle = backend_.upload_texture(texture_with_mips(*image));
    if (!handle) return fail(handle.error());
    textures_.emplace_back(ref, *handle);
    return *handle;
  }

  Result<TextureHandle> environment_texture() {
    if (!environment_handle_) {
      auto handle = backend_.upload_texture(environment_.prefiltered);
      if (!handle) return fail(handle.error());
      environment_handle_ = *handle;
    }
    return environment_handle_;
  }

  Values frame_values() const {
    const Camera& camera = scene_.camera;
    const float aspect = float(scene_.width) / float(scene_.height);
    // Direct3D's depth range [0, 1] in a right-handed world: what the backends' conventions expect.
    const glm::mat4 projection =
        glm::perspectiveRH_ZO(glm::radians(camera.fov_y_degrees), aspect, camera.near_plane, camera.far_plane);
    const glm::mat4 view = glm::lookAtRH(camera.position, camera.target, camera.up);
    Values values;
    values["_WorldToClip"] = hlsl_components(projection * view);
    values["_CameraPosition"] = components(glm::vec4(camera.position, 1.0f));
    // One directional light: the shaders take the first; a scene without one is lit by its environment alone.
    const DirectionalLight light = scene_.lights.empty() ? DirectionalLight{{0, 1, 0}, glm::vec3(0.0f), 0.0f}
                                                         : scene_.lights.front();
    values["_LightDirection"] = components(glm::vec4(light.direction, 0.0f));
    values["_LightColor"] = components(glm::vec4(light.color * light.intensity, 0.0f));
    std::vector<float>& sh = values["_EnvironmentSH"];
    for (const glm::vec3& c : environment_.sh) sh.insert(sh.end(), {c.r, c.g, c.b, 0.0f});
    values["_CameraNearFar"] = {camera.near_plane, camera.far_plane, 0.0f, 0.0f};
    return values;
  }

  Result<void> scene_pass() {
    RenderPass pass{scene_target_, scene_.clear_color, 1.0f, {}};
    Values values = frame_values();
    for (size_t i = 0; i < plan_.instances.size(); ++i) {
      const ObjectInstance& instance = plan_.instances[i];
      const size_t variant = plan_.instance_variant[i];
      const std::string where = "object '" + instance.object_name + "'" +
                                (instance.in_grid ? " cell " + std::to_string(instance.row) + "," + std::to_string(instance.col) : "");
      values["_ObjectToWorld"] = hlsl_components(instance.model);
      values["_NormalToWorld"] = hlsl_components(glm::transpose(glm::inverse(instance.model)));
      auto handle = program(variant);
      if (!handle) return fail(handle.error());
      auto mesh_handle = mesh(instance.mesh);
      if (!mesh_handle) return fail(where + ": " + mesh_handle.error().message);
      DrawItem draw{*handle, *mesh_handle, {}, {}};
      auto uniforms = uniform_bindings(variants_[variant], UniformValues(values, instance.properties, variants_[variant].interface), where);
      if (!uniforms) return fail(uniforms.error());
      draw.uniforms = std::move(*uniforms);
      for (const std::string& name : variants_[variant].interface.textures) {
        if (name == "_EnvironmentSpecular") {
          auto env = environment_texture();
          if (!env) return fail(env.error());
          // Clamped: the equirect's top and bottom rows are the poles, not neighbours.
          draw.textures.push_back({name, TextureSource::texture(*env, {Filter::Linear, AddressMode::ClampToEdge})});
          continue;
        }
        // An unset texture is white, as Unity's default for _MainTex.
        auto given = instance.textures.find(name);
        auto handle_of = texture(given != instance.textures.end() ? given->second : TextureRef{});
        if (!handle_of) return fail(where + ": texture '" + name + "': " + handle_of.error().message);
        draw.textures.push_back({name, TextureSource::texture(*handle_of, {Filter::Linear, AddressMode::Repeat})});
      }
      pass.draws.push_back(std::move(draw));
    }
    return timed("scene", pass);
  }

  Result<void> post_pass(size_t index) {
    const PlannedPass& planned = plan_.passes[index];
    const hlsl::PassDeclaration& declaration = planned.declaration;
    const PostEffect& effect = scene_.post[planned.effect];
    const bool half = declaration.scale == hlsl::PassDeclaration::Scale::Half;
    const uint32_t width = half ? std::max(1u, scene_.width / 2) : scene_.width;
    const uint32_t height = half ? std::max(1u, scene_.height / 2) : scene_.height;
    auto& target = pass_target_[index];
    if (!target) {
      auto created = backend_.create_target({width, height, false});
      if (!created) return fail(created.error());
      target = *created;
    }

    // An effect's first pass reads the image so far; scene.depth is always the scene pass's.
    if (planned.effect != current_effect_) {
      current_effect_ = planned.effect;
      effect_input_ = color_;
      pass_targets_.clear();
    }
    Values values = frame_values();
    const CompiledVariant& variant = variants_[planned.variant];
    DrawItem draw{{}, {}, {}, {}};
    for (const std::string& name : variant.interface.textures) {
      auto input = std::find_if(declaration.inputs.begin(), declaration.inputs.end(),
                                [&](const hlsl::PassInput& i) { return i.texture == name; });
      if (input == declaration.inputs.end())
        return fail("pass '" + planned.name + "' samples '" + name + "', which its #pragma pass gives no source");
      TargetHandle source = effect_input_;
      TextureSource binding;
      if (input->kind == hlsl::PassInput::Kind::SceneDepth) {
        source = scene_target_;
        binding = TextureSource::depth_of(source, {Filter::Nearest, AddressMode::ClampToEdge});
      } else {
        if (input->kind == hlsl::PassInput::Kind::Pass) source = pass_targets_.at(input->pass);
        binding = TextureSource::color_of(source, {Filter::Linear, AddressMode::ClampToEdge});
      }
      const glm::uvec2 size = target_sizes_.at(source.id);
      values[name + "_TexelSize"] = {1.0f / float(size.x), 1.0f / float(size.y), float(size.x), float(size.y)};
      draw.textures.push_back({name, binding});
    }
    auto handle = program(planned.variant);
    if (!handle) return fail(handle.error());
    draw.program = *handle;
    auto uniforms = uniform_bindings(variant, UniformValues(values, effect.parameters, variant.interface), "pass '" + planned.name + "'");
    if (!uniforms) return fail(uniforms.error());
    draw.uniforms = std::move(*uniforms);

    target_sizes_[target.id] = {width, height};
    RenderPass pass{target, glm::vec4(0.0f), 1.0f, {std::move(draw)}};
    if (auto rendered = timed(planned.name, pass); !rendered) return rendered;
    pass_targets_[declaration.name] = target;
    color_ = target;
    return {};
  }

  Result<void> timed(const std::string& name, const RenderPass& pass) {
    const auto start = std::chrono::steady_clock::now();
    if (auto rendered = backend_.render(pass); !rendered) return fail(name + ": " + rendered.error().message, rendered.error().where);
    const std::chrono::duration<double, std::milli> elapsed = std::chrono::steady_clock::now() - start;
    timings_.push_back({name, elapsed.count()});
    return {};
  }

  Backend& backend_;
  const Scene& scene_;
  const Plan& plan_;
  const std::vector<CompiledVariant>& variants_;
  const Environment& environment_;
  const RenderOptions& options_;

  TargetHandle scene_target_;
  TargetHandle color_;  // the image so far
  size_t current_effect_ = SIZE_MAX;
  TargetHandle effect_input_;
  std::map<std::string, TargetHandle> pass_targets_;  // of the current effect, by pass name
  std::map<uint32_t, glm::uvec2> target_sizes_;
  std::map<size_t, TargetHandle> pass_target_;  // by index into the plan's passes
  std::map<size_t, ProgramHandle> programs_;
  std::vector<std::pair<MeshRef, MeshHandle>> meshes_;
  std::vector<std::pair<TextureRef, TextureHandle>> textures_;
  TextureHandle environment_handle_;
  std::vector<PassTiming> timings_;
  std::vector<std::pair<std::string, FloatImage>> pass_images_;
};

}  // namespace

Result<RenderedScene> render_scene(Backend& backend, const Scene& scene, const Plan& plan,
                                   const std::vector<CompiledVariant>& variants, const Environment& environment,
                                   const RenderOptions& options) {
  return SceneRenderer(backend, scene, plan, variants, environment, options).render();
}

}  // namespace xshade::harness
