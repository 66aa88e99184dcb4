#include "harness/render/scene_renderer.h"

#include <algorithm>
#include <chrono>
#include <deque>
#include <map>

#include "harness/assets/cube_map.h"
#include "harness/assets/meshes.h"
#include "harness/assets/obj_mesh.h"
#include "harness/assets/scene_textures.h"
#include "harness/backend/resource_set.h"
#include "harness/render/forward_lights.h"
#include "harness/render/material_source.h"
#include "harness/render/renderer_inputs.h"
#include "harness/render/scene_buffers.h"
#include "harness/render/shadow_map.h"
#include "harness/render/unity_render_state.h"

namespace xshade::harness {
namespace {

using Values = UniformValueMap;

// A backend's failure is the driver's or xshade's, never the scene's: what the backends are given
// has been checked (the plan's contract, the assets read before they are uploaded).
Error from_backend(Error error) {
  if (error.kind == ErrorKind::UserInput) error.kind = ErrorKind::Backend;
  return error;
}

// The error with what was being done in front of its message; its kind and location kept.
Error in_context(const std::string& context, Error error) {
  error.message = context + ": " + error.message;
  return error;
}

// An asset's error at the scene value that named it, where the asset has no line of its own (a
// missing or unreadable file: the message names the file, the location is the line to fix).
Error at_scene_value(Error error, const SourceLocation& where) {
  if (error.where.line == 0 && where.known()) error.where = where;
  return error;
}

// The renderer's own values, looked up first, then the scene's, then the shader's defaults.
class UniformValues {
 public:
  UniformValues(const Values& engine, const std::map<std::string, PropertyValue>& scene,
                const ShaderInterface& interface)
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
    // X_ST, a texture's tiling and offset that neither the scene nor the shader gives: Unity's
    // default, no tiling and no offset.
    static const std::vector<float> kNoTiling{1.0f, 1.0f, 0.0f, 0.0f};
    if (name.ends_with("_ST")) return &kNoTiling;
    // X_HDR, texture X's decode instructions for Unity's DecodeHDR: decode nothing (multiplier 1,
    // exponent 1, alpha unused), since xshade's textures hold their values, not RGBM or dLDR.
    static const std::vector<float> kNoDecoding{1.0f, 1.0f, 0.0f, 0.0f};
    if (name.ends_with("_HDR")) return &kNoDecoding;
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
    if (!bytes) return fail(bytes.error().kind, where + ": " + bytes.error().message);
    bindings.push_back({block.name, std::move(*bytes)});
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
  return fail(ErrorKind::Internal, "unknown mesh kind");
}

// Post passes sample colour bilinear and depth exactly, both clamped at the edges
// (docs/shader_library.md).
constexpr SamplerDesc kColorSampler{Filter::Linear, AddressMode::ClampToEdge};
constexpr SamplerDesc kDepthSampler{Filter::Nearest, AddressMode::ClampToEdge};

// An image a post pass can read: its binding (a target's colour or depth, or an uploaded
// texture, with its sampler) and its size, for X_TexelSize.
struct PassSource {
  TextureSource binding;
  glm::uvec2 size{0};
};

// One RGBA32F level, as given: a post pass reads level 0 only.
TextureData float_texture(const FloatImage& image) {
  return {TextureFormat::Rgba32Float, image.width, image.height, {float_bytes(image)}};
}

// Whether a material or post effect of the scene is a Unity .shader.
bool draws_unity_shader(const Scene& scene) {
  return std::any_of(scene.objects.begin(), scene.objects.end(),
                     [](const SceneObject& object) { return is_unity_shader(object.material); }) ||
         std::any_of(scene.post.begin(), scene.post.end(),
                     [](const PostEffect& effect) { return is_unity_shader(effect.effect); });
}

class SceneRenderer {
 public:
  SceneRenderer(Backend& backend, const Scene& scene, const Plan& plan, const std::vector<CompiledVariant>& variants,
                const Environment& environment, const RenderOptions& options)
      : backend_(backend),
        scene_(scene),
        plan_(plan),
        variants_(variants),
        environment_(environment),
        options_(options) {}

