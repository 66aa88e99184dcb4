#include "harness/render/scene_contract.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <set>

#include <fmt/format.h>

#include "base/spelling.h"
#include "harness/render/renderer_inputs.h"

namespace xshade::harness {
namespace {

void error(ContractProblems& problems, const SourceLocation& where, std::string message) {
  problems.errors.push_back({Severity::Error, where, std::move(message)});
}

// "; did you mean '_Color'?" when a candidate is close, else the names there are.
std::string suggestion(const std::string& name, const std::vector<std::string>& candidates, std::string_view kind) {
  if (auto near = nearest(name, candidates)) return fmt::format("; did you mean '{}'?", *near);
  if (candidates.empty()) return fmt::format("; it declares no {}", kind);
  std::string list;
  for (size_t i = 0; i < candidates.size() && i < 12; ++i) list += (i ? ", " : "") + candidates[i];
  if (candidates.size() > 12) list += fmt::format(" and {} more", candidates.size() - 12);
  return fmt::format("; its {} are {}", kind, list);
}

std::string numbers_text(uint32_t count) { return count == 1 ? "1 number" : fmt::format("{} numbers", count); }

// The uniforms a scene may set: the shader's own, not the renderer's.
std::vector<std::string> settable_uniforms(const ShaderNames& names) {
  std::vector<std::string> out;
  for (const ShaderNames::Uniform& uniform : names.uniforms)
    if (!renderer_uniform(uniform.member.name)) out.push_back(uniform.member.name);
  return out;
}

std::vector<std::string> texture_names(const ShaderNames& names) {
  std::vector<std::string> out;
  for (const ShaderNames::Texture& texture : names.textures)
    if (!renderer_texture(texture.name)) out.push_back(texture.name);
  return out;
}

// A value the scene gives the specialization constant `name` of `owner`: one number, whole for an
// int, uint or bool (0 or 1); a grid may vary a float one only (`value` nullopt).
void check_specialization_value(const std::string& name, uint32_t count, std::optional<float> value,
                                const hlsl::SpecializationConstant& constant, const std::string& owner,
                                const SourceLocation& where, ContractProblems& problems) {
  const std::string type = hlsl::scalar_name(constant.scalar);
  const bool whole = constant.scalar == hlsl::ScalarType::Int || constant.scalar == hlsl::ScalarType::Uint ||
                     constant.scalar == hlsl::ScalarType::Bool;
  if (count != 1) {
    error(problems, where,
          fmt::format("'{}' is a specialization constant ({}) of {}: give it 1 number, not {}", name, type, owner,
                      numbers_text(count)));
  } else if (whole && !value) {
    error(problems, where,
          fmt::format("'{}' is a specialization constant ({}) of {}: a grid may vary a float one only", name, type,
                      owner));
  } else if (whole && value &&
             (std::floor(*value) != *value || (constant.scalar == hlsl::ScalarType::Uint && *value < 0) ||
              (constant.scalar == hlsl::ScalarType::Bool && *value != 0 && *value != 1))) {
    error(problems, where,
          fmt::format("'{}' is a specialization constant ({}) of {}: give it {}, not {}", name, type, owner,
                      constant.scalar == hlsl::ScalarType::Bool ? "0 or 1" : "a whole number", *value));
  }
}

// A value the scene gives `name` (a property, a parameter or a grid rule) against the uniform
// `uniform` of `owner`: the renderer's own names are not the scene's to set, and the numbers
// must be as many as the uniform's components.
void check_value(const std::string& name, uint32_t count, const ShaderNames::Uniform& uniform, const std::string& owner,
                 const SourceLocation& where, ContractProblems& problems) {
  if (renderer_uniform(name)) {
    error(problems, where,
          fmt::format("'{}' is set by the renderer (docs/shader_library.md lists its inputs); a scene cannot set it",
                      name));
    return;
  }
  const UniformMember& member = uniform.member;
  if (member.rows > 1 || member.array_length) {
    error(problems, where,
          fmt::format("'{}' is a {} in {}; a scene sets only float, float2, float3 and float4 values", name,
                      uniform.type, owner));
    return;
  }
  if (member.components() != count)
    error(problems, where,
          fmt::format("'{}' is a {} in {}: give it {}, not {}", name, uniform.type, owner,
                      numbers_text(member.components()), numbers_text(count)));
}

// The uniforms of `names` that the variant reads and that get no value: not the renderer's, not in
// `given`, without a default in the shader. X_ST is Unity's tiling and offset, (1, 1, 0, 0) unless given.
void check_uniforms_have_values(const ShaderNames& names, const std::set<std::string>& given, const std::string& owner,
                                const std::string& how_to_set, const SourceLocation& where,
                                ContractProblems& problems) {
  for (const ShaderNames::Uniform& uniform : names.uniforms) {
    const std::string& name = uniform.member.name;
    if (!uniform.read || uniform.has_default || given.count(name) || renderer_uniform(name) || name.ends_with("_ST"))
      continue;
    error(problems, where,
          fmt::format("{}: uniform '{}' ({}) has no value: the renderer does not give it, the scene does not set it "
                      "and the shader declares no default; set {}.{}, or give it an initializer in the shader",
                      owner, name, uniform.type, how_to_set, name));
  }
}

// Every texture a scene or a default gives holds colour; a comparison reads depth.
constexpr const char* kComparedTexture =
    "with a comparison sampler, a shadow map's depth: no texture a scene names holds depth, only the scene's own "
    "(a post pass's scene.depth source)";

// A texture the variant samples and nobody gives: its declared default, or an error saying how
// to give one.
void default_or_error(const ShaderNames::Texture& texture, const std::string& owner, const std::string& not_given,
                      const std::string& table, const SourceLocation& where,
                      std::map<std::string, TextureRef>& defaults, ContractProblems& problems) {
  if (texture.comparison) {
    error(problems, where,
          fmt::format("{} samples '{}' {}, which {}", owner, texture.name, kComparedTexture, not_given));
    return;
  }
  if (auto origin = renderer_default_texture(texture.name)) {
    TextureRef ref;
    ref.source = *origin;
    ref.where = where;
    defaults.emplace(texture.name, ref);
    return;
  }
  if (auto origin = built_in_texture(texture.default_texture)) {
    TextureRef ref;
    ref.source = *origin;
    ref.where = where;
    defaults.emplace(texture.name, ref);
    problems.notes.push_back(
        fmt::format("{}: texture {} is the shader's default \"{}\"", owner, texture.name, texture.default_texture));
    return;
  }
  error(problems, where,
        fmt::format("{} samples '{}', which {} and the shader declares no default: give it in the scene "
                    "({}.{} = \"white\" or an image path), or declare a default in the shader "
                    "(Texture2D {} <string Default = \"white\";>;)",
                    owner, texture.name, not_given, table, texture.name, texture.name));
}

}  // namespace

const ShaderNames::Uniform* ShaderNames::uniform(const std::string& name) const {
  for (const Uniform& u : uniforms)
    if (u.member.name == name) return &u;
  return nullptr;
}

const ShaderNames::Texture* ShaderNames::texture(const std::string& name) const {
  for (const Texture& t : textures)
    if (t.name == name) return &t;
  return nullptr;
}

const StorageBufferInput* ShaderNames::buffer(const std::string& name) const {
  for (const StorageBufferInput& b : buffers)
    if (b.name == name) return &b;
  return nullptr;
}

const hlsl::SpecializationConstant* ShaderNames::specialization_constant(const std::string& name) const {
  for (const hlsl::SpecializationConstant& c : specialization_constants)
    if (c.name == name) return &c;
  return nullptr;
}

ShaderNames shader_names(const std::string& source, const hlsl::Reflection& reflection) {
  ShaderNames names;
  names.source = source;
  const ShaderInterface interface = shader_interface(reflection);
  for (const UniformBlock& block : interface.uniform_blocks)
    for (const UniformMember& member : block.members) {
      ShaderNames::Uniform uniform{member, {}, false, member.read};
      const PropertyDefault* property = interface.find_property(member.name);
      uniform.has_default = property && !property->value.empty();
      for (const hlsl::ConstantBuffer& buffer : reflection.constant_buffers)
        for (const hlsl::ConstantBufferMember& declared : buffer.members)
          if (declared.name == member.name) {
            uniform.type = declared.type.name();
          }
      names.uniforms.push_back(std::move(uniform));
    }
  for (const hlsl::TextureResource& texture : reflection.textures) {
    ShaderNames::Texture out{texture.name, texture.used, {}, texture.comparison};
    for (const hlsl::Property& property : reflection.properties)
      if (property.name == texture.name) out.default_texture = property.default_texture;
    names.textures.push_back(std::move(out));
  }
  names.buffers = interface.storage_buffers;
  names.specialization_constants = reflection.specialization_constants;
  names.keyword_sets = reflection.keyword_sets;
  return names;
}

ShaderNames merge_names(ShaderNames into, const ShaderNames& other) {
  for (const ShaderNames::Uniform& uniform : other.uniforms) {
    auto found = std::find_if(into.uniforms.begin(), into.uniforms.end(),
                              [&](const ShaderNames::Uniform& u) { return u.member.name == uniform.member.name; });
    if (found == into.uniforms.end()) {
      into.uniforms.push_back(uniform);
      continue;
    }
    found->read = found->read || uniform.read;
    found->has_default = found->has_default || uniform.has_default;
  }
  for (const StorageBufferInput& buffer : other.buffers)
    if (!into.buffer(buffer.name)) into.buffers.push_back(buffer);
  for (const hlsl::SpecializationConstant& constant : other.specialization_constants)
    if (!into.specialization_constant(constant.name)) into.specialization_constants.push_back(constant);
  for (const ShaderNames::Texture& texture : other.textures) {
    auto found = std::find_if(into.textures.begin(), into.textures.end(),
                              [&](const ShaderNames::Texture& t) { return t.name == texture.name; });
    if (found == into.textures.end()) {
      into.textures.push_back(texture);
      continue;
    }
    found->sampled = found->sampled || texture.sampled;
    if (found->default_texture.empty()) found->default_texture = texture.default_texture;
  }
  into.block_properties.insert(other.block_properties.begin(), other.block_properties.end());
  for (const hlsl::KeywordSet& set : other.keyword_sets)
    if (std::find_if(into.keyword_sets.begin(), into.keyword_sets.end(),
                     [&](const hlsl::KeywordSet& s) { return s.keywords == set.keywords; }) == into.keyword_sets.end())
      into.keyword_sets.push_back(set);
  return into;
}

void check_keywords(const std::vector<std::string>& keywords, const SceneLocations& where, const ShaderNames& source,
                    const std::string& owner, ContractProblems& problems) {
  std::vector<std::string> declared;
  for (const hlsl::KeywordSet& set : source.keyword_sets)
    for (const std::string& keyword : set.keywords)
      if (keyword.find_first_not_of('_') != std::string::npos) declared.push_back(keyword);
  for (const std::string& keyword : keywords) {
    if (std::find(declared.begin(), declared.end(), keyword) != declared.end()) continue;
    error(problems, where.of("keywords." + keyword),
          fmt::format("{} declares no keyword '{}' (#pragma multi_compile or shader_feature){}", owner, keyword,
                      suggestion(keyword, declared, "keywords")));
  }
}

std::map<std::string, TextureRef> check_object(const SceneObject& object, const ShaderNames& material,
                                               ContractProblems& problems) {
  const std::string owner = "material '" + material.source + "'";
  std::set<std::string> given;
  // `value`: the object's number (nullopt for a grid rule's, which differ from cell to cell).
  const auto check_named = [&](const std::string& name, uint32_t count, const std::string& key,
                               std::optional<float> value) {
    given.insert(name);
    const SourceLocation& where = object.where.of(key);
    if (const ShaderNames::Uniform* uniform = material.uniform(name)) {
      check_value(name, count, *uniform, owner, where, problems);
      return;
    }
    if (const hlsl::SpecializationConstant* constant = material.specialization_constant(name)) {
      check_specialization_value(name, count, value, *constant, owner, where, problems);
      return;
    }
    if (auto property = material.block_properties.find(name); property != material.block_properties.end()) {
      if (count != property->second)
        error(problems, where,
              fmt::format("'{}' is a property of {} with {}: give it {}", name, owner, numbers_text(property->second),
                          numbers_text(property->second)));
      return;
    }
    error(problems, where,
          fmt::format("{} has no property '{}'{}", owner, name,
                      suggestion(name, settable_uniforms(material), "properties")));
  };
  for (const auto& [name, value] : object.properties)
    check_named(name, value.count, "properties." + name, value.components[0]);
  if (object.grid)
    for (const auto& [name, rule] : object.grid->vary)
      if (!object.properties.count(name)) check_named(name, rule.from.count, "grid.vary." + name, std::nullopt);

  for (const auto& [name, ref] : object.textures) {
    if (const ShaderNames::Texture* texture = material.texture(name); texture && !renderer_texture(name)) {
      if (texture->comparison)
        error(problems, object.where.of("textures." + name),
              fmt::format("{} samples '{}' {}", owner, name, kComparedTexture));
      continue;
    }
    const std::string why = renderer_texture(name)
                                ? fmt::format("; '{}' is the renderer's (the scene's environment)", name)
                                : suggestion(name, texture_names(material), "textures");
    error(problems, object.where.of("textures." + name), fmt::format("{} has no texture '{}'{}", owner, name, why));
  }

  std::vector<std::string> buffer_names;
  for (const StorageBufferInput& buffer : material.buffers) buffer_names.push_back(buffer.name);
  for (const auto& [name, ref] : object.buffers) {
    const SourceLocation& where = object.where.of("buffers." + name);
    const StorageBufferInput* buffer = material.buffer(name);
    if (!buffer) {
      error(problems, where,
            fmt::format("{} reads no buffer '{}'{}", owner, name, suggestion(name, buffer_names, "buffers")));
      continue;
    }
    if (!ref.numbers.empty() && ref.numbers.size() % buffer->words.size() != 0)
      error(problems, where,
            fmt::format("an element of {}'s buffer '{}' is {} 32-bit words: give a multiple of {} numbers, not {}",
                        owner, name, buffer->words.size(), buffer->words.size(), ref.numbers.size()));
  }

  std::map<std::string, TextureRef> defaults;
  const SourceLocation& material_line = object.where.of("material");
  for (const StorageBufferInput& buffer : material.buffers)
    if (!object.buffers.count(buffer.name))
      error(problems, material_line,
            fmt::format("object '{}': {} reads the buffer '{}', which has no default: give it in [object.buffers] "
                        "({} = [numbers] or \"file.bin\")",
                        object.name, owner, buffer.name, buffer.name));
  for (const ShaderNames::Texture& texture : material.textures) {
    if (!texture.sampled || object.textures.count(texture.name) || renderer_texture(texture.name)) continue;
    default_or_error(texture, fmt::format("object '{}': {}", object.name, owner), "the object's textures do not give",
                     "textures", material_line, defaults, problems);
  }
  check_uniforms_have_values(material, given, fmt::format("object '{}': {}", object.name, owner), "properties",
                             material_line, problems);
  return defaults;
}

std::vector<std::map<std::string, TextureRef>> check_effect(const PostEffect& effect,
                                                            const std::vector<PassNames>& passes,
                                                            ContractProblems& problems) {
  const std::string owner = "post effect '" + effect.effect + "'";
  std::vector<std::string> parameters;
  std::vector<std::string> textures;
  for (const PassNames& pass : passes) {
    for (const std::string& name : settable_uniforms(pass.names))
      if (std::find(parameters.begin(), parameters.end(), name) == parameters.end()) parameters.push_back(name);
    for (const std::string& name : texture_names(pass.names))
      if (std::find(textures.begin(), textures.end(), name) == textures.end()) textures.push_back(name);
  }

  for (const auto& [name, value] : effect.parameters) {
    const SourceLocation& where = effect.where.of("parameters." + name);
    bool found = false;
    for (const PassNames& pass : passes)
      if (const ShaderNames::Uniform* uniform = pass.names.uniform(name)) {
        check_value(name, value.count, *uniform, owner, where, problems);
        found = true;
        break;
      }
    if (!found)
      error(problems, where,
            fmt::format("{} has no parameter '{}'{}", owner, name, suggestion(name, parameters, "parameters")));
  }
  for (const auto& [name, ref] : effect.textures) {
    if (std::find(textures.begin(), textures.end(), name) == textures.end())
      error(problems, effect.where.of("textures." + name),
            fmt::format("{} has no texture '{}'{}", owner, name, suggestion(name, textures, "textures")));
    for (const PassNames& pass : passes)
      if (const ShaderNames::Texture* texture = pass.names.texture(name); texture && texture->comparison) {
        error(problems, effect.where.of("textures." + name),
              fmt::format("{} samples '{}' {}", owner, name, kComparedTexture));
        break;
      }
  }

  std::set<std::string> given;
  for (const auto& [name, value] : effect.parameters) given.insert(name);
  const SourceLocation& effect_line = effect.where.of("effect");
  std::vector<std::map<std::string, TextureRef>> defaults(passes.size());
  for (size_t p = 0; p < passes.size(); ++p) {
    const PassNames& pass = passes[p];
    const std::string pass_owner = fmt::format("{} pass '{}'", owner, pass.declaration.name);
    for (const StorageBufferInput& buffer : pass.names.buffers)
      error(problems, effect_line,
            fmt::format("{} reads the buffer '{}', and a post effect cannot be given buffers yet (an object can, in "
                        "[object.buffers])",
                        pass_owner, buffer.name));
    for (const ShaderNames::Texture& texture : pass.names.textures) {
      if (!texture.sampled || effect.textures.count(texture.name) || renderer_texture(texture.name)) continue;
      const auto& inputs = pass.declaration.inputs;
      if (std::any_of(inputs.begin(), inputs.end(),
                      [&](const hlsl::PassInput& i) { return i.texture == texture.name; }))
        continue;
      // Unity's depth texture is the scene's depth where the pass names no other source.
      if (texture.name == "_CameraDepthTexture") continue;
      default_or_error(
          texture, pass_owner,
          "neither its sources (its #pragma pass line, or its step in passes) nor the effect's textures give",
          "textures", effect_line, defaults[p], problems);
    }
    check_uniforms_have_values(pass.names, given, pass_owner, "parameters", effect_line, problems);
  }
  return defaults;
}

}  // namespace xshade::harness
