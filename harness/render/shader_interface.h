// What the harness must supply to a compiled shader — its constant buffers member by member,
// its textures, its properties' defaults — as plain data that survives the shader cache, and
// the bytes of a constant buffer built from values looked up by member name.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "base/result.h"
#include "hlsl_like/reflection.h"

namespace xshade::harness {

struct UniformMember {
  std::string name;
  hlsl::ScalarType scalar = hlsl::ScalarType::Float;
  uint32_t rows = 1;          // HLSL floatRxC: R rows; 1 for scalars and vectors
  uint32_t cols = 1;          // components of a vector; 1 for scalars
  uint32_t array_length = 0;  // 0: not an array
  uint32_t offset = 0;        // bytes, HLSL packing
  bool row_major = false;
  // Read by the variant's entry points. An unread member needs no value: its bytes stay zero.
  bool read = true;

  uint32_t components() const { return rows * cols * (array_length ? array_length : 1); }
};

struct UniformBlock {
  std::string name;   // as the shader declares it ("$Globals" for loose globals), the layout's too
  uint32_t size = 0;  // bytes
  std::vector<UniformMember> members;
};

// A read-only buffer the variant reads, which the scene must give (it has no default).
struct StorageBufferInput {
  std::string name;
  uint32_t stride = 4;  // bytes an element takes, as Direct3D packs it
  // The type of each 32-bit word of an element, in order: 'f' float, 'i' int, 'u' uint, 'b'
  // bool. A ByteAddressBuffer's is "f": the numbers a scene writes for raw words are floats.
  std::string words;
};

struct PropertyDefault {
  std::string name;
  std::vector<float> value;  // empty: no default
};

struct ShaderInterface {
  std::vector<UniformBlock> uniform_blocks;
  std::vector<std::string> textures;  // every Texture2D / sampler2D the layout lists
  std::vector<StorageBufferInput> storage_buffers;
  std::vector<PropertyDefault> properties;

  const PropertyDefault* find_property(const std::string& name) const;
};

ShaderInterface shader_interface(const hlsl::Reflection& reflection);

std::string shader_interface_json(const ShaderInterface& interface);
Result<ShaderInterface> parse_shader_interface_json(const std::string& text);

// A member's value, HLSL component order: a matrix row by row (M[r][c] at r * cols + c), an
// array element after element. Null when the caller has none for that name.
using UniformLookup = std::function<const std::vector<float>*(const std::string& member)>;

// The block's bytes with every member from `lookup`. Fails naming the block and the member when
// one has no value or a value of the wrong size: an unset uniform is a bug, never a silent zero.
Result<std::vector<std::byte>> build_uniform_block(const UniformBlock& block, const UniformLookup& lookup);

// One reflected constant buffer's bytes with each member's value from `value_of` (which sees the
// member and the buffer's interface, properties' defaults included), for running a shader without
// a scene: eval's defaults and its seeded inputs. A value of the wrong size leaves zeros.
using MemberValue = std::function<std::vector<float>(const UniformMember& member, const ShaderInterface& interface)>;
std::vector<std::byte> constant_buffer_from(const hlsl::ConstantBuffer& buffer,
                                            const std::vector<hlsl::Property>& properties, const MemberValue& value_of);

}  // namespace xshade::harness