  // The scene pass, then the post passes on its colour and depth.
  Result<RenderedScene> render() {
    // A stencil buffer only where a draw tests stencil (Unity's camera target always has one,
    // cleared to 0 as here, so a shader sees the same).
    const bool stencil = std::any_of(plan_.instance_draws.begin(), plan_.instance_draws.end(), [](const auto& draws) {
      return std::any_of(draws.begin(), draws.end(),
                         [](const Plan::InstanceDraw& draw) { return draw.state.stencil.enabled; });
    });
    auto target = resources_.create_target({scene_.width, scene_.height, true, options_.trace_nonfinite, stencil});
    if (!target) return fail(from_backend(target.error()));
    scene_target_ = *target;
    const glm::uvec2 size{scene_.width, scene_.height};
    scene_color_ = {TextureSource::color_of(*target, kColorSampler), size};
    scene_depth_ = {TextureSource::depth_of(*target, kDepthSampler), size};
    return render_passes();
  }

  // The post passes alone, on the given colour and depth.
  Result<RenderedScene> render_post(const FloatImage& color, const FloatImage& depth) {
    if (rows_bottom_first_)
      return fail(ErrorKind::UserInput,
                  "post passes on given images draw only in scenes of xshade's own shaders: the images are upright, "
                  "their depth 0 at the near plane");
    for (const auto& [name, image] : {std::pair{"colour", &color}, std::pair{"depth", &depth}}) {
      const bool fits = image->width == scene_.width && image->height == scene_.height &&
                        image->rgba.size() == size_t(image->width) * image->height * 4;
      if (!fits)
        return fail(ErrorKind::UserInput, std::string("the ") + name + " image is " + std::to_string(image->width) +
                                              "x" + std::to_string(image->height) + ", the scene " +
                                              std::to_string(scene_.width) + "x" + std::to_string(scene_.height));
    }
    if (std::none_of(plan_.passes.begin(), plan_.passes.end(),
                     [](const PlannedPass& pass) { return pass.kind == PlannedPass::Kind::Post; }))
      return fail(ErrorKind::UserInput, "scene '" + scene_.name + "' has no post pass to run on the given images");
    auto color_texture = resources_.upload_texture(float_texture(color));
    if (!color_texture) return fail(from_backend(color_texture.error()));
    auto depth_texture = resources_.upload_texture(float_texture(depth));
    if (!depth_texture) return fail(from_backend(depth_texture.error()));
    const glm::uvec2 size{scene_.width, scene_.height};
    scene_color_ = {TextureSource::texture(*color_texture, kColorSampler), size};
    scene_depth_ = {TextureSource::texture(*depth_texture, kDepthSampler), size};
    return render_passes();
  }

 private:
  // Every frame runs every pass; programs, meshes, textures and targets are made in the first.
  // Without a scene target (render_post) the scene pass is not run.
  Result<RenderedScene> render_passes() {
    std::vector<std::vector<PassTiming>> frame_timings;
    for (uint32_t frame = 0; frame < std::max(1u, options_.frames); ++frame) {
      timings_.clear();
      pass_images_.clear();
      traces_.clear();
      current_ = scene_color_;
      current_effect_ = SIZE_MAX;
      for (size_t p = 0; p < plan_.passes.size(); ++p) {
        const PlannedPass& pass = plan_.passes[p];
        if (pass.kind == PlannedPass::Kind::Scene && !scene_target_) continue;
        auto rendered = pass.kind == PlannedPass::Kind::Scene ? scene_pass() : post_pass(p);
        if (!rendered) return fail(rendered.error());
        if (options_.keep_pass_images) {
          auto image = read_current();
          if (!image) return fail(image.error());
          pass_images_.emplace_back(pass.name, std::move(*image));
        }
        if (options_.trace_nonfinite) {
          auto record = backend_.read_second_color(TargetHandle{current_.binding.id});
          if (!record) return fail(from_backend(record.error()));
          traces_.push_back({pass.name, upright(std::move(*record))});
        }
      }
      frame_timings.push_back(timings_);
    }
    auto image = read_current();
    if (!image) return fail(image.error());
    return RenderedScene{std::move(*image), std::move(timings_), std::move(pass_images_), std::move(frame_timings),
                         std::move(traces_)};
  }

