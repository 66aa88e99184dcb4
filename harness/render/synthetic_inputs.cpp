#include "harness/render/synthetic_inputs.h"

#include <algorithm>
#include <cctype>
#include <cstring>
#include <map>
#include <random>
#include <string>

#include "harness/render/shader_interface.h"

namespace xshade::harness {
namespace {

// A generator of its own for each name, so that a value does not depend on what else the shader
// declares. std::mt19937's sequence is the same on every implementation; the mapping to [0, 1)
// is written here for the same reason.
class Noise {
 public:
  Noise(uint32_t seed, const std::string& name) {
    std::seed_seq sequence{seed, uint32_t(std::hash<std::string>{}(name))};
    engine_.seed(sequence);
  }
  float unit() { return float(engine_() >> 8) * (1.0f / 16777216.0f); }  // [0, 1)
  uint32_t below(uint32_t n) { return uint32_t(engine_() % n); }

 private:
  std::mt19937 engine_;
};

}  // namespace

std::vector<std::byte> seeded_constant_buffer(const hlsl::ConstantBuffer& buffer, uint32_t seed) {
  return constant_buffer_from(buffer, {}, [seed](const UniformMember& member, const ShaderInterface&) {
    Noise noise(seed, member.name);
    std::vector<float> value;
    const uint32_t elements = member.array_length ? member.array_length : 1;
    for (uint32_t e = 0; e < elements; ++e)
      for (uint32_t r = 0; r < member.rows; ++r)
        for (uint32_t c = 0; c < member.cols; ++c) {
          switch (member.scalar) {
            case hlsl::ScalarType::Int:
            case hlsl::ScalarType::Uint: value.push_back(float(noise.below(4))); break;
            case hlsl::ScalarType::Bool: value.push_back(float(noise.below(2))); break;
            default:
              value.push_back(member.rows > 1 ? (r == c ? 1.0f : 0.0f) + 0.2f * noise.unit() - 0.1f
                                              : 0.1f + 0.9f * noise.unit());
          }
        }
    return value;
  });
}

std::vector<std::byte> seeded_storage_buffer(const StorageBufferInput& buffer, uint32_t seed) {
  const uint32_t elements = buffer.words.size() == 1 ? 256 : 64;
  Noise noise(seed, buffer.name);
  std::vector<std::byte> bytes;
  bytes.reserve(size_t(elements) * buffer.words.size() * 4);
  const auto append = [&bytes](auto value) {
    const size_t end = bytes.size();
    bytes.resize(end + 4);
    std::memcpy(bytes.data() + end, &value, 4);
  };
  for (uint32_t e = 0; e < elements; ++e)
    for (char word : buffer.words) {
      switch (word) {
        case 'i': append(int32_t(noise.below(4))); break;
        case 'u': append(noise.below(4)); break;
        case 'b': append(noise.below(2)); break;
        default: append(0.1f + 0.9f * noise.unit());
      }
    }
  return bytes;
}

TextureData seeded_texture(const TextureSlot& slot, uint32_t seed) {
  constexpr uint32_t kSize = 16;
  TextureData texture;
  texture.dimension = slot.shape.dimension;
  texture.width = kSize;
  texture.height =
      slot.shape.dimension == TextureDimension::Tex1D || slot.shape.dimension == TextureDimension::Tex1DArray ? 1
                                                                                                              : kSize;
  switch (slot.shape.dimension) {
    case TextureDimension::Tex1DArray:
    case TextureDimension::Tex2DArray: texture.layers = 2; break;
    case TextureDimension::Cube: texture.layers = 6; break;
    case TextureDimension::CubeArray: texture.layers = 12; break;
    case TextureDimension::Tex3D: texture.layers = kSize; break;
    default: texture.layers = 1;
  }
  texture.samples = slot.shape.multisampled ? 4 : 1;
  std::string lower = slot.name;
  for (char& c : lower) c = char(std::tolower(static_cast<unsigned char>(c)));
  const bool depth_like = slot.comparison || lower.find("depth") != std::string::npos;
  texture.format = slot.comparison                 ? TextureFormat::Depth32Float
                   : slot.texel == TexelKind::Int  ? TextureFormat::Rgba32Sint
                   : slot.texel == TexelKind::Uint ? TextureFormat::Rgba32Uint
                                                   : TextureFormat::Rgba32Float;
  Noise noise(seed, slot.name);
  const uint32_t levels = slot.shape.multisampled ? 1 : [&] {
    uint32_t count = 1;
    for (uint32_t side = std::max(texture.width, texture.height); side > 1; side /= 2) ++count;
    return count;
  }();
  for (uint32_t level = 0; level < levels; ++level) {
    const size_t bytes = level_bytes(texture, level);
    std::vector<std::byte> data(bytes);
    for (size_t at = 0; at + 4 <= bytes; at += 4) {
      if (slot.texel != TexelKind::Float && !slot.comparison) {
        const uint32_t value = noise.below(8);
        std::memcpy(&data[at], &value, 4);
      } else {
        // Depth in (0, 1): never exactly the near or the far plane.
        const float value = depth_like ? 0.01f + 0.98f * noise.unit() : noise.unit();
        std::memcpy(&data[at], &value, 4);
      }
    }
    texture.levels.push_back(std::move(data));
  }
  return texture;
}

SamplerDesc seeded_sampler(const TextureSlot& slot) {
  return {slot.texel == TexelKind::Float || slot.comparison ? Filter::Linear : Filter::Nearest, AddressMode::Repeat};
}

}  // namespace xshade::harness
