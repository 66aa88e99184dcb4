#include "harness/backend/backend.h"

#include <algorithm>
#include <bit>
#include <cctype>
#include <type_traits>

namespace xshade::harness {

size_t bytes_per_texel(TextureFormat format) {
  switch (format) {
    case TextureFormat::Rgba8Unorm:
    case TextureFormat::Rgba8Srgb:
    case TextureFormat::R32Float:
    case TextureFormat::Depth32Float: return 4;
    case TextureFormat::Rgba32Float:
    case TextureFormat::Rgba32Uint:
    case TextureFormat::Rgba32Sint: return 16;
  }
  return 0;
}

const char* format_name(TextureFormat format) {
  switch (format) {
    case TextureFormat::Rgba8Unorm: return "Rgba8Unorm";
    case TextureFormat::Rgba8Srgb: return "Rgba8Srgb";
    case TextureFormat::Rgba32Float: return "Rgba32Float";
    case TextureFormat::R32Float: return "R32Float";
    case TextureFormat::Depth32Float: return "Depth32Float";
    case TextureFormat::Rgba32Uint: return "Rgba32Uint";
    case TextureFormat::Rgba32Sint: return "Rgba32Sint";
  }
  return "?";
}

TexelKind texel_kind(TextureFormat format) {
  switch (format) {
    case TextureFormat::Rgba32Uint: return TexelKind::Uint;
    case TextureFormat::Rgba32Sint: return TexelKind::Int;
    default: return TexelKind::Float;
  }
}

const char* texel_kind_name(TexelKind kind) {
  switch (kind) {
    case TexelKind::Float: return "float";
    case TexelKind::Int: return "int";
    case TexelKind::Uint: return "uint";
  }
  return "?";
}

std::string shape_name(TextureShape shape) {
  switch (shape.dimension) {
    case TextureDimension::Tex1D: return "Texture1D";
    case TextureDimension::Tex1DArray: return "Texture1DArray";
    case TextureDimension::Tex2D: return shape.multisampled ? "Texture2DMS" : "Texture2D";
    case TextureDimension::Tex2DArray: return shape.multisampled ? "Texture2DMSArray" : "Texture2DArray";
    case TextureDimension::Tex3D: return "Texture3D";
    case TextureDimension::Cube: return "TextureCube";
    case TextureDimension::CubeArray: return "TextureCubeArray";
  }
  return "?";
}

bool is_array(TextureDimension dimension) {
  return dimension == TextureDimension::Tex1DArray || dimension == TextureDimension::Tex2DArray ||
         dimension == TextureDimension::CubeArray;
}

size_t level_bytes(const TextureData& texture, uint32_t level) {
  const size_t width = std::max<uint32_t>(1, texture.width >> level);
  const size_t height = std::max<uint32_t>(1, texture.height >> level);
  const size_t layers =
      texture.dimension == TextureDimension::Tex3D ? std::max<uint32_t>(1, texture.layers >> level) : texture.layers;
  return width * height * layers * bytes_per_texel(texture.format);
}

Result<void> validate_texture(const TextureData& texture, uint32_t max_size) {
  const std::string what = "upload_texture: " + shape_name(texture.shape());
  const std::string size =
      std::to_string(texture.width) + "x" + std::to_string(texture.height) + "x" + std::to_string(texture.layers);
  if (texture.width == 0 || texture.height == 0 || texture.layers == 0 || texture.levels.empty())
    return fail(ErrorKind::Internal,
                what + ": the texture is empty (" + size + ", " + std::to_string(texture.levels.size()) + " levels)");
  const TextureDimension dimension = texture.dimension;
  const bool one_d = dimension == TextureDimension::Tex1D || dimension == TextureDimension::Tex1DArray;
  if (one_d && texture.height != 1)
    return fail(ErrorKind::Internal, what + ": a 1D texture has height 1, not " + std::to_string(texture.height));
  if (!is_array(dimension) && dimension != TextureDimension::Tex3D && dimension != TextureDimension::Cube &&
      texture.layers != 1)
    return fail(ErrorKind::Internal, what + ": has " + std::to_string(texture.layers) +
                                         " layers; only arrays, cubes and 3D textures have more than one");
  if (dimension == TextureDimension::Cube && texture.layers != 6)
    return fail(ErrorKind::Internal, what + ": a cube has 6 faces (+X, -X, +Y, -Y, +Z, -Z), not " +
                                         std::to_string(texture.layers) + " layers");
  if (dimension == TextureDimension::CubeArray && texture.layers % 6 != 0)
    return fail(ErrorKind::Internal,
                what + ": a cube array has 6 layers per cube, not " + std::to_string(texture.layers));
  if ((dimension == TextureDimension::Cube || dimension == TextureDimension::CubeArray) &&
      texture.width != texture.height)
    return fail(ErrorKind::Internal, what + ": a cube's faces are square, not " + std::to_string(texture.width) + "x" +
                                         std::to_string(texture.height));
  const uint32_t extent = dimension == TextureDimension::Tex3D
                              ? std::max({texture.width, texture.height, texture.layers})
                              : std::max(texture.width, texture.height);
  if (extent > max_size || (is_array(dimension) && texture.layers > max_size))
    return fail(ErrorKind::Backend,
                what + ": size " + size + " exceeds the device limit of " + std::to_string(max_size));
  if (texture.samples > 1) {
    if (dimension != TextureDimension::Tex2D && dimension != TextureDimension::Tex2DArray)
      return fail(ErrorKind::Internal, what + ": only 2D textures and 2D arrays can be multisampled");
    if (texture.levels.size() != 1)
      return fail(ErrorKind::Internal,
                  what + ": a multisampled texture has one level, not " + std::to_string(texture.levels.size()));
    // Filled by a draw of the level-0 data into every sample (see the backends): a colour
    // format that a shader writes unchanged. Depth would need a depth-writing draw and sRGB an
    // encode after the sampler's decode; neither is needed yet.
    if (texture.format == TextureFormat::Depth32Float || texture.format == TextureFormat::Rgba8Srgb)
      return fail(ErrorKind::Internal, what + ": a multisampled " + format_name(texture.format) +
                                           " texture is not supported (" + "use a linear colour or integer format)");
  }
  if (texture.samples == 0) return fail(ErrorKind::Internal, what + ": 0 samples per texel");
  if (texture.format == TextureFormat::Depth32Float && dimension == TextureDimension::Tex3D)
    return fail(ErrorKind::Internal, what + ": neither API has 3D depth textures");
  const uint32_t full_chain = uint32_t(std::bit_width(extent));
  if (texture.levels.size() > full_chain)
    return fail(ErrorKind::Internal, what + ": " + std::to_string(texture.levels.size()) + " mip levels given but a " +
                                         size + " texture has at most " + std::to_string(full_chain));
  for (uint32_t level = 0; level < texture.levels.size(); ++level) {
    const uint32_t w = std::max<uint32_t>(1, texture.width >> level),
                   h = std::max<uint32_t>(1, texture.height >> level);
    const size_t expected = level_bytes(texture, level);
    if (texture.levels[level].size() != expected)
      return fail(ErrorKind::Internal,
                  what + ": mip level " + std::to_string(level) + " has " +
                      std::to_string(texture.levels[level].size()) + " bytes, expected " + std::to_string(expected) +
                      " (" + std::to_string(w) + "x" + std::to_string(h) + ", " +
                      std::to_string(expected / (size_t(w) * h * bytes_per_texel(texture.format))) + " layers, " +
                      std::to_string(bytes_per_texel(texture.format)) + " bytes a texel)");
  }
  return {};
}

Result<void> check_bound_texture(const TextureSlot& slot, const BoundTextureFacts& bound, const SamplerDesc& sampler,
                                 const std::string& where) {
  const std::string texture = where + ": texture '" + slot.name + "'";
  if (bound.shape != slot.shape)
    return fail(ErrorKind::Internal, texture + " is declared " + shape_name(slot.shape) + ", but " + bound.label +
                                         " is a " + shape_name(bound.shape));
  const TexelKind kind = texel_kind(bound.format);
  if (kind != slot.texel)
    return fail(ErrorKind::Internal, texture + " reads " + texel_kind_name(slot.texel) + " texels, but " + bound.label +
                                         " is " + format_name(bound.format) + " (" + texel_kind_name(kind) +
                                         " texels)");
  if (slot.comparison && bound.format != TextureFormat::Depth32Float)
    return fail(ErrorKind::Internal,
                texture +
                    " is read with a comparison sampler, which needs a depth texture (Depth32Float or a "
                    "target's depth), but " +
                    bound.label + " is " + format_name(bound.format));
  if (kind != TexelKind::Float && sampler.filter == Filter::Linear)
    return fail(ErrorKind::Internal, texture + ": " + bound.label + " has integer texels (" +
                                         format_name(bound.format) +
                                         "), which cannot be filtered linearly; use a nearest sampler");
  return {};
}

namespace {

// Fills `matched` (one entry per slot) from `bindings`, by name.
template <class Slot, class Binding>
Result<void> match_by_name(const std::vector<Slot>& slots, const std::vector<Binding>& bindings,
                           std::vector<const Binding*>& matched, const char* kind, const std::string& where) {
  matched.assign(slots.size(), nullptr);
  for (const Binding& binding : bindings) {
    auto slot = std::find_if(slots.begin(), slots.end(), [&](const Slot& s) { return s.name == binding.name; });
    if (slot == slots.end())
      return fail(ErrorKind::Internal, where + ": the program has no " + kind + " named '" + binding.name + "'");
    if constexpr (std::is_same_v<Binding, UniformBinding>) {
      if (binding.bytes.size() != slot->size)
        return fail(ErrorKind::Internal, where + ": " + kind + " '" + binding.name + "' needs " +
                                             std::to_string(slot->size) + " bytes but " +
                                             std::to_string(binding.bytes.size()) + " were bound");
    }
    if constexpr (std::is_same_v<Binding, StorageBufferBinding>) {
      // The shaders read 32-bit words, and no API binds an empty buffer.
      if (binding.bytes.empty() || binding.bytes.size() % 4 != 0)
        return fail(ErrorKind::Internal, where + ": " + kind + " '" + binding.name +
                                             "' needs a whole number of 32-bit words, at least one, but " +
                                             std::to_string(binding.bytes.size()) + " bytes were bound");
    }
    const auto index = size_t(slot - slots.begin());
    if (matched[index])
      return fail(ErrorKind::Internal, where + ": " + kind + " '" + binding.name + "' is bound twice");
    matched[index] = &binding;
  }
  for (size_t i = 0; i < slots.size(); ++i)
    if (!matched[i]) return fail(ErrorKind::Internal, where + ": " + kind + " '" + slots[i].name + "' is not bound");
  return {};
}

}  // namespace

Result<void> validate_mesh(const MeshData& mesh) {
  if (mesh.vertices.empty() || mesh.indices.empty())
    return fail(ErrorKind::Internal, "upload_mesh: the mesh is empty (" + std::to_string(mesh.vertices.size()) +
                                         " vertices, " + std::to_string(mesh.indices.size()) + " indices)");
  if (mesh.indices.size() % 3 != 0)
    return fail(ErrorKind::Internal,
                "upload_mesh: " + std::to_string(mesh.indices.size()) + " indices is not a whole number of triangles");
  for (size_t i = 0; i < mesh.indices.size(); ++i)
    if (mesh.indices[i] >= mesh.vertices.size())
      return fail(ErrorKind::Internal, "upload_mesh: index " + std::to_string(mesh.indices[i]) + " (at position " +
                                           std::to_string(i) + ") is out of range for " +
                                           std::to_string(mesh.vertices.size()) + " vertices");
  return {};
}

Result<MatchedBindings> match_bindings(const ProgramLayout& layout, const DrawItem& draw, const std::string& where) {
  MatchedBindings matched;
  if (auto ok = match_by_name(layout.uniform_blocks, draw.uniforms, matched.uniforms, "uniform block", where); !ok)
    return fail(ok.error());
  if (auto ok = match_by_name(layout.textures, draw.textures, matched.textures, "texture", where); !ok)
    return fail(ok.error());
  if (auto ok =
          match_by_name(layout.storage_buffers, draw.storage_buffers, matched.storage_buffers, "storage buffer", where);
      !ok)
    return fail(ok.error());
  return matched;
}

std::string llvm_version_of(const std::string& renderer) {
  const size_t at = renderer.find("LLVM ");
  if (at == std::string::npos) return {};
  size_t end = at + 5;
  while (end < renderer.size() && (std::isdigit(static_cast<unsigned char>(renderer[end])) || renderer[end] == '.'))
    ++end;
  std::string version = renderer.substr(at + 5, end - at - 5);
  while (!version.empty() && version.back() == '.') version.pop_back();
  return version;
}

}  // namespace xshade::harness
