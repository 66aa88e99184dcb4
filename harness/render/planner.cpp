#include "harness/render/planner.h"

#include <algorithm>
#include <map>
#include <set>

#include <fmt/format.h>

#include "harness/backend/backend.h"
#include "harness/render/forward_lights.h"
#include "harness/render/material_source.h"
#include "harness/render/scene_contract.h"
#include "harness/render/unity_render_state.h"
#include "hlsl_like/compiler.h"
#include "shaderlab/pass_program.h"
#include "shaderlab/reader.h"

namespace xshade::harness {
namespace {

namespace fs = std::filesystem;

bool is_no_keyword(const std::string& keyword) {
  return !keyword.empty() && keyword.find_first_not_of('_') == std::string::npos;
}

// What the planner learns from reading a source once (front end only).
struct SourceFacts {
  fs::path path;
  std::vector<hlsl::KeywordSet> keyword_sets;
  std::vector<hlsl::PassDeclaration> passes;           // of a post effect
  std::vector<std::string> vertex_inputs;              // the semantics the vertex entry reads, canonical
  ShaderNames names;                                   // what the variant offers a scene by name
  std::vector<std::string> notes;                      // what the plan says of the source (material_source.h)
  std::optional<shaderlab::RenderState> render_state;  // a .shader's (material_source.h)
  int queue = kGeometryQueue;
  std::vector<shaderlab::Property> properties;  // a .shader's (material_source.h)
  std::vector<size_t> drawn_passes;             // a .shader's (material_source.h); empty for an .hlsl
  std::vector<size_t> additive_passes;          // a .shader's ForwardAdd passes (material_source.h)
  std::optional<size_t> caster_pass;            // a .shader's ShadowCaster pass (material_source.h)
  std::optional<size_t> pass;                   // the .shader's pass read (the first drawn, unless asked for another)
};

class SourceReader {
 public:
  SourceReader(const ShaderSearchPath& shaders, shaderlab::UnityPlatform platform, std::set<fs::path>* files_read)
      : shaders_(shaders), platform_(platform), files_read_(files_read) {}

  // Reads `library_path` with `keywords` (pass declarations may depend on them); with
  // `pass_entry`, as that post pass's variant.
  Result<SourceFacts> read(const std::string& library_path, const std::vector<std::string>& keywords, bool post,
                           const std::string& pass_entry = {}, std::optional<size_t> shader_pass = std::nullopt) {
    std::vector<fs::path> looked_in;
    auto path = shaders_.find(library_path, &looked_in);
    // Where it was looked for before: a file made there later (a source that was missing, or a
    // user's file that takes the library's place) changes the plan. A folder that does not exist
    // cannot be watched, and would be created first.
    if (files_read_)
      for (const fs::path& place : looked_in) {
        std::error_code error;
        if (fs::is_directory(place.parent_path(), error)) files_read_->insert(place);
      }
    if (!path) return fail(path.error());
    hlsl::CompileOptions options;
    options.include_dirs = shaders_.folders();
    options.keywords = keywords;
    options.pass_fragment_entry = pass_entry;
    auto source = compile_source(*path, options, shader_pass, platform_);
    if (files_read_) {
      files_read_->insert(*path);
      if (source)
        for (const fs::path& file : source->module->dependencies()) files_read_->insert(file);
    }
    if (!source) return fail(source.error());
    const std::unique_ptr<hlsl::Module>& module = source->module;
    SourceFacts facts;
    facts.path = *path;
    facts.drawn_passes = source->drawn_passes;
    facts.additive_passes = source->additive_passes;
    facts.caster_pass = source->caster_pass;
    if (!source->drawn_passes.empty()) facts.pass = source->pass;
    facts.notes = std::move(source->notes);
    // The source's own warnings each; those of the files it includes (Unity's own, often) counted.
    size_t included = 0;
    for (const Diagnostic& diagnostic : module->diagnostics.diagnostics()) {
      if (diagnostic.severity != Severity::Warning) continue;
      if (diagnostic.where.file != path->string()) {
        ++included;
        continue;
      }
      add_warning(diagnostic.to_string());
    }
    if (included)
      add_warning(library_path + ": " + std::to_string(included) + " warning" + (included == 1 ? "" : "s") +
                  " in the files it includes (xshade compile shows them)");
    facts.render_state = std::move(source->render_state);
    facts.properties = std::move(source->properties);
    auto queue = render_queue(source->queue);
    if (!queue) return fail(Error{queue.error().message, {path->string(), 0, 0}, {}});
    facts.queue = *queue;
    if (post) facts.passes = module->passes;
    if (!module->ok()) {
      return fail(Error{"'" + library_path + "' does not compile",
                        {path->string(), 0, 0},
                        module->diagnostics.errors_with_excerpts()});
    }
    if (post && facts.passes.empty())
      return fail(ErrorKind::UserInput, "post effect '" + library_path + "' declares no passes (#pragma pass)",
                  {path->string(), 0, 0});
    facts.keyword_sets = module->reflection.keyword_sets;
    facts.names = shader_names(library_path, module->reflection);
    for (const shaderlab::Property& property : facts.properties)
      if (!property.is_texture() && !facts.names.uniform(property.name))
        facts.names.block_properties[property.name] =
            property.type == shaderlab::PropertyType::Color || property.type == shaderlab::PropertyType::Vector ? 4 : 1;
    for (const hlsl::StageVariable& input : module->reflection.vertex_inputs)
      facts.vertex_inputs.push_back(input.semantic);
    return facts;
  }

