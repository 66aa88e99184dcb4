// The reflection as JSON (docs/hlsl_like.md, "Reflection"): what `xshade compile --reflect` prints.
#include <nlohmann/json.hpp>

#include "hlsl_like/reflection.h"

namespace xshade::hlsl {

namespace {

nlohmann::json type_json(const Type& type) { return type.name(); }

const char* interpolation_name(Interpolation interpolation) {
  switch (interpolation) {
    case Interpolation::Default: return "linear";
    case Interpolation::Linear: return "linear";
    case Interpolation::Centroid: return "centroid";
    case Interpolation::NoInterpolation: return "nointerpolation";
    case Interpolation::NoPerspective: return "noperspective";
    case Interpolation::Sample: return "sample";
  }
  return "linear";
}

nlohmann::json stage_json(const std::vector<StageVariable>& variables) {
  nlohmann::json list = nlohmann::json::array();
  for (const StageVariable& v : variables)
    list.push_back({{"semantic", v.semantic},
                    {"type", type_json(v.type)},
                    {"location", v.location},
                    {"interpolation", interpolation_name(v.interpolation)}});
  return list;
}

}  // namespace

std::string reflection_json(const Reflection& reflection) {
  nlohmann::json json;
  json["entry_points"] = {{"vertex", reflection.vertex_entry}, {"fragment", reflection.fragment_entry}};
  json["vertex_inputs"] = stage_json(reflection.vertex_inputs);
  json["varyings"] = stage_json(reflection.varyings);
  json["fragment_outputs"] = stage_json(reflection.fragment_outputs);
  json["constant_buffers"] = nlohmann::json::array();
  for (const ConstantBuffer& buffer : reflection.constant_buffers) {
    nlohmann::json members = nlohmann::json::array();
    for (const ConstantBufferMember& m : buffer.members)
      members.push_back({{"name", m.name},
                         {"type", type_json(m.type)},
                         {"offset", m.offset},
                         {"size", m.size},
                         {"row_major", m.row_major}});
    nlohmann::json entry = {
        {"name", buffer.name}, {"binding", buffer.binding}, {"size", buffer.size}, {"members", members}};
    if (buffer.set) entry["set"] = buffer.set;
    if (buffer.count > 1) entry["count"] = buffer.count;
    if (buffer.push_constant) entry["push_constant"] = true;
    json["constant_buffers"].push_back(entry);
  }
  json["textures"] = nlohmann::json::array();
  for (const TextureResource& t : reflection.textures) {
    nlohmann::json texture = {{"name", t.name},
                              {"kind", texture_shape_name(t.shape, t.kind == TextureKind::Sampler)},
                              {"binding", t.binding},
                              {"used", t.used}};
    if (t.texel != ScalarType::Float) texture["texel"] = scalar_name(t.texel);
    if (t.comparison) texture["comparison"] = true;
    if (!t.sampler.empty()) texture["sampler"] = t.sampler;
    if (t.sampler_binding) texture["sampler_binding"] = *t.sampler_binding;
    if (t.set) texture["set"] = t.set;
    if (t.count > 1) texture["count"] = t.count;
    json["textures"].push_back(texture);
  }
  json["samplers"] = nlohmann::json::array();
  for (const SamplerResource& s : reflection.samplers) {
    nlohmann::json sampler = {{"name", s.name}, {"binding", s.binding}, {"used", s.used}};
    if (s.comparison) sampler["comparison"] = true;
    if (s.set) sampler["set"] = s.set;
    if (s.count > 1) sampler["count"] = s.count;
    json["samplers"].push_back(sampler);
  }
  json["buffers"] = nlohmann::json::array();
  for (const StorageBufferResource& b : reflection.buffers) {
    nlohmann::json buffer = {{"name", b.name},
                             {"kind", buffer_kind_name(b.kind)},
                             {"element", type_json(b.element)},
                             {"stride", b.stride},
                             {"binding", b.binding},
                             {"used", b.used}};
    if (b.set) buffer["set"] = b.set;
    json["buffers"].push_back(buffer);
  }
  json["specialization_constants"] = nlohmann::json::array();
  for (const SpecializationConstant& c : reflection.specialization_constants)
    json["specialization_constants"].push_back({{"name", c.name}, {"id", c.id}, {"type", scalar_name(c.scalar)}});
  json["properties"] = nlohmann::json::array();
  for (const Property& p : reflection.properties) {
    nlohmann::json property = {{"name", p.name}, {"display_name", p.display_name}, {"type", type_json(p.type)}};
    if (p.min) property["min"] = *p.min;
    if (p.max) property["max"] = *p.max;
    if (!p.default_value.empty()) property["default"] = p.default_value;
    if (!p.default_texture.empty()) property["default"] = p.default_texture;
    json["properties"].push_back(property);
  }
  json["keywords"] = nlohmann::json::array();
  for (const KeywordSet& set : reflection.keyword_sets)
    json["keywords"].push_back(
        {{"keywords", set.keywords}, {"pragma", set.shader_feature ? "shader_feature" : "multi_compile"}});
  json["active_keywords"] = reflection.active_keywords;
  if (reflection.clip_distances) json["clip_distances"] = reflection.clip_distances;
  if (reflection.cull_distances) json["cull_distances"] = reflection.cull_distances;
  if (reflection.reads_shading_rate) json["reads_shading_rate"] = true;
  return json.dump(2);
}

}  // namespace xshade::hlsl