  // The image so far is always a target's colour once a pass has run: the scene pass's or a
  // post pass's.
  Result<FloatImage> read_current() {
    if (current_.binding.kind != TextureSource::Kind::TargetColor)
      return fail(ErrorKind::Internal, "no pass has rendered an image to read");
    auto image = backend_.read_color(TargetHandle{current_.binding.id});
    if (!image) return fail(from_backend(image.error()));
    return upright(std::move(*image));
  }

  // A target's image as the picture stands: a scene of Unity's shaders keeps its targets' rows
  // bottom first, as Unity does on every platform, and its last blit to the screen turns them
  // round as this does.
  FloatImage upright(FloatImage image) const {
    if (rows_bottom_first_) flip_rows(image);
    return image;
  }

  Result<ProgramHandle> program(size_t variant) {
    if (auto it = programs_.find(variant); it != programs_.end()) return it->second;
    auto created = options_.programs ? options_.programs->program(backend_, variants_[variant].program)
                                     : resources_.create_program(variants_[variant].program);
    if (!created) return fail(from_backend(created.error()));
    programs_[variant] = *created;
    return *created;
  }

  // A mesh the scene names, read and uploaded once, with its object-space bounds (a shadow map's
  // view is fitted to them).
  struct SceneMesh {
    MeshRef ref;
    MeshHandle handle;
    std::pair<glm::vec3, glm::vec3> box;
  };
  Result<const SceneMesh*> scene_mesh(const MeshRef& ref) {
    for (const SceneMesh& known : meshes_)
      if (known.ref == ref) return &known;
    auto data = mesh_data(ref);
    if (!data) return fail(at_scene_value(data.error(), ref.where));
    auto handle = resources_.upload_mesh(*data);
    if (!handle) return fail(from_backend(handle.error()));
    glm::vec3 low(std::numeric_limits<float>::max()), high(-std::numeric_limits<float>::max());
    for (const Vertex& vertex : data->vertices) {
      low = glm::min(low, vertex.position);
      high = glm::max(high, vertex.position);
    }
    return &meshes_.emplace_back(SceneMesh{ref, *handle, {low, high}});
  }

  Result<MeshHandle> mesh(const MeshRef& ref) {
    auto known = scene_mesh(ref);
    if (!known) return fail(known.error());
    return (*known)->handle;
  }

  struct SceneTexture {
    TextureRef ref;
    TextureShape shape;
    TextureHandle handle;
    glm::uvec2 size{0};
  };
  // A texture the scene names, made for the shape the shader declares (scene_textures.h); the
  // environment is the renderer's own cube.
  Result<SceneTexture> texture(const TextureRef& ref, TextureShape shape) {
    for (const SceneTexture& known : textures_)
      if (known.ref == ref && known.shape == shape) return known;
    if (ref.source == TextureOrigin::Environment) {
      if (shape != TextureShape{TextureDimension::Cube, false})
        return fail(ErrorKind::UserInput, "the environment is a cube map; the shader declares a " + shape_name(shape),
                    ref.where);
      auto cube = environment_cube();
      if (!cube) return fail(cube.error());
      return textures_.emplace_back(
          SceneTexture{ref, shape, *cube, {environment_.prefiltered.width / 4, environment_.prefiltered.width / 4}});
    }
    auto data = texture_data(ref, shape);
    if (!data) {
      // The file's own location where it has one (a .cube file's line), else the scene's value.
      return fail(at_scene_value(data.error(), ref.where));
    }
    auto handle = resources_.upload_texture(*data);
    if (!handle) return fail(from_backend(handle.error()));
    return textures_.emplace_back(SceneTexture{ref, shape, *handle, {data->width, data->height}});
  }

  // The sampler of a texture the scene gives: a material's 2D texture repeats; a cube map's faces
  // meet without wrapping either way; a 3D LUT and anything a post pass reads clamp at the edges.
  static SamplerDesc scene_sampler(TextureShape shape, bool post) {
    const bool repeat = !post && shape.dimension == TextureDimension::Tex2D;
    return {Filter::Linear, repeat ? AddressMode::Repeat : AddressMode::ClampToEdge};
  }

