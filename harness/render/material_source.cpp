#include "harness/render/material_source.h"

#include <algorithm>
#include <cmath>
#include <list>
#include <map>

#include "base/file_io.h"
#include "harness/render/renderer_inputs.h"
#include "harness/render/surface_program.h"
#include "shaderlab/compile_environment.h"
#include "shaderlab/reader.h"
#include "shaderlab/shader_lookup.h"

namespace xshade::harness {
namespace {

namespace fs = std::filesystem;

// sRGB to linear, as Unity converts a Color property for a project in Linear colour space.
double linear_from_srgb(double c) { return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4); }

// The scene's built-in texture for a Unity built-in texture name.
std::string built_in_for(const std::string& unity_default) {
  if (shaderlab::same_word(unity_default, "white")) return "white";
  if (shaderlab::same_word(unity_default, "black")) return "clear";  // Unity's black is (0, 0, 0, 0)
  if (shaderlab::same_word(unity_default, "bump")) return "normal";
  if (shaderlab::same_word(unity_default, "red")) return "red";
  return "gray";  // "gray", "grey", "" and any name Unity does not know
}

std::string pass_label(const shaderlab::Pass& pass, size_t index) {
  std::string label = "pass " + std::to_string(index);
  if (!pass.name.empty()) label += " '" + pass.name + "'";
  const std::string light_mode = shaderlab::tag(pass.tags, "LightMode");
  if (!light_mode.empty()) label += " (LightMode " + light_mode + ")";
  return label;
}

// The text Unity reads a program's build pragmas from (`#pragma target`, which SHADER_TARGET
// says): the program's own and, after it, each file it includes with #include_with_pragmas, and
// theirs in turn, found where the preprocessor finds them. Read as Unity reads these pragmas,
// before compiling: conditionals are not weighed. A file not found is left to the compile to
// report.
std::string with_pragma_includes(std::string text, const fs::path& including, const std::vector<fs::path>& folders,
                                 int depth = 0) {
  constexpr std::string_view kDirective = "include_with_pragmas";
  std::string included;
  size_t start = 0;
  while (start < text.size() && depth < 16) {
    size_t end = text.find('\n', start);
    if (end == std::string::npos) end = text.size();
    std::string_view line = std::string_view(text).substr(start, end - start);
    start = end + 1;
    const auto skip_blanks = [&] {
      while (!line.empty() && (line.front() == ' ' || line.front() == '\t')) line.remove_prefix(1);
    };
    skip_blanks();
    if (line.empty() || line.front() != '#') continue;
    line.remove_prefix(1);
    skip_blanks();
    if (!line.starts_with(kDirective)) continue;
    line.remove_prefix(kDirective.size());
    skip_blanks();
    if (line.empty() || (line.front() != '"' && line.front() != '<')) continue;
    const bool angled = line.front() == '<';
    const size_t close = line.find(angled ? '>' : '"', 1);
    if (close == std::string_view::npos) continue;
    const auto found = hlsl::find_include(line.substr(1, close - 1), including, angled, folders);
    if (!found) continue;
    if (auto file = read_file(*found))
      included += "\n" + with_pragma_includes(std::move(*file), *found, folders, depth + 1);
  }
  return text + included;
}

}  // namespace

bool is_unity_shader(const fs::path& path) { return path.extension() == ".shader"; }

bool forward_renderer_draws(const shaderlab::Pass& pass) {
  const std::string light_mode = shaderlab::tag(pass.tags, "LightMode");
  return light_mode.empty() || shaderlab::same_word(light_mode, "Always") ||
         shaderlab::same_word(light_mode, "ForwardBase");
}

// Whether a compiled entry point reads the uniform `name`.
bool read_uniform(const hlsl::Reflection& reflection, const std::string& name) {
  for (const hlsl::ConstantBuffer& buffer : reflection.constant_buffers)
    for (const hlsl::ConstantBufferMember& member : buffer.members)
      if (member.name == name) return member.used;
  return false;
}

