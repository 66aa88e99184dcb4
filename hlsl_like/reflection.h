// What a compiled shader reads and writes, with the bindings and locations the compiler assigned:
// the contract between the compiler, the GLSL emitter and the harness (which binds by name).
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "hlsl_like/ast.h"
#include "hlsl_like/diagnostic_engine.h"
#include "hlsl_like/resource_origins.h"
#include "hlsl_like/sema.h"

namespace xshade::hlsl {

// Vulkan descriptor set 0 holds every class of resource, so each HLSL register class has its own
// range of bindings. glslang's HLSL front end is given the same shifts (the vk-hlsl lane), and
// OpenGL uses the same numbers as uniform-block binding points and texture units.
inline constexpr uint32_t kConstantBufferBindingBase = 0;  // register(bN)
inline constexpr uint32_t kTextureBindingBase = 16;        // register(tN); sampler2D too
inline constexpr uint32_t kSamplerBindingBase = 32;        // register(sN) of a SamplerState
inline constexpr uint32_t kRegistersPerClass = 16;

// The name of the constant buffer that holds the globals declared outside any cbuffer.
inline constexpr const char* kGlobalsBufferName = "$Globals";

// How one constant-buffer member is laid out by HLSL's packing rules, and how the GLSL block
// (std140 with explicit offsets) reproduces exactly those bytes.
struct ConstantBufferMember {
  std::string name;
  Type type;
  uint32_t offset = 0;     // bytes from the start of the buffer, HLSL packing
  uint32_t size = 0;       // bytes HLSL gives it (an array's last element is not padded)
  bool row_major = false;  // a matrix stored by rows (HLSL's default is by columns)
  // A vector whose HLSL offset std140 cannot hold (a float2 at 4, a float3 at 4): the emitter
  // declares it as scalars at these offsets and rebuilds the vector where it is read.
  bool split_into_scalars = false;
  // Read by the compiled entry points (or by a static global's initializer they read). An unread
  // member keeps its place in the buffer's layout; nobody needs to give it a value.
  bool used = true;
};

struct ConstantBuffer {
  std::string name;  // as declared, or kGlobalsBufferName
  uint32_t binding = 0;
  uint32_t size = 0;  // bytes, rounded up to 16 as Direct3D does
  std::vector<ConstantBufferMember> members;
  // The CBufferDecl, or the VarDecl of a `ConstantBuffer<S> name` (whose members are S's fields,
  // read as name.field); null for $Globals.
  const Decl* decl = nullptr;
  uint32_t set = 0;            // Vulkan's descriptor set: 0 unless [[vk::binding(N, set)]] says otherwise
  bool push_constant = false;  // [[vk::push_constant]]: a push-constant block on Vulkan
  // Elements of an array of them (ConstantBuffer<S> cb[2]): the registers from `binding` on on
  // Direct3D and OpenGL, one binding of that many descriptors on Vulkan.
  uint32_t count = 1;
};

enum class TextureKind : uint8_t {
  Texture,  // Texture2D, TextureCube, ... read with SamplerState objects, separate
  Sampler,  // DX9 sampler2D, samplerCUBE, ...: texture and sampler in one
};

struct TextureResource {
  std::string name;
  TextureKind kind = TextureKind::Texture;
  TextureShape shape = TextureShape::Tex2D;
  // What a texel reads as: float (float and half), int or uint; a DX9 sampler reads float.
  ScalarType texel = ScalarType::Float;
  uint32_t binding = 0;
  // For a Texture: the SamplerState it is sampled with (the first one, when several are),
  // and that sampler's binding. Empty when the shader never samples it through a SamplerState.
  std::string sampler;
  std::optional<uint32_t> sampler_binding;
  // Sampled with a SamplerComparisonState (SampleCmp, GatherCmp): a shadow map, whose sampler
  // compares against a reference. OpenGL declares such a texture as a shadow sampler.
  bool comparison = false;
  // Read by the compiled entry points. An unread resource keeps its binding (the numbers do not
  // move when a shader stops reading one) but is neither declared in GLSL nor bound.
  bool used = true;
  const VarDecl* decl = nullptr;
  uint32_t set = 0;    // as ConstantBuffer::set
  uint32_t count = 1;  // as ConstantBuffer::count
};

struct SamplerResource {
  std::string name;
  uint32_t binding = 0;
  bool comparison = false;  // a SamplerComparisonState
  bool used = true;         // as TextureResource::used
  const VarDecl* decl = nullptr;
  uint32_t set = 0;    // as ConstantBuffer::set
  uint32_t count = 1;  // as ConstantBuffer::count
};

// A read-only buffer (StructuredBuffer<T>, ByteAddressBuffer, Buffer<T>): Direct3D's shader
// resource view in a t register, a storage buffer on OpenGL and Vulkan read as 32-bit words laid
// out as Direct3D lays them out (an element of a structured buffer packed tightly, four bytes per
// scalar, matrices column by column unless row_major; a typed buffer's element its components).
struct StorageBufferResource {
  std::string name;
  BufferKind kind = BufferKind::StructuredBuffer;
  Type element;          // T; uint for a ByteAddressBuffer
  uint32_t stride = 4;   // bytes from one element to the next (4 for a ByteAddressBuffer's words)
  uint32_t binding = 0;  // in the texture range, as the register it shares with textures
  bool used = true;      // as TextureResource::used
  const VarDecl* decl = nullptr;
  uint32_t set = 0;  // as ConstantBuffer::set
};
// Whether this target reads `kind` (the read-only buffers); the read-write ones are refused.
bool is_read_only_buffer(BufferKind kind);

// A stage input or output with the location the compiler gave it.
struct StageVariable {
  std::string semantic;  // canonical: "TEXCOORD0", "SV_Target0", "POSITION"
  Type type;
  uint32_t location = 0;
  Interpolation interpolation = Interpolation::Default;
  // The location the source gives with [[vk::location(N)]], which `location` then is.
  std::optional<uint32_t> given_location = std::nullopt;
};

// A material property: a uniform with its annotations (`<string UIName = ...; float UIMin...>`).
struct Property {
  std::string name;
  std::string display_name;  // UIName, or the name
  Type type;
  std::optional<double> min;          // UIMin
  std::optional<double> max;          // UIMax
  std::vector<double> default_value;  // the initializer's components, when constant
  bool is_texture = false;
  // A texture's `<string Default = "white";>`: what it samples where a scene gives it nothing
  // (Unity's `= "white" {}`). One of kTextureDefaults; empty when it declares none.
  std::string default_texture;
};

// The defaults a texture may declare: the scene format's built-in textures (docs/scenes.md).
inline constexpr std::string_view kTextureDefaults[] = {"white", "black", "checker", "normal", "gray", "red", "clear"};

// Keywords from `#pragma multi_compile A B C` (every combination is a variant) and
// `#pragma shader_feature A B` (only the combinations a scene asks for). `_` means "none".
struct KeywordSet {
  std::vector<std::string> keywords;
  bool shader_feature = false;
};

// How many keyword combinations `sets` make (a set without keywords counts once), saturating at
// UINT64_MAX: 70 two-keyword sets are already past what 64 bits count.
uint64_t keyword_combination_count(const std::vector<KeywordSet>& sets);
// Combination `index` (below the count) as a mixed-radix number, the first set changing slowest,
// each set's `_` (none) left out: the combinations one at a time, never all of them in memory.
std::vector<std::string> keyword_combination(const std::vector<KeywordSet>& sets, uint64_t index);

// A `[[vk::constant_id(N)]] const` scalar: a specialization constant, which a host may give
// another value than its initializer (docs/hlsl_like.md, section 10).
struct SpecializationConstant {
  std::string name;
  uint32_t id = 0;
  ScalarType scalar = ScalarType::Float;
};

struct Reflection {
  std::string vertex_entry;
  std::string fragment_entry;
  std::vector<StageVariable> vertex_inputs;
  std::vector<StageVariable> varyings;  // vertex outputs = fragment inputs, SV_Position excluded
  std::vector<StageVariable> fragment_outputs;
  std::vector<ConstantBuffer> constant_buffers;
  std::vector<TextureResource> textures;
  std::vector<SamplerResource> samplers;
  std::vector<StorageBufferResource> buffers;
  std::vector<SpecializationConstant> specialization_constants;
  std::vector<Property> properties;
  std::vector<KeywordSet> keyword_sets;
  std::vector<std::string> active_keywords;  // of this variant
  // Components of gl_ClipDistance[] and gl_CullDistance[] the program carries (its vertex stage's
  // SV_ClipDistanceN and SV_CullDistanceN outputs; a full-screen pass's fragment inputs): an
  // OpenGL draw enables that many clip planes.
  uint32_t clip_distances = 0;
  uint32_t cull_distances = 0;
  // The fragment stage reads SV_ShadingRate (Vulkan's gl_ShadingRateEXT, which a device must have).
  bool reads_shading_rate = false;