  static TextureShape declared_shape(const CompiledVariant& variant, const std::string& name) {
    for (const TextureSlot& slot : variant.program.layout.textures)
      if (slot.name == name) return slot.shape;
    return {};
  }

  // Positions (-1, -1), (-1, 3), (3, -1) at z = 0: one triangle over the whole target; its uv 0
  // to 1 across the target from the corner that lands on row 0, where uv (0, 0) addresses a
  // target's row 0 (docs/architecture.md), so that a blit that samples its source at the mesh's uv
  // copies it as it is, as Graphics.Blit's quad does. That corner is the top-left one in xshade's
  // own orientation; where the rows go bottom first (OpenGL's row order, or Direct3D's blit
  // projection that flips y) the bottom-left one, where Unity's quad has uv (0, 0).
  Result<MeshHandle> fullscreen_triangle() {
    if (!triangle_) {
      MeshData mesh;
      for (glm::vec2 p : {glm::vec2(-1.0f, -1.0f), glm::vec2(-1.0f, 3.0f), glm::vec2(3.0f, -1.0f)}) {
        Vertex vertex{glm::vec3(p, 0.0f)};
        vertex.uv = glm::vec2(0.5f * (p.x + 1.0f), 0.5f * (rows_bottom_first_ ? 1.0f + p.y : 1.0f - p.y));
        mesh.vertices.push_back(vertex);
      }
      mesh.indices = {0, 1, 2};
      auto handle = resources_.upload_mesh(mesh);
      if (!handle) return fail(from_backend(handle.error()));
      triangle_ = *handle;
    }
    return triangle_;
  }

  Result<TextureHandle> environment_texture() {
    if (!environment_handle_) {
      auto handle = resources_.upload_texture(environment_.prefiltered);
      if (!handle) return fail(from_backend(handle.error()));
      environment_handle_ = *handle;
    }
    return environment_handle_;
  }

  // The environment as a cube map of the same prefiltered levels, made the first time a shader
  // samples a reflection probe.
  Result<TextureHandle> environment_cube() {
    if (!environment_cube_) {
      auto handle = resources_.upload_texture(cube_from_prefiltered(environment_.prefiltered));
      if (!handle) return fail(from_backend(handle.error()));
      environment_cube_ = *handle;
    }
    return environment_cube_;
  }

  // A texture the renderer itself gives a shader, by its name: the environment (xshade's
  // equirect, Unity's reflection probes), the main light's shadow map where the plan draws one,
  // the attenuation textures of `light`, the light the draw is lit by (its type, and its shadows'
  // filter for its map). Nothing for any other name.
  Result<std::optional<TextureSource>> engine_texture(const std::string& name, const Light& light,
                                                      std::optional<TargetHandle> shadow_map = std::nullopt) {
    // Clamped: the equirect's top and bottom rows are the poles, not neighbours; a cube's
    // faces meet without wrapping either way; a light's falloff ends at its last texel.
    const SamplerDesc clamped{Filter::Linear, AddressMode::ClampToEdge};
    // The shadow map's depth, compared (LEqual: lit where the pixel is no farther from the light
    // than the nearest caster): one comparison a pixel for hard shadows, the 2x2 nearest
    // comparisons weighted bilinearly for soft ones.
    if (name == kShadowMapTexture && shadow_map) {
      const Filter filter = light.shadows == Light::Shadows::Soft ? Filter::Linear : Filter::Nearest;
      return TextureSource::depth_of(*shadow_map, SamplerDesc{filter, AddressMode::ClampToEdge, CompareOp::LessEqual});
    }
    // _LightTexture0 is a spot's cookie, else (a point light's) the falloff; _LightTextureB0 a
    // spot's falloff.
    if (name == "_LightTexture0" || name == "_LightTextureB0") {
      const bool cookie = name == "_LightTexture0" && light.type == LightType::Spot;
      std::optional<TextureHandle>& made = cookie ? spot_cookie_ : light_falloff_;
      if (!made) {
        auto handle = resources_.upload_texture(cookie ? spot_cookie_texture() : light_falloff_texture());
        if (!handle) return fail(from_backend(handle.error()));
        made = *handle;
      }
      return TextureSource::texture(*made, clamped);
    }
    if (name == "_EnvironmentSpecular") {
      auto env = environment_texture();
      if (!env) return fail(env.error());
      return TextureSource::texture(*env, clamped);
    }
    // Unity's reflection probes: both are the scene's environment (one probe, weight 1).
    if (renderer_texture(name)) {
      auto cube = environment_cube();
      if (!cube) return fail(cube.error());
      return TextureSource::texture(*cube, clamped);
    }
    return std::optional<TextureSource>{};
  }