void apply_properties(const shaderlab::Shader& shader, hlsl::Reflection& reflection, std::vector<std::string>& notes) {
  for (hlsl::Property& declared : reflection.properties) {
    const shaderlab::Property* property = shader.property(declared.name);
    if (!property) {
      // A uniform the Properties block does not declare is set, in Unity, by a script or not at
      // all, and reads 0 until one does; the renderer's own inputs and X_ST keep their values.
      if (declared.is_texture || !declared.default_value.empty() || !declared.type.is_numeric() ||
          renderer_uniform(declared.name) || declared.name.ends_with("_ST") || !read_uniform(reflection, declared.name))
        continue;
      declared.default_value.assign(declared.type.rows() * declared.type.cols(), 0.0);
      notes.push_back("uniform " + declared.name +
                      " reads 0: neither the Properties block nor the renderer sets it "
                      "(in Unity a script, or the engine for what this scene has not, would; set it in the scene's "
                      "properties)");
      continue;
    }
    if (declared.is_texture) {
      if (property->is_texture() && declared.default_texture.empty())
        declared.default_texture = built_in_for(property->texture_default);
      continue;
    }
    if (property->is_texture() || !declared.default_value.empty() || !declared.type.is_numeric()) continue;
    const bool color = property->type == shaderlab::PropertyType::Color;
    const bool gamma = color || property->attribute("Gamma") != nullptr;
    const bool four = color || property->type == shaderlab::PropertyType::Vector;
    const uint32_t count = std::min<uint32_t>(declared.type.rows() * declared.type.cols(), four ? 4 : 1);
    for (uint32_t i = 0; i < count; ++i) {
      const double value = property->value[i];
      declared.default_value.push_back(gamma && i < 3 ? linear_from_srgb(value) : value);
    }
  }
}

Result<hlsl::CompileOptions> pass_compile_options(const fs::path& file, const shaderlab::PassProgram& program,
                                                  hlsl::CompileOptions options, shaderlab::UnityPlatform platform) {
  options.include_dirs.insert(options.include_dirs.begin(),
                              file.parent_path().empty() ? fs::path(".") : file.parent_path());
  if (program.implicit_includes)
    if (auto found = shaderlab::find_implicit_includes(options.include_dirs); !found)
      return fail(Error{found.error().message, program.pass->program->start, {}});
  std::vector<hlsl::MacroDefinition> defines;
  for (const shaderlab::Define& define :
       shaderlab::unity_defines(with_pragma_includes(program.text, file, options.include_dirs), platform))
    if (std::none_of(options.defines.begin(), options.defines.end(),
                     [&](const hlsl::MacroDefinition& given) { return given.name == define.name; }))
      defines.push_back({define.name, define.value});
  options.defines.insert(options.defines.begin(), defines.begin(), defines.end());
  return options;
}

namespace {

// Unity's Fallback chains end; a longer one goes round.
constexpr int kLongestFallbackChain = 8;

// A pass to draw and where it comes from: the .shader's own, or another shader's by UsePass.
struct SourcePass {
  const shaderlab::SubShader* sub = nullptr;
  const shaderlab::Pass* pass = nullptr;
  fs::path file;  // the .shader that holds it
};

// The shaders a compile reads besides the one it was asked for (a Fallback, the shader of a
// UsePass), each found and read once however often it is named, and kept while the passes refer
// to them.
class NamedShaders {
 public:
  explicit NamedShaders(const std::vector<fs::path>& folders) : folders_(folders) {}

  Result<std::pair<const shaderlab::Shader*, fs::path>> read(const std::string& name, const SourceLocation& where) {
    if (auto known = read_.find(name); known != read_.end())
      return std::pair<const shaderlab::Shader*, fs::path>{&known->second.first, known->second.second};
    auto path = shaderlab::find_shader_named(name, folders_);
    if (!path) return fail(Error{path.error().message, where, {}});
    auto shader = shaderlab::read_shader_file(*path);
    if (!shader) return fail(shader.error());
    const auto entry = read_.try_emplace(name, std::move(*shader), *path).first;
    return std::pair<const shaderlab::Shader*, fs::path>{&entry->second.first, entry->second.second};
  }

