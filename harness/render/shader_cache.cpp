#include "harness/render/shader_cache.h"

#include <fmt/format.h>
#include <xxhash.h>
#include <nlohmann/json.hpp>

#include <fstream>

#include "base/file_io.h"
#include "spirv/spirv_compiler.h"

namespace xshade::harness {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

json stage_json(const ShaderStageSource& stage) {
  return {{"glsl", stage.glsl},
          {"spirv", stage.spirv},
          {"entry_point", stage.entry_point},
          {"name", stage.name},
          {"source_files", stage.source_files}};
}

ShaderStageSource stage_from_json(const json& j) {
  ShaderStageSource stage;
  stage.glsl = j.at("glsl");
  stage.spirv = j.at("spirv").get<std::vector<uint32_t>>();
  stage.entry_point = j.at("entry_point");
  stage.name = j.at("name");
  stage.source_files = j.at("source_files").get<std::vector<std::string>>();
  return stage;
}

std::string variant_json(const CompiledVariant& variant) {
  const ProgramDesc& p = variant.program;
  json blocks = json::array();
  for (const UniformBlockSlot& b : p.layout.uniform_blocks)
    blocks.push_back({{"name", b.name},
                      {"binding", b.binding},
                      {"size", b.size},
                      {"push_constant", b.push_constant},
                      {"glsl_block", b.glsl_block}});
  json textures = json::array();
  for (const TextureSlot& t : p.layout.textures) {
    json slot{{"name", t.name},
              {"binding", t.binding},
              {"dimension", int(t.shape.dimension)},
              {"multisampled", t.shape.multisampled},
              {"comparison", t.comparison},
              {"texel", int(t.texel)},
              {"image_only", t.image_only},
              {"filtered_in_shader", t.filtered_in_shader},
              {"glsl_name", t.glsl_name}};
    if (t.sampler_binding) slot["sampler_binding"] = *t.sampler_binding;
    textures.push_back(std::move(slot));
  }
  json storage_buffers = json::array();
  for (const StorageBufferSlot& b : p.layout.storage_buffers)
    storage_buffers.push_back({{"name", b.name}, {"binding", b.binding}, {"glsl_block", b.glsl_block}});
  return json{{"name", p.name},
              {"fullscreen", p.fullscreen},
              {"clip_distances", p.clip_distances},
              {"vertex", stage_json(p.vertex)},
              {"fragment", stage_json(p.fragment)},
              {"uniform_blocks", blocks},
              {"textures", textures},
              {"storage_buffers", storage_buffers},
              {"specialization", p.specialization},
              {"interface", shader_interface_json(variant.interface)}}
      .dump();
}

std::optional<CompiledVariant> variant_from_json(const std::string& text) {
  try {
    const json j = json::parse(text);
    CompiledVariant variant;
    ProgramDesc& p = variant.program;
    p.name = j.at("name");
    p.fullscreen = j.at("fullscreen");
    p.clip_distances = j.at("clip_distances");
    p.vertex = stage_from_json(j.at("vertex"));
    p.fragment = stage_from_json(j.at("fragment"));
    for (const json& b : j.at("uniform_blocks"))
      p.layout.uniform_blocks.push_back(
          {b.at("name"), b.at("binding"), b.at("size"), b.at("push_constant"), b.at("glsl_block")});
    for (const json& t : j.at("textures")) {
      TextureSlot slot{t.at("name"), t.at("binding"), std::nullopt};
      if (t.contains("sampler_binding")) slot.sampler_binding = t.at("sampler_binding").get<uint32_t>();
      slot.shape = {TextureDimension(t.at("dimension").get<int>()), t.at("multisampled").get<bool>()};
      slot.comparison = t.at("comparison");
      slot.texel = TexelKind(t.at("texel").get<int>());
      slot.image_only = t.at("image_only");
      slot.filtered_in_shader = t.at("filtered_in_shader");
      slot.glsl_name = t.at("glsl_name");
      p.layout.textures.push_back(std::move(slot));
    }
    p.specialization = j.at("specialization").get<std::map<uint32_t, uint32_t>>();
    for (const json& b : j.at("storage_buffers"))
      p.layout.storage_buffers.push_back({b.at("name"), b.at("binding"), b.at("glsl_block")});
    auto interface = parse_shader_interface_json(j.at("interface"));
    if (!interface) return std::nullopt;
    variant.interface = std::move(*interface);
    return variant;
  } catch (const json::exception&) {
    return std::nullopt;  // a damaged entry is a miss: the variant is compiled again
  }
}

// Every entry is its contents' hash on the first line, then the contents: a flipped bit, an
// edited GLSL line or a torn write after a power cut makes the two disagree, and the entry is a
// miss instead of a program that renders something else or crashes the driver.
std::string sealed(const std::string& contents) { return content_hash(contents) + "\n" + contents; }

// The contents of a sealed entry, or nullopt when they do not match their hash.
std::optional<std::string> unsealed(const std::string& entry) {
  const size_t newline = entry.find('\n');
  if (newline != 32) return std::nullopt;
  std::string contents = entry.substr(newline + 1);
  if (content_hash(contents) != entry.substr(0, newline)) return std::nullopt;
  return contents;
}

Error damaged(const fs::path& path, const VariantRequest& request) {
  return Error{fmt::format("the shader cache entry {} was damaged (its contents do not match their hash), so {} was "
                           "compiled again and the entry rewritten",
                           path.string(), request.label()),
               {},
               {},
               ErrorKind::Internal};
}

}  // namespace