  Values frame_values() const { return frame_inputs(scene_, environment_.sh); }

  Result<void> scene_pass() {
    Values values = frame_values();
    for (size_t light : plan_.shadow_lights)
      if (auto drawn = shadow_pass(light, values); !drawn) return fail(drawn.error());
    // Depth cleared to the far plane: 0 where the platform reverses it.
    RenderPass pass{scene_target_, scene_.clear_color, direct3d_ ? 0.0f : 1.0f, {}};
    pass.row_origin = row_origin_;
    for (size_t i : plan_.draw_order) {
      // An object's passes, in order, one after the other (Unity's forward renderer).
      for (const Plan::InstanceDraw& instance_draw : plan_.instance_draws[i]) {
        if (instance_draw.caster) continue;
        auto draw = draw_item(plan_.instances[i], instance_draw, values);
        if (!draw) return fail(draw.error());
        pass.draws.push_back(std::move(*draw));
      }
    }
    return timed("scene", pass);
  }

  // An instance's draw of one of its passes, with `values` as its uniforms read them (the
  // instance's model and the light it is drawn for are set in them here).
  Result<DrawItem> draw_item(const ObjectInstance& instance, const Plan::InstanceDraw& instance_draw, Values& values) {
    const std::string where =
        "object '" + instance.object_name + "'" +
        (instance.in_grid ? " cell " + std::to_string(instance.row) + "," + std::to_string(instance.col) : "");
    add_object_inputs(instance.model, values);
    auto mesh_handle = mesh(instance.mesh);
    if (!mesh_handle) return fail(in_context(where, mesh_handle.error()));
    const size_t variant = instance_draw.variant;
    // A ForwardAdd pass reads its own light where the others read the main one.
    const std::optional<size_t> light_index = instance_draw.light ? instance_draw.light : main_light_index_;
    const Light& light = instance_draw.light ? scene_.lights[*instance_draw.light] : main_light_;
    add_light_inputs(light, values);
    // What a receiving pass reads of its light's shadow map (a caster draws into it instead).
    const auto map = light_index ? shadow_maps_.find(*light_index) : shadow_maps_.end();
    const std::optional<TargetHandle> shadow_map = map != shadow_maps_.end() && !instance_draw.caster
                                                       ? std::optional<TargetHandle>(map->second.first)
                                                       : std::nullopt;
    if (shadow_map) add_shadow_receiver_inputs(light, map->second.second, values);
    auto handle = program(variant);
    if (!handle) return fail(handle.error());
    DrawItem draw{*handle,
                  *mesh_handle,
                  {},
                  {},
                  direct3d_ ? on_direct3d_render_target(instance_draw.state) : instance_draw.state};
    for (const std::string& name : variants_[variant].interface.textures) {
      auto engine = engine_texture(name, light, shadow_map);
      if (!engine) return fail(in_context(where + ": texture '" + name + "'", engine.error()));
      if (*engine) {
        draw.textures.push_back({name, **engine});
        continue;
      }
      // The planner gave the instance every texture its material samples (the scene's or the
      // shader's declared default), or refused the scene.
      auto given = instance.textures.find(name);
      if (given == instance.textures.end())
        return fail(ErrorKind::Internal,
                    where + ": texture '" + name + "' has no source; the plan should have refused the scene");
      const TextureShape shape = declared_shape(variants_[variant], name);
      auto made = texture(given->second, shape);
      if (!made) return fail(in_context(where + ": texture '" + name + "'", made.error()));
      values[name + "_TexelSize"] = texel_size(made->size);
      draw.textures.push_back({name, TextureSource::texture(made->handle, scene_sampler(shape, false))});
    }
    // The planner refused a scene that does not give each buffer the material reads.
    for (const StorageBufferInput& buffer : variants_[variant].interface.storage_buffers) {
      auto given = instance.buffers.find(buffer.name);
      if (given == instance.buffers.end())
        return fail(ErrorKind::Internal,
                    where + ": buffer '" + buffer.name + "' has no source; the plan should have refused the scene");
      auto bytes = scene_buffer_bytes(given->second, buffer);
      if (!bytes) return fail(bytes.error());
      draw.storage_buffers.push_back({buffer.name, std::move(*bytes)});
    }
    auto uniforms = uniform_bindings(variants_[variant],
                                     UniformValues(values, instance.properties, variants_[variant].interface), where);
    if (!uniforms) return fail(uniforms.error());
    draw.uniforms = std::move(*uniforms);
    return draw;
  }