  // Every source's front-end warnings, each once, in the order they were first met.
  const std::vector<std::string>& warnings() const { return warnings_; }

 private:
  void add_warning(const std::string& warning) {
    if (std::find(warnings_.begin(), warnings_.end(), warning) == warnings_.end()) warnings_.push_back(warning);
  }

  const ShaderSearchPath& shaders_;
  shaderlab::UnityPlatform platform_;
  std::set<fs::path>* files_read_;
  std::vector<std::string> warnings_;
};

// The keywords that make the variant: per set, the one asked for or the set's default, so that
// naming a default explicitly or not gives the same variant. Keywords no set declares are kept
// here; the contract then refuses the scene at the keyword's line (scene_contract.h).
std::vector<std::string> variant_keywords(const std::vector<hlsl::KeywordSet>& sets,
                                          const std::vector<std::string>& asked) {
  std::set<std::string> keywords;
  std::set<std::string> declared;
  for (const hlsl::KeywordSet& set : sets) {
    declared.insert(set.keywords.begin(), set.keywords.end());
    auto named = std::find_first_of(set.keywords.begin(), set.keywords.end(), asked.begin(), asked.end());
    const std::string& chosen = named != set.keywords.end() ? *named : set.keywords.front();
    if (!is_no_keyword(chosen)) keywords.insert(chosen);
  }
  for (const std::string& keyword : asked)
    if (!declared.count(keyword)) keywords.insert(keyword);
  return {keywords.begin(), keywords.end()};
}

// A keyword the scene turns on for every shader that declares it, as Unity's global keywords (the
// fog's) are: asked of the set that holds it, unless the object asks another of that set.
void add_global_keyword(const std::string& keyword, const std::vector<hlsl::KeywordSet>& sets,
                        std::vector<std::string>& asked) {
  for (const hlsl::KeywordSet& set : sets) {
    if (std::find(set.keywords.begin(), set.keywords.end(), keyword) == set.keywords.end()) continue;
    if (std::find_first_of(set.keywords.begin(), set.keywords.end(), asked.begin(), asked.end()) == set.keywords.end())
      asked.push_back(keyword);
    return;
  }
}

// `note` once: every instance of a material would say it again.
void add_left_out(std::vector<std::string>& left_out, const std::string& note) {
  if (std::find(left_out.begin(), left_out.end(), note) == left_out.end()) left_out.push_back(note);
}

bool declares(const std::vector<hlsl::KeywordSet>& sets, const std::string& keyword) {
  return std::any_of(sets.begin(), sets.end(), [&](const hlsl::KeywordSet& set) {
    return std::find(set.keywords.begin(), set.keywords.end(), keyword) != set.keywords.end();
  });
}

size_t add_variant(Plan& plan, VariantRequest request) {
  auto found = std::find(plan.variants.begin(), plan.variants.end(), request);
  if (found != plan.variants.end()) return size_t(found - plan.variants.begin());
  plan.variants.push_back(std::move(request));
  plan.variant_notes.emplace_back();
  return plan.variants.size() - 1;
}

// What every mesh supplies (Vertex: locations 0..3); any other input reads zeros.
bool meshes_supply(const std::string& semantic) {
  return semantic == "POSITION0" || semantic == "NORMAL0" || semantic == "TANGENT0" || semantic == "TEXCOORD0";
}

std::string effect_name(const std::string& library_path) { return fs::path(library_path).stem().string(); }

std::vector<size_t> draw_order(const glm::vec3& camera, const std::vector<ObjectInstance>& instances,
                               const std::vector<int>& queues) {
  std::vector<size_t> order(instances.size());
  for (size_t i = 0; i < order.size(); ++i) order[i] = i;
  const auto distance = [&](size_t i) { return glm::length(glm::vec3(instances[i].model[3]) - camera); };
  std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) {
    if (queues[a] != queues[b]) return queues[a] < queues[b];
    return queues[a] > kLastOpaqueQueue && distance(a) > distance(b);
  });
  return order;
}

}  // namespace