namespace {

std::string hex(const XXH128_hash_t& hash) {
  char text[33];
  std::snprintf(text, sizeof text, "%016llx%016llx", static_cast<unsigned long long>(hash.high64),
                static_cast<unsigned long long>(hash.low64));
  return text;
}

}  // namespace

std::string content_hash(std::string_view bytes) { return hex(XXH3_128bits(bytes.data(), bytes.size())); }

// The executable is hashed as it is read, a chunk at a time: every worker process computes this,
// and reading the 14 MB file into one string and copying it took a quarter of a second of each
// process's start.
std::string compiler_identity() {
  static const std::string identity = [] {
    XXH3_state_t* state = XXH3_createState();
    XXH3_128bits_reset(state);
    std::ifstream executable("/proc/self/exe", std::ios::binary);
    if (!executable) XXH3_128bits_update(state, "unknown executable", 18);
    std::vector<char> chunk(size_t(1) << 20);
    while (executable.read(chunk.data(), std::streamsize(chunk.size())) || executable.gcount() > 0)
      XXH3_128bits_update(state, chunk.data(), size_t(executable.gcount()));
    const std::string version = "\n" + spirv::compiler_version();
    XXH3_128bits_update(state, version.data(), version.size());
    const std::string hash = hex(XXH3_128bits_digest(state));
    XXH3_freeState(state);
    return hash;
  }();
  return identity;
}

ShaderCache::ShaderCache(fs::path directory, std::string compiler_identity)
    : directory_(std::move(directory)), compiler_identity_(std::move(compiler_identity)) {}

std::string ShaderCache::request_key(const VariantRequest& request, Lane lane) const {
  // The request's label names everything that makes a variant (entry, pass, Unity platform,
  // keywords, half), so that a field added to the request is in the key without being listed here
  // again.
  return content_hash(compiler_identity_ + "\n" + std::string(lane_name(lane)) + "\n" + request.source.string() + "\n" +
                      request.label());
}

CacheLookup ShaderCache::look_up(const VariantRequest& request, Lane lane) const {
  const fs::path manifest_path = directory_ / (request_key(request, lane) + ".manifest");
  const std::optional<std::string> manifest_entry = read_file(manifest_path);
  if (!manifest_entry) return {};
  const std::optional<std::string> manifest_text = unsealed(*manifest_entry);
  if (!manifest_text) return {std::nullopt, damaged(manifest_path, request)};
  fs::path variant_path;
  std::vector<fs::path> dependencies;
  try {
    const json manifest = json::parse(*manifest_text);
    for (const json& dependency : manifest.at("dependencies")) {
      const std::optional<std::string> contents = read_file(dependency.at("path").get<std::string>());
      if (!contents || content_hash(*contents) != dependency.at("hash").get<std::string>()) return {};
      dependencies.push_back(dependency.at("path").get<std::string>());
    }
    variant_path = directory_ / (manifest.at("result").get<std::string>() + ".variant");
  } catch (const json::exception&) {
    return {std::nullopt, damaged(manifest_path, request)};  // sealed, yet not what store() writes
  }
  const std::optional<std::string> stored = read_file(variant_path);
  if (!stored) return {};
  const std::optional<std::string> variant_text = unsealed(*stored);
  std::optional<CompiledVariant> variant = variant_text ? variant_from_json(*variant_text) : std::nullopt;
  if (!variant) return {std::nullopt, damaged(variant_path, request)};
  return {std::move(variant), std::nullopt, std::move(dependencies)};
}

std::optional<CompiledVariant> ShaderCache::find(const VariantRequest& request, Lane lane) const {
  return look_up(request, lane).variant;
}

Result<void> ShaderCache::store(const VariantRequest& request, Lane lane, const CompiledVariant& variant,
                                const std::vector<fs::path>& dependencies) const {
  std::error_code error;
  fs::create_directories(directory_, error);
  if (error)
    return fail(ErrorKind::Backend, "cannot create the shader cache " + directory_.string() + ": " + error.message());
  const std::string key = request_key(request, lane);
  json listed = json::array();
  std::string result_key = key;
  for (const fs::path& path : dependencies) {
    const std::optional<std::string> contents = read_file(path);
    if (!contents)
      return fail(ErrorKind::Backend, "cannot read " + path.string() + " to record it in the shader cache");
    const std::string hash = content_hash(*contents);
    listed.push_back({{"path", fs::absolute(path).lexically_normal().string()}, {"hash", hash}});
    result_key += hash;
  }
  result_key = content_hash(result_key);
  // The program before the manifest that names it, so that a reader never finds a manifest
  // without its program. Several processes may store the same entry at once: each writes its
  // own temporary and renames it (write_file_atomically), and the entries they write are equal.
  if (auto written = write_file_atomically(directory_ / (result_key + ".variant"), sealed(variant_json(variant)));
      !written)
    return written;
  return write_file_atomically(
      directory_ / (key + ".manifest"),
      sealed(json{{"dependencies", listed}, {"result", result_key}, {"request", request.label()}}.dump(1)));
}

}  // namespace xshade::harness