  // A light's shadow map: every caster's ShadowCaster pass drawn from the light, a directional
  // light's with an orthographic projection fitted to everything the scene draws, a spot's with
  // its cone's perspective (shadow_map.h); the receiving passes read it in draw_item.
  Result<void> shadow_pass(size_t light_index, const Values& values) {
    const Light& light = scene_.lights[light_index];
    ShadowView view;
    if (light.type == LightType::Spot) {
      view = spot_shadow_view(light);
    } else {
      std::vector<std::pair<glm::vec3, glm::vec3>> boxes;  // each instance's world-space box
      for (const ObjectInstance& instance : plan_.instances) {
        auto known = scene_mesh(instance.mesh);
        if (!known) return fail(known.error());
        boxes.push_back(world_box((*known)->box, instance.model));
      }
      view = directional_shadow_view(light, boxes);
    }
    auto known = shadow_maps_.find(light_index);
    if (known == shadow_maps_.end()) {
      auto target = resources_.create_target({light.shadow_resolution, light.shadow_resolution, true, false, false});
      if (!target) return fail(from_backend(target.error()));
      known = shadow_maps_.emplace(light_index, std::make_pair(*target, view)).first;
    }
    known->second.second = view;
    Values caster_values = values;
    add_shadow_caster_inputs(light, view, caster_values);
    RenderPass pass{known->second.first, glm::vec4(1.0f), 1.0f, {}};
    pass.row_origin = row_origin_;
    for (size_t i = 0; i < plan_.instances.size(); ++i)
      for (const Plan::InstanceDraw& instance_draw : plan_.instance_draws[i]) {
        if (!instance_draw.caster || instance_draw.light != light_index) continue;
        auto draw = draw_item(plan_.instances[i], instance_draw, caster_values);
        if (!draw) return fail(draw.error());
        pass.draws.push_back(std::move(*draw));
      }
    return timed("shadow", pass);
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
      auto created = resources_.create_target({width, height, false, options_.trace_nonfinite});
      if (!created) return fail(from_backend(created.error()));
      target = *created;
    }