std::string VariantRequest::label() const {
  std::string text = library_path;
  if (!fragment_entry.empty()) text += ":" + fragment_entry;
  if (shader_pass) text += " pass " + std::to_string(*shader_pass);
  if (unity_platform != shaderlab::UnityPlatform::GLCore)
    text += " for " + std::string(shaderlab::renderer_name(unity_platform));
  text += " [";
  for (size_t i = 0; i < keywords.size(); ++i) text += (i ? " " : "") + keywords[i];
  text += "]" + std::string(filtered_comparison ? " filtered comparison" : "") + (half_emulation ? " half" : "");
  if (!specialization.empty()) {
    text += " specialized {";
    for (const auto& [id, value] : specialization)
      text += (text.back() == '{' ? "" : ",") + fmt::format("{}={}", id, value);
    text += "}";
  }
  return text;
}

namespace {

// The steps of the .shader post effect `scene.post[e]` (at `path`) as post passes: each its pass
// of the drawn SubShader compiled whole (its vertex and fragment programs), drawn as Unity's
// Graphics.Blit draws it, its _MainTex the image of the step before unless it names a source (or
// the effect's textures give one: Graphics.Blit of a texture, a cube map, ...).
Result<void> plan_shader_effect(const Scene& scene, size_t e, const fs::path& path, SourceReader& reader, Plan& plan,
                                ContractProblems& contract) {
  const PostEffect& effect = scene.post[e];
  auto shader = shaderlab::read_shader_file(path);
  if (!shader) return fail(shader.error());
  std::vector<PostStep> steps = effect.passes;
  if (steps.empty()) {  // its first drawn pass
    PostStep first;
    first.where = effect.where.of("effect");
    steps.push_back(std::move(first));
  }
  std::vector<PassNames> pass_names;
  std::vector<size_t> indices;
  std::vector<std::vector<std::string>> step_keywords;
  ShaderNames keyword_names;
  std::string previous;
  for (const PostStep& step : steps) {
    std::optional<size_t> index;
    if (!step.pass.empty()) {
      auto found = shaderlab::find_pass(*shader, step.pass, scene.unity_platform);
      if (!found) return fail(Error{found.error().message, step.where, {}});
      index = size_t(*found - shaderlab::drawn_subshader(*shader, scene.unity_platform)->passes.data());
    }
    auto facts = reader.read(effect.effect, effect.keywords, false, {}, index);
    if (!facts) return fail(facts.error());
    const size_t pass_index = *facts->pass;
    hlsl::PassDeclaration declaration;
    declaration.name = !step.name.empty() ? step.name : !step.pass.empty() ? step.pass : std::to_string(pass_index);
    declaration.scale = step.half ? hlsl::PassDeclaration::Scale::Half : hlsl::PassDeclaration::Scale::Full;
    for (const auto& [texture, source] : step.sources) {
      using Kind = hlsl::PassInput::Kind;
      const Kind kind = source == "scene.color"   ? Kind::SceneColor
                        : source == "scene.depth" ? Kind::SceneDepth
                                                  : Kind::Pass;
      declaration.inputs.push_back({texture, kind, kind == Kind::Pass ? source : std::string()});
    }
    if (!step.sources.count("_MainTex") && !effect.textures.count("_MainTex"))
      declaration.inputs.push_back(previous.empty()
                                       ? hlsl::PassInput{"_MainTex", hlsl::PassInput::Kind::SceneColor, {}}
                                       : hlsl::PassInput{"_MainTex", hlsl::PassInput::Kind::Pass, previous});
    previous = declaration.name;
    keyword_names.keyword_sets.insert(keyword_names.keyword_sets.end(), facts->keyword_sets.begin(),
                                      facts->keyword_sets.end());
    step_keywords.push_back(variant_keywords(facts->keyword_sets, effect.keywords));
    indices.push_back(pass_index);
    pass_names.push_back({std::move(declaration), std::move(facts->names)});
  }
  check_keywords(effect.keywords, effect.where, keyword_names, "post effect '" + effect.effect + "'", contract);
  const size_t notes_before = contract.notes.size();
  const std::vector<std::map<std::string, TextureRef>> pass_defaults = check_effect(effect, pass_names, contract);
  for (size_t d = 0; d < pass_names.size(); ++d) {
    PlannedPass pass;
    pass.kind = PlannedPass::Kind::Post;
    pass.name = effect_name(effect.effect) + "." + pass_names[d].declaration.name;
    pass.effect = e;
    pass.declaration = pass_names[d].declaration;
    pass.blit = true;
    pass.variant = add_variant(plan, {path, effect.effect, step_keywords[d], {}, indices[d]});
    pass.default_textures = pass_defaults[d];
    plan.passes.push_back(std::move(pass));
  }
  for (size_t n = notes_before; n < contract.notes.size(); ++n)
    plan.variant_notes[plan.passes.back().variant].push_back(contract.notes[n]);
  return {};
}

}  // namespace