 private:
  const std::vector<fs::path>& folders_;
  std::map<std::string, std::pair<shaderlab::Shader, fs::path>> read_;  // by the name they were asked for
};

// The pass UsePass "Shader/NAME" names: NAME in the SubShader the shader of that name draws,
// matched in upper case as Unity does.
Result<SourcePass> used_pass(const shaderlab::Pass& use, NamedShaders& named, shaderlab::UnityPlatform platform) {
  const auto [shader_name, pass_name] = shaderlab::split_used_pass(use.used);
  auto found = named.read(shader_name, use.where);
  if (!found) return fail(found.error());
  const shaderlab::SubShader* sub = shaderlab::drawn_subshader(*found->first, platform);
  if (sub)
    for (const shaderlab::Pass& pass : sub->passes)
      if (!pass.name.empty() && shaderlab::same_word(pass.name, pass_name))
        return SourcePass{sub, &pass, found->second};
  return fail(Error{"UsePass \"" + use.used + "\": the shader '" + shader_name + "' (" + found->second.string() +
                        ") has no pass named '" + pass_name + "' in the SubShader it draws",
                    use.where,
                    {}});
}

// `sub` as drawn: itself, or for a surface shader a copy with its generated passes, kept in
// `generated` while passes point into it.
Result<const shaderlab::SubShader*> with_generated_passes(const shaderlab::SubShader* sub, const fs::path& file,
                                                          const hlsl::CompileOptions& options,
                                                          shaderlab::UnityPlatform platform,
                                                          std::list<shaderlab::SubShader>& generated) {
  if (!sub->surface) return sub;
  auto with_passes = with_surface_passes(file, *sub, options, platform);
  if (!with_passes) return fail(with_passes.error());
  return &generated.emplace_back(std::move(*with_passes));
}

// The ShadowCaster pass of the first shader of `shader`'s Fallback chain whose drawn SubShader has
// one (its surface program's generated passes included); none when no shader of the chain has.
Result<std::optional<SourcePass>> fallback_caster(const shaderlab::Shader& shader, const fs::path& file,
                                                  NamedShaders& named, const hlsl::CompileOptions& options,
                                                  shaderlab::UnityPlatform platform,
                                                  std::list<shaderlab::SubShader>& generated) {
  const shaderlab::Shader* current = &shader;
  fs::path current_file = file;
  for (int hops = 0; hops < kLongestFallbackChain && current->fallback && !current->fallback->empty(); ++hops) {
    auto fallback = named.read(*current->fallback, {current_file.string(), 1, 1});
    if (!fallback) return std::optional<SourcePass>{};  // a Fallback not found casts nothing, as in Unity
    current = fallback->first;
    current_file = fallback->second;
    const shaderlab::SubShader* drawn = shaderlab::drawn_subshader(*current, platform);
    if (!drawn) continue;
    auto sub = with_generated_passes(drawn, current_file, options, platform, generated);
    if (!sub) return fail(sub.error());
    for (const shaderlab::Pass& pass : (*sub)->passes)
      if (pass.kind == shaderlab::PassKind::Program &&
          shaderlab::same_word(shaderlab::tag(pass.tags, "LightMode"), "ShadowCaster"))
        return std::optional<SourcePass>{SourcePass{*sub, &pass, current_file}};
  }
  return std::optional<SourcePass>{};
}

}  // namespace