  const ConstantBuffer* find_constant_buffer(std::string_view name) const;
};

// The canonical spelling of a semantic: "texcoord" -> "TEXCOORD0", "sv_target" -> "SV_Target0".
std::string canonical_semantic_name(const std::string& semantic);

// Vertex inputs have fixed locations so that every mesh serves every shader:
// POSITION 0, NORMAL 1, TANGENT 2, TEXCOORD0 3, TEXCOORD1 4, COLOR0 5, TEXCOORD2-7 6-11, COLOR1 12.
// Empty for others, which take the next free location from 13 in the order they are declared
// ([[vk::location(N)]] puts one at N). A mesh supplies 0..3; the backends feed zeros to the rest.
std::optional<uint32_t> vertex_input_location(const std::string& canonical_semantic);
// Varyings are placed by semantic, so that the two stages agree whatever their structs look like:
// TEXCOORD0-7 at 0-7, COLOR0-1 at 8-9, NORMAL 10, TANGENT 11, BINORMAL 12, POSITION 13. A
// varying after an array moves up past the locations it takes, and any other semantic (HLSL's
// user semantics, TEXCOORD8 and up) takes the next free location from 14, in the order the
// vertex stage declares them (Reflection::varyings holds where each one is). [[vk::location(N)]]
// puts one at N, as DXC does.
std::optional<uint32_t> varying_location(const std::string& canonical_semantic);

// Builds the reflection of an analysed translation unit. Reports what the bindings or the GLSL
// block layout cannot express (a register used twice, a member std140 cannot place).
Reflection reflect(const TranslationUnit& unit, const EntryPoints& entry_points, const ResourceOrigins& origins,
                   DiagnosticEngine& diagnostics);

// The reflection as JSON (an object; see docs/hlsl_like.md, "Reflection").
std::string reflection_json(const Reflection& reflection);

}  // namespace xshade::hlsl