Result<Plan> plan_scene(const Scene& scene, const ShaderSearchPath& shaders, std::set<fs::path>* files_read) {
  Plan plan;
  SourceReader reader(shaders, scene.unity_platform, files_read);
  // Distinct combinations a source is used with, for the "left out" account.
  std::map<std::string, std::set<std::vector<std::string>>> used_combinations;
  std::map<std::string, uint64_t> possible_combinations;

  // load_scene has refused a scene over budget; one made in code is held to the same limits
  // before anything is expanded.
  if (Result<void> work = check_scene_work(scene); !work) return fail(work.error());
  plan.instances = expand_instances(scene);
  const ForwardLights lights = forward_lights(scene);
  for (const std::string& note : lights.left_out) plan.left_out.push_back(note);
  // Shadows: the main light's, received by ForwardBase (SHADOWS_SCREEN), and each spot pixel
  // light's, received by its ForwardAdd (SHADOWS_DEPTH); the scene refuses point lights'.
  std::vector<std::pair<size_t, const char*>> casting;  // each light that casts, and its receivers' keyword
  for (size_t i = 0; i < scene.lights.size(); ++i) {
    if (scene.lights[i].shadows == Light::Shadows::None) continue;
    const bool pixel = std::find(lights.pixel.begin(), lights.pixel.end(), i) != lights.pixel.end();
    if (lights.main == i)
      casting.emplace_back(i, "SHADOWS_SCREEN");
    else if (pixel && scene.lights[i].type == LightType::Spot)
      casting.emplace_back(i, "SHADOWS_DEPTH");
    else
      plan.left_out.push_back("light " + std::to_string(i + 1) +
                              "'s shadows: not rendered: only the main light and "
                              "spot pixel lights cast shadows so far");
  }
  std::map<std::string, SourceFacts> materials;
  // A .shader's passes are read each once (keyword sets and render state are a pass's own).
  auto material_facts = [&](const std::string& material, std::optional<size_t> pass) -> Result<const SourceFacts*> {
    const std::string key = material + (pass ? "\n" + std::to_string(*pass) : "");
    auto known = materials.find(key);
    if (known == materials.end()) {
      auto facts = reader.read(material, {}, false, {}, pass);
      if (!facts) return fail(facts.error());
      known = materials.emplace(key, std::move(*facts)).first;
    }
    return &known->second;
  };
  // A shadow map only where a pass drawn for the light receives it (declares the keyword) and
  // something casts.
  for (const auto& [light, keyword] : casting) {
    bool receivers = false, casters = false;
    const bool additive = lights.main != light;
    for (const ObjectInstance& instance : plan.instances) {
      auto first = material_facts(instance.material, std::nullopt);
      if (!first) return fail(first.error());
      casters = casters || (*first)->caster_pass.has_value();
      // A reference: the facts read below are new map entries, which move none of the others.
      const std::vector<size_t>& receiving = additive ? (*first)->additive_passes : (*first)->drawn_passes;
      for (size_t pass : receiving) {
        auto facts = material_facts(instance.material, pass);
        if (!facts) return fail(facts.error());
        receivers = receivers || declares((*facts)->keyword_sets, keyword);
      }
    }
    if (!receivers || !casters)
      plan.left_out.push_back("light " + std::to_string(light + 1) + "'s shadows: no shadow map: " +
                              (!receivers
                                   ? std::string("no pass drawn for it receives them (none declares ") + keyword + ")"
                                   : std::string("no object casts (no ShadowCaster pass, nor its Fallback's)")));
    else if (scene.unity_platform != shaderlab::UnityPlatform::GLCore)
      return fail(ErrorKind::UserInput,
                  "light " + std::to_string(light + 1) + "'s shadows: a scene of the Unity platform " +
                      std::string(shaderlab::renderer_name(scene.unity_platform)) +
                      " draws no shadow map yet (its reversed depth and flipped targets are not in the shadow pass); "
                      "use [unity] platform = \"glcore\" or shadows = \"none\"");
    else
      plan.shadow_lights.push_back(light);
  }
  const auto has_map = [&](std::optional<size_t> light) {
    return light && std::find(plan.shadow_lights.begin(), plan.shadow_lights.end(), *light) != plan.shadow_lights.end();
  };
  const bool shadowed = !plan.shadow_lights.empty();
  std::vector<ShaderNames> variant_names;  // per variant of the scene pass
  ContractProblems contract;
  std::map<size_t, std::map<std::string, TextureRef>> object_defaults;  // by object index
  for (const ObjectInstance& instance : plan.instances) {
    auto pass_facts = [&](std::optional<size_t> pass) { return material_facts(instance.material, pass); };
    auto first = pass_facts(std::nullopt);
    if (!first) return fail(first.error());
    const SourceFacts& material = **first;
    plan.instance_queue.push_back(material.queue);
    std::vector<Plan::InstanceDraw> draws;
    std::optional<ShaderNames> object_names;  // every drawn pass's, merged, for the object's check
    // An .hlsl draws once; a .shader each pass the forward renderer draws, then each ForwardAdd
    // pass once for each pixel light besides the main one.
    struct PassToDraw {
      std::optional<size_t> pass;   // none: an .hlsl's one program
      std::optional<size_t> light;  // an additive pass's light
      bool caster = false;          // drawn into the main light's shadow map, not the scene
    };
    std::vector<PassToDraw> passes(1);
    if (!material.drawn_passes.empty()) {
      passes.clear();
      for (size_t pass : material.drawn_passes) passes.push_back({pass, std::nullopt, false});
    }
    for (size_t pass : material.additive_passes) {
      for (size_t light : lights.pixel) passes.push_back({pass, light, false});
      if (lights.pixel.empty())
        add_left_out(plan.left_out,
                     "'" + instance.material + "' pass " + std::to_string(pass) +
                         " (ForwardAdd): not drawn: the scene has no light besides its main directional one");
    }
    if (material.caster_pass) {
      for (size_t light : plan.shadow_lights) passes.push_back({material.caster_pass, light, true});
      if (!shadowed)
        add_left_out(plan.left_out, "'" + instance.material + "' pass " + std::to_string(*material.caster_pass) +
                                        " (ShadowCaster): not drawn: no shadow map is drawn");
    }
    for (const auto& [pass, light, caster] : passes) {
      auto facts_of_pass = pass == material.pass ? Result<const SourceFacts*>(&material) : pass_facts(pass);
      if (!facts_of_pass) return fail(facts_of_pass.error());
      const SourceFacts& facts = **facts_of_pass;
      // The object's property (its first number), else nullopt for the shader's default.
      const auto scene_value = [&](const std::string& name) -> std::optional<float> {
        if (auto given = instance.properties.find(name); given != instance.properties.end())
          return given->second.components[0];
        return std::nullopt;
      };
      DrawState state;
      bool alpha_to_mask = false;
      if (facts.render_state) {
        // A state in brackets reads the object's property, else the shader's default.
        const auto material_value = [&](const std::string& name) -> std::optional<float> {
          if (auto given = scene_value(name)) return given;
          for (const shaderlab::Property& property : facts.properties)
            if (property.name == name) return property.value[0];
          return std::nullopt;
        };
        auto drawn = unity_draw_state(*facts.render_state, material_value);
        if (!drawn) return fail(drawn.error());
        state = *drawn;
        auto masked = unity_alpha_to_mask(*facts.render_state, material_value);
        if (!masked) return fail(masked.error());
        alpha_to_mask = *masked;
      }
      std::vector<std::string> asked =
          with_inspector_keywords(facts.properties, facts.keyword_sets, instance.keywords, scene_value);
      if (scene.fog) add_global_keyword(fog_keyword(scene.fog->mode), facts.keyword_sets, asked);
      // The light a pass is drawn for chooses its variant, as Unity's forward renderer sets the
      // keywords: an additive pass's light type; ForwardBase's per-vertex lights where there are any.
      // The light whose shadow map the pass reads, and the keyword that says so.
      std::optional<std::pair<size_t, const char*>> received;
      if (caster) {
        add_global_keyword("SHADOWS_DEPTH", facts.keyword_sets, asked);  // a directional or spot light's map
      } else if (light) {
        add_global_keyword(additive_keyword(scene.lights[*light].type), facts.keyword_sets, asked);
        // A spot light's shadow, as Unity's additive pass receives it.
        if (has_map(light)) received = {*light, "SHADOWS_DEPTH"};
      } else {
        if (!lights.vertex.empty()) add_global_keyword("VERTEXLIGHT_ON", facts.keyword_sets, asked);
        // The main light's shadow, as Unity's forward base pass receives it.
        if (has_map(lights.main)) received = {*lights.main, "SHADOWS_SCREEN"};
      }
      if (received) add_global_keyword(received->second, facts.keyword_sets, asked);
      // A soft shadow: Unity's keyword (its fullshadows passes filter more taps), and the map's
      // comparisons filtered linearly where the variant reads it.
      const bool soft = received && scene.lights[received->first].shadows == Light::Shadows::Soft;
      if (soft) add_global_keyword("SHADOWS_SOFT", facts.keyword_sets, asked);
      VariantRequest request{facts.path, instance.material, variant_keywords(facts.keyword_sets, asked), {}};
      request.shader_pass = pass;
      for (const hlsl::SpecializationConstant& constant : facts.names.specialization_constants)
        if (auto given = instance.properties.find(constant.name); given != instance.properties.end())
          request.specialization[constant.id] = given->second.components[0];
      request.filtered_comparison = soft && std::find(request.keywords.begin(), request.keywords.end(),
                                                      received->second) != request.keywords.end();
      used_combinations[instance.material].insert(request.keywords);
      possible_combinations[instance.material] = hlsl::keyword_combination_count(material.keyword_sets);
      const std::vector<std::string> keywords = request.keywords;
      const size_t variants_before = plan.variants.size();
      const size_t variant = add_variant(plan, std::move(request));
      if (plan.variants.size() != variants_before) {
        // The vertex inputs and the names depend on the keywords: the variant's own are read once more.
        auto variant_facts = reader.read(instance.material, keywords, false, {}, pass);
        if (!variant_facts) return fail(variant_facts.error());
        plan.variant_notes[variant] = variant_facts->notes;
        for (const std::string& semantic : variant_facts->vertex_inputs) {
          if (meshes_supply(semantic)) continue;
          const std::optional<uint32_t> location = hlsl::vertex_input_location(semantic);
          plan.variant_notes[variant].push_back(
              "vertex input " + semantic + " is not in the meshes; the shader reads " +
              (location && unsupplied_input_reads_white(*location) ? "white, as from a mesh without vertex colours"
                                                                   : "zeros"));
        }
        variant_names.resize(plan.variants.size());
        variant_names[variant] = std::move(variant_facts->names);
      }
      if (alpha_to_mask) {
        const std::string note =
            "AlphaToMask On is drawn as Off: a target of one sample has no samples to mask "
            "(OpenGL skips it, other APIs leave it to the driver)";
        std::vector<std::string>& notes = plan.variant_notes[variant];
        if (std::find(notes.begin(), notes.end(), note) == notes.end()) notes.push_back(note);
      }
      object_names =
          object_names ? merge_names(std::move(*object_names), variant_names[variant]) : variant_names[variant];
      draws.push_back({variant, state, light, caster});
    }
    plan.instance_draws.push_back(draws);
    // Each object once: its instances share its material, keywords and names.
    if (!object_defaults.count(instance.object_index)) {
      const SceneObject& object = scene.objects[instance.object_index];
      const size_t before = contract.notes.size();
      check_keywords(object.keywords, object.where, *object_names, "material '" + instance.material + "'", contract);
      // A light's shadow map is the renderer's to give where it draws one.
      if (shadowed)
        std::erase_if(object_names->textures,
                      [](const ShaderNames::Texture& texture) { return texture.name == kShadowMapTexture; });
      object_defaults[instance.object_index] = check_object(object, *object_names, contract);
      for (size_t n = before; n < contract.notes.size(); ++n)
        plan.variant_notes[draws.front().variant].push_back(contract.notes[n]);
    }
  }
  for (ObjectInstance& instance : plan.instances)
    for (const auto& [name, ref] : object_defaults[instance.object_index]) instance.textures.emplace(name, ref);
  if (!plan.instances.empty()) plan.passes.push_back({PlannedPass::Kind::Scene, "scene", 0, {}, 0, {}});
  plan.draw_order = draw_order(scene.camera.position, plan.instances, plan.instance_queue);

  for (size_t e = 0; e < scene.post.size(); ++e) {
    const PostEffect& effect = scene.post[e];
    auto unity = shaders.find(effect.effect);
    if (unity && is_unity_shader(*unity)) {
      if (auto planned = plan_shader_effect(scene, e, *unity, reader, plan, contract); !planned)
        return fail(planned.error());
      used_combinations[effect.effect];
      continue;
    }
    if (!effect.passes.empty())
      return fail(
          Error{"passes = [...] chooses the passes of a Unity .shader effect; an .hlsl effect's passes are its "
                "#pragma pass lines",
                effect.where.of("effect"),
                {}});
    auto facts = reader.read(effect.effect, effect.keywords, true);
    if (!facts) return fail(facts.error());
    const std::vector<std::string> keywords = variant_keywords(facts->keyword_sets, effect.keywords);
    used_combinations[effect.effect].insert(keywords);
    possible_combinations[effect.effect] = hlsl::keyword_combination_count(facts->keyword_sets);
    check_keywords(effect.keywords, effect.where, facts->names, "post effect '" + effect.effect + "'", contract);
    std::vector<PassNames> pass_names;
    for (const hlsl::PassDeclaration& declaration : facts->passes) {
      auto pass_facts = reader.read(effect.effect, effect.keywords, true, declaration.entry);
      if (!pass_facts) return fail(pass_facts.error());
      pass_names.push_back({declaration, std::move(pass_facts->names)});
    }
    const size_t notes_before = contract.notes.size();
    const std::vector<std::map<std::string, TextureRef>> pass_defaults = check_effect(effect, pass_names, contract);
    for (size_t d = 0; d < facts->passes.size(); ++d) {
      const hlsl::PassDeclaration& declaration = facts->passes[d];
      PlannedPass pass;
      pass.kind = PlannedPass::Kind::Post;
      pass.name = effect_name(effect.effect) + "." + declaration.name;
      pass.effect = e;
      pass.declaration = declaration;
      pass.variant = add_variant(plan, {facts->path, effect.effect, keywords, declaration.entry});
      pass.default_textures = pass_defaults[d];
      plan.passes.push_back(std::move(pass));
    }
    for (size_t n = notes_before; n < contract.notes.size(); ++n)
      plan.variant_notes[plan.passes.back().variant].push_back(contract.notes[n]);
  }
  if (!contract.errors.empty()) {
    std::stable_sort(contract.errors.begin(), contract.errors.end(), [](const Diagnostic& a, const Diagnostic& b) {
      return std::pair(a.where.line, a.where.column) < std::pair(b.where.line, b.where.column);
    });
    const Diagnostic& first = contract.errors.front();
    Error error{first.message, first.where, {}};
    if (contract.errors.size() > 1) error.diagnostics = contract.errors;
    return fail(std::move(error));
  }

  for (const auto& [source, used] : used_combinations) {
    const uint64_t possible = possible_combinations[source];
    if (possible == UINT64_MAX)  // saturated: 70 two-keyword sets are more than 64 bits count
      plan.left_out.push_back(source + ": all but " + std::to_string(used.size()) + " of its " +
                              std::to_string(UINT64_MAX) +
                              " or more keyword combinations (the scene asks for no other)");
    else if (possible > used.size())
      plan.left_out.push_back(source + ": " + std::to_string(possible - used.size()) + " of its " +
                              std::to_string(possible) + " keyword combinations (the scene asks for no other)");
  }
  for (const std::string& material : shaders.files("materials"))
    if (!used_combinations.count(material)) plan.left_out.push_back(material + ": no object uses it");
  for (const std::string& effect : shaders.files("post"))
    if (!used_combinations.count(effect))
      plan.left_out.push_back(effect + ": not in the post chain, so none of its passes is compiled or run");
  plan.warnings = reader.warnings();
  // A .shader compiles for the scene's Unity platform; an .hlsl file knows none.
  for (VariantRequest& request : plan.variants)
    if (is_unity_shader(request.source)) request.unity_platform = scene.unity_platform;
  return plan;
}