    // An effect's first pass reads the image so far; scene.depth is always the scene's (the scene
    // pass's depth, or the given depth image).
    if (planned.effect != current_effect_) {
      current_effect_ = planned.effect;
      effect_input_ = current_;
      pass_outputs_.clear();
    }
    Values values = frame_values();
    // Unity draws a post pass as a blit: the identity model matrix.
    add_object_inputs(glm::mat4(1.0f), values);
    if (planned.blit) add_blit_inputs(values, scene_.unity_platform);
    const CompiledVariant& variant = variants_[planned.variant];
    DrawItem draw{{}, {}, {}, {}, {}};
    if (!variant.program.fullscreen) {
      // The effect's own vertex shader (#pragma vertex, Unity's VertDefault) reads the triangle
      // Unity's post-processing stack draws.
      auto triangle = fullscreen_triangle();
      if (!triangle) return fail(triangle.error());
      draw.mesh = *triangle;
    }
    for (const std::string& name : variant.interface.textures) {
      auto input = std::find_if(declaration.inputs.begin(), declaration.inputs.end(),
                                [&](const hlsl::PassInput& i) { return i.texture == name; });
      if (input == declaration.inputs.end()) {
        const TextureRef* given = nullptr;
        if (auto scene_given = effect.textures.find(name); scene_given != effect.textures.end())
          given = &scene_given->second;
        else if (auto defaulted = planned.default_textures.find(name); defaulted != planned.default_textures.end())
          given = &defaulted->second;
        if (given) {
          const TextureShape shape = declared_shape(variant, name);
          auto made = texture(*given, shape);
          if (!made) return fail(in_context("pass '" + planned.name + "': texture '" + name + "'", made.error()));
          values[name + "_TexelSize"] = texel_size(made->size);
          draw.textures.push_back({name, TextureSource::texture(made->handle, scene_sampler(shape, true))});
          continue;
        }
        auto engine = engine_texture(name, main_light_);
        if (!engine) return fail(in_context("pass '" + planned.name + "': texture '" + name + "'", engine.error()));
        if (*engine) {
          draw.textures.push_back({name, **engine});
          continue;
        }
      }
      // Unity's depth texture is the scene's depth where the pass names no other source.
      const bool camera_depth = input == declaration.inputs.end() && name == "_CameraDepthTexture";
      if (input == declaration.inputs.end() && !camera_depth)
        return fail(ErrorKind::UserInput,
                    "pass '" + planned.name + "' samples '" + name +
                        "', which neither its #pragma pass nor the scene's [post.textures] gives a source");
      const PassSource& source = camera_depth || input->kind == hlsl::PassInput::Kind::SceneDepth ? scene_depth_
                                 : input->kind == hlsl::PassInput::Kind::Pass ? pass_outputs_.at(input->pass)
                                                                              : effect_input_;
      if (const TextureShape shape = declared_shape(variant, name); shape != TextureShape{})
        return fail(ErrorKind::UserInput,
                    "pass '" + planned.name + "' samples '" + name + "' as a " + shape_name(shape) +
                        ", and its source (the scene's image or depth, or an earlier pass's) is a Texture2D");
      values[name + "_TexelSize"] = texel_size(source.size);
      draw.textures.push_back({name, source.binding});
    }
    auto handle = program(planned.variant);
    if (!handle) return fail(handle.error());
    draw.program = *handle;
    auto uniforms = uniform_bindings(variant, UniformValues(values, effect.parameters, variant.interface),
                                     "pass '" + planned.name + "'");
    if (!uniforms) return fail(uniforms.error());
    draw.uniforms = std::move(*uniforms);

    RenderPass pass{target, glm::vec4(0.0f), 1.0f, {std::move(draw)}};
    pass.row_origin = row_origin_;
    if (auto rendered = timed(planned.name, pass); !rendered) return rendered;
    current_ = {TextureSource::color_of(target, kColorSampler), {width, height}};
    pass_outputs_[declaration.name] = current_;
    return {};
  }

  Result<void> timed(const std::string& name, const RenderPass& pass) {
    if (options_.on_pass) options_.on_pass(name);
    const auto start = std::chrono::steady_clock::now();
    if (auto rendered = backend_.render(pass); !rendered) return fail(from_backend(in_context(name, rendered.error())));
    const std::chrono::duration<double, std::milli> elapsed = std::chrono::steady_clock::now() - start;
    timings_.push_back({name, elapsed.count()});
    return {};
  }

  Backend& backend_;
  const Scene& scene_;
  // How a scene that draws Unity's .shader files keeps Unity's row order, bottom row first: under
  // Direct3D's conventions the projection flips y and reverses depth (render_target_convention);
  // under GLCore's the targets take OpenGL's row origin (RowOrigin::Bottom), as Unity's GLCore
  // draws. A scene of xshade's own shaders keeps xshade's orientation, row 0 at the top.
  const bool direct3d_ = shaderlab::direct3d_conventions(scene_.unity_platform);
  const RowOrigin row_origin_ = !direct3d_ && draws_unity_shader(scene_) ? RowOrigin::Bottom : RowOrigin::Top;
  const bool rows_bottom_first_ = direct3d_ || row_origin_ == RowOrigin::Bottom;
  const Plan& plan_;
  const std::vector<CompiledVariant>& variants_;
  const Environment& environment_;
  const RenderOptions& options_;
  // Every target, mesh and texture this render made, and its programs unless a ProgramCache
  // keeps them: destroyed when the render ends, however it ends.
  ResourceSet resources_{backend_};