Result<SourceModule> compile_source(const fs::path& path, hlsl::CompileOptions options,
                                    std::optional<size_t> pass_index, shaderlab::UnityPlatform platform) {
  if (!is_unity_shader(path)) {
    SourceModule source;
    source.module = hlsl::compile_file(path, options);
    return source;
  }

  auto read = shaderlab::read_shader_file(path);
  if (!read) return fail(read.error());
  NamedShaders named(options.include_dirs);
  SourceModule source;
  // A shader without a SubShader the platform runs (shaderlab::drawn_subshader) is drawn by its
  // Fallback, as Unity draws it.
  const shaderlab::Shader* shader = &*read;
  fs::path file = path;
  // drawn_subshader composes each pass's text to read its renderer pragmas: asked once a shader.
  const shaderlab::SubShader* sub = nullptr;
  for (int hops = 0; !(sub = shaderlab::drawn_subshader(*shader, platform)); ++hops) {
    if (!shader->fallback || shader->fallback->empty())
      return fail(ErrorKind::UserInput,
                  "'" + shader->name + "' " + shaderlab::without_subshader(*shader, platform) +
                      (shader->fallback ? " (Fallback Off)" : ""),
                  {file.string(), 1, 1});
    if (hops == kLongestFallbackChain)
      return fail(ErrorKind::UserInput,
                  "'" + shader->name + "' falls back after " + std::to_string(kLongestFallbackChain) +
                      " shaders without a SubShader (a chain that goes round?)",
                  {file.string(), 1, 1});
    auto fallback = named.read(*shader->fallback, {file.string(), 1, 1});
    if (!fallback) return fail(fallback.error());
    source.notes.push_back("'" + shader->name + "' " + shaderlab::without_subshader(*shader, platform) +
                           ": drawn as its Fallback '" + *shader->fallback + "' (" + fallback->second.string() + ")");
    shader = fallback->first;
    file = fallback->second;
  }
  // A surface shader's passes are generated, and drawn as written ones are; so are those of a
  // Fallback's that casts for it (below).
  std::list<shaderlab::SubShader> generated;
  if (sub->surface)
    source.notes.push_back("'" + shader->name +
                           "': its surface program's Meta and Deferred passes, which Unity also "
                           "generates, are not generated: the forward renderer of a still scene draws neither");
  auto drawn_sub = with_generated_passes(sub, file, options, platform, generated);
  if (!drawn_sub) return fail(drawn_sub.error());
  sub = *drawn_sub;
  std::vector<SourcePass> passes(sub->passes.size());
  std::vector<std::pair<std::string, SourceLocation>> grabs;  // each GrabPass's texture
  for (size_t i = 0; i < sub->passes.size(); ++i) {
    const shaderlab::Pass& pass = sub->passes[i];
    passes[i] = {sub, &pass, file};
    if (pass.kind == shaderlab::PassKind::Use) {
      // One that is not found is left out, as Unity leaves it out with an error in its console.
      auto used = used_pass(pass, named, platform);
      if (!used) {
        source.notes.push_back(pass_label(pass, i) + ": not drawn: " + used.error().to_string());
        continue;
      }
      passes[i] = *used;
    }
    const shaderlab::Pass& drawn = *passes[i].pass;
    if (drawn.kind == shaderlab::PassKind::Grab) {
      // Left out; a pass that reads what it grabs is refused below.
      grabs.emplace_back(drawn.grab_texture.empty() ? "_GrabTexture" : drawn.grab_texture, drawn.where);
      source.notes.push_back(pass_label(pass, i) +
                             ": not drawn: GrabPass is not drawn yet, and the drawn passes do not "
                             "read what it grabs");
    } else if (drawn.kind != shaderlab::PassKind::Program) {
      source.notes.push_back(pass_label(pass, i) + ": not drawn: it has no program (fixed-function)");
    } else if (shaderlab::same_word(shaderlab::tag(drawn.tags, "LightMode"), "ForwardAdd")) {
      source.additive_passes.push_back(i);  // drawn once for each further pixel light (forward_lights.h)
    } else if (shaderlab::same_word(shaderlab::tag(drawn.tags, "LightMode"), "ShadowCaster")) {
      if (!source.caster_pass) source.caster_pass = i;  // drawn into a shadow map where a light casts
    } else if (!forward_renderer_draws(drawn)) {
      source.notes.push_back(pass_label(pass, i) +
                             ": not drawn: the forward renderer runs it for what the scene has not");
    } else {
      source.drawn_passes.push_back(i);
    }
  }
  // Without a ShadowCaster of its own, an object casts with its Fallback's, as Unity looks for one.
  if (!source.caster_pass) {
    auto caster = fallback_caster(*shader, file, named, options, platform, generated);
    if (!caster) return fail(caster.error());
    if (*caster) {
      source.caster_pass = passes.size();
      passes.push_back(**caster);
    }
  }
  if (source.drawn_passes.empty()) {
    if (std::all_of(sub->passes.begin(), sub->passes.end(),
                    [](const shaderlab::Pass& pass) { return pass.kind == shaderlab::PassKind::FixedFunction; }))
      return fail(ErrorKind::UserInput,
                  "'" + shader->name +
                      "' is a fixed-function shader (SetTexture, Lighting, Material): Unity generates its " +
                      "programs, xshade compiles only the programs a shader writes (CGPROGRAM or HLSLPROGRAM)",
                  sub->where);
    std::string why;
    for (const std::string& note : source.notes) why += (why.empty() ? "" : "; ") + note;
    return fail(ErrorKind::UserInput,
                "'" + shader->name +
                    "' has no pass the forward renderer draws (a program pass without LightMode, or "
                    "with Always or ForwardBase): " +
                    why,
                sub->where);
  }
  source.pass = pass_index.value_or(source.drawn_passes.front());
  if (source.pass >= passes.size())
    return fail(ErrorKind::Internal, "'" + shader->name + "' has no pass " + std::to_string(source.pass), sub->where);
  // A pass asked for by index (a post step's, compile --pass) that has no program to compile.
  if (passes[source.pass].pass->kind != shaderlab::PassKind::Program)
    return fail(ErrorKind::UserInput,
                pass_label(*passes[source.pass].pass, source.pass) + " of '" + shader->name +
                    "' has no program: a GrabPass, a fixed-function pass or a UsePass not found draws none",
                passes[source.pass].pass->where);
  const SourcePass& drawn = passes[source.pass];
  auto program = shaderlab::pass_program(*drawn.sub, *drawn.pass);
  if (!program) return fail(program.error());
  auto pass_options = pass_compile_options(drawn.file, *program, std::move(options), platform);
  if (!pass_options) return fail(pass_options.error());
  source.module = hlsl::compile_text(drawn.file.string(), std::move(program->text), *pass_options);
  for (const hlsl::TextureResource& texture : source.module->reflection.textures)
    for (const auto& [grabbed, where] : grabs)
      if (texture.used && texture.name == grabbed)
        return fail(ErrorKind::UserInput,
                    "'" + shader->name +
                        "': GrabPass is not drawn yet: xshade's renderer does not copy the target "
                        "between an object's passes, and " +
                        pass_label(*drawn.pass, source.pass) + " reads '" + grabbed + "'",
                    where);
  source.render_state = drawn.pass->state.over(drawn.sub->state);
  source.queue = shaderlab::tag(sub->tags, "Queue");
  source.properties = shader->properties;
  if (source.module->ok()) apply_properties(*shader, source.module->reflection, source.notes);
  return source;
}

std::vector<std::string> with_inspector_keywords(const std::vector<shaderlab::Property>& properties,
                                                 const std::vector<hlsl::KeywordSet>& sets,
                                                 std::vector<std::string> asked,
                                                 const shaderlab::PropertyValue& value) {
  for (const std::string& keyword : shaderlab::material_keywords(properties, value)) {
    for (const hlsl::KeywordSet& set : sets) {
      if (std::find(set.keywords.begin(), set.keywords.end(), keyword) == set.keywords.end()) continue;
      if (std::find_first_of(set.keywords.begin(), set.keywords.end(), asked.begin(), asked.end()) ==
          set.keywords.end())
        asked.push_back(keyword);
      break;
    }
  }
  return asked;
}

}  // namespace xshade::harness