std::string describe_plan(const Scene& scene, const Plan& plan, const std::vector<bool>& cached) {
  std::string text = "plan for scene '" + scene.name + "' (" + std::to_string(scene.width) + "x" +
                     std::to_string(scene.height) + ")\n";
  text += "  variants to compile (" + std::to_string(plan.variants.size()) + "):\n";
  for (size_t i = 0; i < plan.variants.size(); ++i) {
    std::string state = i < cached.size() ? (cached[i] ? "  (in the cache)" : "  (to compile)") : "";
    text += "    " + plan.variants[i].label() + state + "\n";
    if (i < plan.variant_notes.size())
      for (const std::string& note : plan.variant_notes[i]) text += "      " + note + "\n";
  }
  text += "  passes to run (" + std::to_string(plan.passes.size()) + "):\n";
  for (const PlannedPass& pass : plan.passes) {
    if (pass.kind == PlannedPass::Kind::Scene) {
      size_t draws = 0;  // a .shader draws an object once for each of its passes
      for (const auto& instance_draws : plan.instance_draws) draws += instance_draws.size();
      text += "    scene: " + std::to_string(draws) + " draws\n";
      for (size_t light : plan.shadow_lights) {
        const Light& caster = scene.lights[light];
        size_t casting_draws = 0;
        for (const auto& instance_draws : plan.instance_draws)
          casting_draws +=
              size_t(std::count_if(instance_draws.begin(), instance_draws.end(),
                                   [&](const Plan::InstanceDraw& draw) { return draw.caster && draw.light == light; }));
        text += "      shadow map of light " + std::to_string(light + 1) + ": " +
                std::to_string(caster.shadow_resolution) + "x" + std::to_string(caster.shadow_resolution) +
                (caster.shadows == Light::Shadows::Soft ? ", soft (2x2 comparisons filtered), " : ", hard, ") +
                std::to_string(casting_draws) +
                " casters drawn first (ShadowCaster passes), the rest of these draws receiving it\n";
      }
      // The lights as the forward renderer divides them, and each draw an additive light adds.
      const ForwardLights lights = forward_lights(scene);
      const auto light_name = [&](size_t i) {
        const LightType type = scene.lights[i].type;
        return "light " + std::to_string(i + 1) + " (" +
               (type == LightType::Directional ? "directional"
                : type == LightType::Point     ? "point"
                                               : "spot") +
               ")";
      };
      if (lights.main) text += "      main light: " + light_name(*lights.main) + ", in ForwardBase\n";
      for (size_t i : lights.vertex) text += "      per-vertex light: " + light_name(i) + ", in ForwardBase\n";
      for (size_t i = 0; i < plan.instance_draws.size(); ++i)
        for (const Plan::InstanceDraw& draw : plan.instance_draws[i])
          if (draw.light)
            text += "      object '" + plan.instances[i].object_name + "': " + plan.variants[draw.variant].label() +
                    (draw.caster ? " into the shadow map of " : " for ") + light_name(*draw.light) + "\n";
      continue;
    }
    const hlsl::PassDeclaration& d = pass.declaration;
    // A .shader's step is its pass's whole program, blitted; an .hlsl pass is its fragment entry.
    const std::string program =
        pass.blit ? "blit of pass " + std::to_string(plan.variants[pass.variant].shader_pass.value_or(0)) : d.entry;
    text += "    " + pass.name + ": " + program + ", " +
            (d.scale == hlsl::PassDeclaration::Scale::Half ? "half" : "full") + " resolution";
    for (const hlsl::PassInput& input : d.inputs) {
      const std::string from = input.kind == hlsl::PassInput::Kind::SceneColor   ? "scene.color"
                               : input.kind == hlsl::PassInput::Kind::SceneDepth ? "scene.depth"
                                                                                 : input.pass;
      text += ", " + input.texture + " <- " + from;
    }
    text += "\n";
  }
  text += "  left out (" + std::to_string(plan.left_out.size()) + "):\n";
  for (const std::string& line : plan.left_out) text += "    " + line + "\n";
  return text;
}

}  // namespace xshade::harness