  TargetHandle scene_target_;  // none when the post passes run on given images
  PassSource scene_color_;     // what scene.color and scene.depth name
  PassSource scene_depth_;
  PassSource current_;  // the image so far
  size_t current_effect_ = SIZE_MAX;
  PassSource effect_input_;                         // the image the current effect received
  std::map<std::string, PassSource> pass_outputs_;  // of the current effect, by pass name
  std::map<size_t, TargetHandle> pass_target_;      // by index into the plan's passes
  std::map<size_t, ProgramHandle> programs_;
  std::deque<SceneMesh> meshes_;  // a deque: pointers to its meshes stay valid as it grows
  std::vector<SceneTexture> textures_;
  TextureHandle environment_handle_;
  TextureHandle environment_cube_;
  std::optional<TextureHandle> light_falloff_, spot_cookie_;  // made where a draw reads them
  // Each casting light's shadow map and the view it was drawn from, by light.
  std::map<size_t, std::pair<TargetHandle, ShadowView>> shadow_maps_;
  // What the passes that are not an additive light's read as the light: the main light, or none.
  Light main_light_ = main_light(scene_);
  std::optional<size_t> main_light_index_ = forward_lights(scene_).main;
  MeshHandle triangle_;
  std::vector<PassTiming> timings_;
  std::vector<std::pair<std::string, FloatImage>> pass_images_;
  std::vector<PassTrace> traces_;
};

// What makes two programs the same: their stages' code and the layout they are bound by, not
// their names.
std::string program_key(const ProgramDesc& desc) {
  std::string key = desc.fullscreen ? "fullscreen\n" : "mesh\n";
  for (const ShaderStageSource* stage : {&desc.vertex, &desc.fragment}) {
    key += stage->entry_point + "\n" + stage->glsl + "\n";
    key.append(reinterpret_cast<const char*>(stage->spirv.data()), stage->spirv.size() * sizeof(uint32_t));
    key += "\n";
  }
  for (const UniformBlockSlot& block : desc.layout.uniform_blocks)
    key += "b " + block.name + " " + std::to_string(block.binding) + " " + std::to_string(block.size) + " " +
           block.glsl_block + "\n";
  for (const TextureSlot& texture : desc.layout.textures)
    key += "t " + texture.name + " " + std::to_string(texture.binding) + " " +
           (texture.sampler_binding ? std::to_string(*texture.sampler_binding) : "-") + " " +
           shape_name(texture.shape) + " " + texel_kind_name(texture.texel) + (texture.comparison ? " compare" : "") +
           (texture.image_only ? " image" : "") + " " + texture.glsl_name + "\n";
  return key;
}

}  // namespace

Result<ProgramHandle> ProgramCache::program(Backend& backend, const ProgramDesc& desc) {
  if (backend_ && backend_ != &backend) return fail(ErrorKind::Internal, "a program cache serves one backend only");
  backend_ = &backend;
  std::string key = program_key(desc);
  if (auto it = programs_.find(key); it != programs_.end()) return it->second;
  auto created = backend.create_program(desc);
  if (!created) return fail(created.error());
  programs_.emplace(std::move(key), *created);
  return *created;
}

Result<RenderedScene> render_scene(Backend& backend, const Scene& scene, const Plan& plan,
                                   const std::vector<CompiledVariant>& variants, const Environment& environment,
                                   const RenderOptions& options) {
  return SceneRenderer(backend, scene, plan, variants, environment, options).render();
}

Result<RenderedScene> render_post_effects(Backend& backend, const Scene& scene, const Plan& plan,
                                          const std::vector<CompiledVariant>& variants, const FloatImage& color,
                                          const FloatImage& depth, const RenderOptions& options) {
  // No scene pass, so no environment: the post passes read none of its values.
  const Environment none;
  return SceneRenderer(backend, scene, plan, variants, none, options).render_post(color, depth);
}

double milliseconds_of(const std::vector<PassTiming>& frame, std::string_view prefix) {
  double total = 0.0;
  for (const PassTiming& timing : frame)
    if (timing.pass.starts_with(prefix)) total += timing.milliseconds;
  return total;
}

}  // namespace xshade::harness
