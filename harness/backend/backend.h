// The seam between the harness and a graphics API: one small interface, one class per API.
//
// Conventions every implementation keeps, so that lanes agree (see docs/architecture.md):
// - Direct3D orientation: clip-space +y is up, clip z in [0, w], framebuffer row 0 is the top row,
//   and texture coordinate (0,0) addresses the first row of uploaded data (the top of an image
//   file). OpenGL gets there with glClipControl(GL_UPPER_LEFT, GL_ZERO_TO_ONE), Vulkan with a
//   negative viewport height. A pass may ask for OpenGL's row order instead (RowOrigin).
// - Targets are RGBA32F colour and D32F depth; both can be sampled by later passes. Nothing is
//   clamped: NaN, Inf, negatives and values above 1 reach read-back unchanged.
// - Resources are bound by name through the program's layout, never by hard-coded numbers.
#pragma once

#include <compare>
#include <cstddef>
#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <type_traits>
#include <vector>

#include <glm/glm.hpp>

#include "base/result.h"
#include "harness/image/image.h"

namespace xshade::harness {

// A typed index into a backend's own tables; 0 is never a valid handle.
template <class Tag>
struct Handle {
  uint32_t id = 0;
  explicit operator bool() const { return id != 0; }
  friend bool operator==(Handle, Handle) = default;
};
using TargetHandle = Handle<struct TargetTag>;
using MeshHandle = Handle<struct MeshTag>;
using TextureHandle = Handle<struct TextureTag>;
using ProgramHandle = Handle<struct ProgramTag>;

// The one vertex format: locations 0..3 are POSITION, NORMAL, TANGENT, TEXCOORD0. A vertex
// shader may read other locations too (TEXCOORD1..7, COLOR0..1: hlsl::vertex_input_location);
// no mesh supplies them, so every backend feeds them a constant: white (1, 1, 1, 1) to a float
// colour input (COLOR0 at location 5, COLOR1 at 12), as a Unity mesh without vertex colours
// gives its shaders, and zeros of the input's type to any other.
struct Vertex {
  glm::vec3 position{0.0f};
  glm::vec3 normal{0.0f, 0.0f, 1.0f};
  glm::vec4 tangent{1.0f, 0.0f, 0.0f, 1.0f};
  glm::vec2 uv{0.0f};
};
static_assert(sizeof(Vertex) == 48, "the vertex layout is shared with the shaders");
// Whether the input at `location`, which no mesh supplies, reads white (a float colour input).
constexpr bool unsupplied_input_reads_white(uint32_t location) { return location == 5 || location == 12; }

struct MeshData {
  std::vector<Vertex> vertices;
  std::vector<uint32_t> indices;  // triangle list
};

enum class TextureFormat {
  Rgba8Unorm,    // 4 bytes per texel, linear
  Rgba8Srgb,     // 4 bytes per texel, sRGB-encoded (decoded by the sampler)
  Rgba32Float,   // 16 bytes per texel
  R32Float,      // 4 bytes per texel: one float channel (reads as (r, 0, 0, 1))
  Depth32Float,  // 4 bytes per texel: a depth texture, the one a comparison sampler reads (a
                 // comparison of a colour format is undefined on both APIs)
  Rgba32Uint,    // 16 bytes per texel: four uint32 (Texture2D<uint4>)
  Rgba32Sint,    // 16 bytes per texel: four int32 (Texture2D<int4>)
};
size_t bytes_per_texel(TextureFormat format);
const char* format_name(TextureFormat format);

// What a shader's texel reads as: float (float, half, unorm, depth), int or uint. A texture of
// one kind cannot be read through a sampler of another on either API.
enum class TexelKind { Float, Int, Uint };
TexelKind texel_kind(TextureFormat format);
const char* texel_kind_name(TexelKind kind);

// How a texture's texels are arranged. A cube has 6 layers, its faces in the order +X, -X, +Y,
// -Y, +Z, -Z (the same on both APIs: the face a direction selects and the face's (s, t) come
// from one table shared by Direct3D, OpenGL and Vulkan); a cube array 6 per cube.
enum class TextureDimension { Tex1D, Tex1DArray, Tex2D, Tex2DArray, Tex3D, Cube, CubeArray };

// A texture's shape as a shader declares it: a dimension, multisampled or not (2D and 2D array
// only). Named as HLSL names the type: "Texture2DMS", "TextureCubeArray".
struct TextureShape {
  TextureDimension dimension = TextureDimension::Tex2D;
  bool multisampled = false;
  friend bool operator==(TextureShape, TextureShape) = default;
};
std::string shape_name(TextureShape shape);
bool is_array(TextureDimension dimension);  // 1D array, 2D array, cube array

struct TextureData {
  TextureFormat format = TextureFormat::Rgba8Unorm;
  uint32_t width = 0;
  uint32_t height = 0;  // 1 for a 1D texture or 1D array
  // Mip levels, level 0 first. Each holds all its layers (or slices) one after the other, each
  // tightly packed with row 0 = v 0 = the top of the image. Level i is max(1, width >> i) by
  // max(1, height >> i), with `layers` layers (arrays and cubes) or max(1, layers >> i) slices
  // (3D).
  std::vector<std::vector<std::byte>> levels;
  TextureDimension dimension = TextureDimension::Tex2D;
  // Array layers (1 for a plain 1D or 2D texture; 6 for a cube, 6 * N for a cube array), or the
  // depth of a 3D texture.
  uint32_t layers = 1;
  // Samples per texel: above 1 a multisampled texture (2D or 2D array, one level, a colour
  // format), each sample of a texel holding its level-0 value.
  uint32_t samples = 1;

  TextureShape shape() const { return {dimension, samples > 1}; }
};
// The bytes level `level` of `texture` must hold.
size_t level_bytes(const TextureData& texture, uint32_t level);
// A texture every backend can upload within `max_size` texels a side: not empty, the size its
// dimension allows (1D: height 1; cube: square, 6 layers a cube), whole levels, each with the
// bytes its size needs, multisampling only where both APIs have it. Fails naming the problem.
Result<void> validate_texture(const TextureData& texture, uint32_t max_size);

enum class Filter { Nearest, Linear };
enum class AddressMode { Repeat, ClampToEdge };

// The comparison a comparison sampler makes: the result is 1 where `reference <op> texel` holds,
// else 0 (Direct3D's order of the operands, which OpenGL and Vulkan share).
enum class CompareOp { Never, Less, Equal, LessEqual, Greater, NotEqual, GreaterEqual, Always };

struct SamplerDesc {
  // Mip levels are sampled with the same filter as texels (trilinear when Linear).
  Filter filter = Filter::Linear;
  AddressMode address = AddressMode::Repeat;
  // Used only where the program's slot is a comparison slot (TextureSlot::comparison).
  CompareOp compare = CompareOp::LessEqual;
  friend bool operator==(const SamplerDesc&, const SamplerDesc&) = default;
};

// What a pass samples: an uploaded texture, or the colour or depth of an earlier target.
struct TextureSource {
  enum class Kind { Texture, TargetColor, TargetDepth };
  Kind kind = Kind::Texture;
  uint32_t id = 0;  // a TextureHandle's or TargetHandle's id
  SamplerDesc sampler;

  static TextureSource texture(TextureHandle handle, SamplerDesc sampler = {}) {
    return {Kind::Texture, handle.id, sampler};
  }
  static TextureSource color_of(TargetHandle handle, SamplerDesc sampler = {}) {
    return {Kind::TargetColor, handle.id, sampler};
  }
  static TextureSource depth_of(TargetHandle handle, SamplerDesc sampler = {}) {
    return {Kind::TargetDepth, handle.id, sampler};
  }
};

// The resources a program reads, with the bindings its compiler assigned (from reflection).
// All live in descriptor set 0 on Vulkan; on OpenGL a binding is a uniform-block binding point
// or a texture unit.
struct UniformBlockSlot {
  std::string name;
  uint32_t binding = 0;
  uint32_t size = 0;  // bytes; a bound block must supply exactly this many
  // Vulkan only: the block is the program's push constants (at most one, given with each draw),
  // not a descriptor; `binding` is then unused. OpenGL reads every block as a uniform block.
  bool push_constant = false;
  // OpenGL only: the block's name in the GLSL when it is not `name` ("$Globals" is "xs_Globals",
  // and GLSL reserves some HLSL names). Draws still bind by `name`.
  std::string glsl_block = {};
  const std::string& glsl_block_name() const { return glsl_block.empty() ? name : glsl_block; }
};
struct TextureSlot {
  std::string name;
  uint32_t binding = 0;
  // Vulkan only: the binding of the separate sampler paired with this texture. Absent means a
  // combined image sampler at `binding` (or a sampled image alone, with `image_only`). OpenGL
  // always combines, at texture unit `binding`.
  std::optional<uint32_t> sampler_binding;
  // What the shader declared: the texture's shape, whether it reads the texture with a
  // comparison sampler (a shadow map: the bound texture must be a depth texture, and its
  // sampler compares with SamplerDesc::compare), and what its texels read as. A draw fails
  // when the bound texture has another shape or texel kind.
  TextureShape shape = {};
  bool comparison = false;
  TexelKind texel = TexelKind::Float;
  // Vulkan only: a sampled image without a sampler (a texture the shader only Loads from or
  // asks the size of).
  bool image_only = false;
  // A comparison slot whose filtering the shader does itself (2x2 comparisons by textureGather,
  // glsl::EmitOptions::filter_comparisons; the vk lane's, for a device that cannot filter a
  // depth texture): the driver reads it nearest whatever filter the bound sampler names.
  bool filtered_in_shader = false;
  // OpenGL only: the sampler uniform's name in the GLSL when it is not `name` (GLSL reserves the
  // HLSL name, e.g. `sample` or `flat`, and the emitter renames it). Draws still bind by `name`.
  std::string glsl_name = {};
  const std::string& uniform_name() const { return glsl_name.empty() ? name : glsl_name; }
};
// A read-only buffer (HLSL's StructuredBuffer, ByteAddressBuffer, Buffer): a shader storage
// buffer of 32-bit words at `binding` (a storage-buffer binding point on OpenGL, a storage-buffer
// descriptor on Vulkan) whose bytes each draw gives.
struct StorageBufferSlot {
  std::string name;
  uint32_t binding = 0;
  std::string glsl_block = {};  // OpenGL: the block's name in the GLSL, which the linked program lists
};
struct ProgramLayout {
  std::vector<UniformBlockSlot> uniform_blocks;
  std::vector<TextureSlot> textures;
  std::vector<StorageBufferSlot> storage_buffers = {};
};

struct ShaderStageSource {
  std::string glsl;             // read by OpenGL backends
  std::vector<uint32_t> spirv;  // read by Vulkan backends
  std::string entry_point = "main";
  std::string name;  // shown in diagnostics, e.g. the source file
  // Generated GLSL says `#line L N` to point at the author's files: entry N names source
  // string N, so that the driver's messages name the author's file and line.
  std::vector<std::string> source_files;
};

struct ProgramDesc {
  std::string name;
  ShaderStageSource vertex;
  ShaderStageSource fragment;
  ProgramLayout layout;
  // A mesh program reads the Vertex format; a full-screen program reads no vertex input and is
  // drawn as one triangle of three vertices (see glsl::fullscreen_vertex_shader).
  bool fullscreen = false;
  // How many of gl_ClipDistance[] the vertex stage writes: OpenGL clips by a distance only where
  // its plane is enabled (Vulkan by every one the shader writes).
  uint32_t clip_distances = 0;
  // Vulkan only: the specialization constants' values (the 32-bit word of each, by constant_id),
  // given to both stages (an id a stage lacks is not its). OpenGL's GLSL has them written in.
  std::map<uint32_t, uint32_t> specialization = {};
};

// The bytes of a host-side uniform block (a struct laid out to match the shader's block).
template <class Block>
std::vector<std::byte> uniform_bytes(const Block& block) {
  static_assert(std::is_trivially_copyable_v<Block>);
  const auto* first = reinterpret_cast<const std::byte*>(&block);
  return {first, first + sizeof(Block)};
}

struct UniformBinding {
  std::string name;  // a UniformBlockSlot's name
  std::vector<std::byte> bytes;
};
struct TextureBinding {
  std::string name;  // a TextureSlot's name
  TextureSource source;
};
struct StorageBufferBinding {
  std::string name;              // a StorageBufferSlot's name
  std::vector<std::byte> bytes;  // whole 32-bit words, at least one
};

// How a draw is rasterized, depth-tested and blended into the target: the render state of a
// Unity pass (ShaderLab's Cull, ZWrite, ZTest, Blend, BlendOp, ColorMask, Offset, Stencil)
// with its Direct3D meaning on every backend. A front face is one whose vertices run
// counter-clockwise in the image (row 0 at the top): the scene's world is right-handed and its
// meshes wind counter-clockwise seen from outside (OBJ's convention), which is what Unity's
// importer turns into its left-handed world's clockwise front faces, so Cull Back removes the
// same faces here as there. The default is what a pass of xshade's own materials has always had:
// no culling, depth written and tested less, no blending, every channel written, no stencil test.
enum class CullMode { Off, Back, Front };
enum class BlendFactor {
  Zero,
  One,
  SrcColor,
  OneMinusSrcColor,
  DstColor,
  OneMinusDstColor,
  SrcAlpha,
  OneMinusSrcAlpha,
  DstAlpha,
  OneMinusDstAlpha,
  SrcAlphaSaturate,
};
enum class BlendOp { Add, Subtract, ReverseSubtract, Min, Max };

struct BlendState {
  bool enabled = false;
  BlendFactor color_source = BlendFactor::One, color_destination = BlendFactor::Zero;
  BlendFactor alpha_source = BlendFactor::One, alpha_destination = BlendFactor::Zero;
  BlendOp color_op = BlendOp::Add, alpha_op = BlendOp::Add;
  friend bool operator==(const BlendState&, const BlendState&) = default;
  friend auto operator<=>(const BlendState&, const BlendState&) = default;
};

inline constexpr uint8_t kColorWriteAll = 0xF;  // bit 0 red, 1 green, 2 blue, 3 alpha

// What a stencil test does to the stored value: Direct3D's operations (the clamped ones stop at 0
// and 255, the wrapping ones go round).
enum class StencilOp { Keep, Zero, Replace, IncrementClamp, DecrementClamp, Invert, IncrementWrap, DecrementWrap };
// One face's test and operations: the test is `(reference & read_mask) <compare> (stored &
// read_mask)`; `fail` applies where it fails, `depth_fail` where it passes and the depth test
// fails, `pass` where both pass. The stored value changes only in write_mask's bits.
struct StencilFaceState {
  CompareOp compare = CompareOp::Always;
  StencilOp pass = StencilOp::Keep, fail = StencilOp::Keep, depth_fail = StencilOp::Keep;
  friend bool operator==(const StencilFaceState&, const StencilFaceState&) = default;
  friend auto operator<=>(const StencilFaceState&, const StencilFaceState&) = default;
};
// An 8-bit stencil test (Unity's Stencil block), front and back faces apart (a front face as
// DrawState says). Tested and written only where the target has a stencil buffer
// (TargetDesc::stencil).
struct StencilState {
  bool enabled = false;
  uint8_t reference = 0, read_mask = 0xFF, write_mask = 0xFF;
  StencilFaceState front, back;
  friend bool operator==(const StencilState&, const StencilState&) = default;
  friend auto operator<=>(const StencilState&, const StencilState&) = default;
};

struct DrawState {
  CullMode cull = CullMode::Off;
  bool depth_write = true;                    // where the target has depth
  CompareOp depth_compare = CompareOp::Less;  // the incoming depth <op> the stored one
  BlendState blend;                           // the first colour attachment's
  uint8_t color_write = kColorWriteAll;
  // Added to the depth before the test: factor x the triangle's depth slope + units x the
  // smallest step of the depth format (Unity's Offset factor, units).
  float depth_bias_slope = 0.0f;
  float depth_bias_units = 0.0f;
  StencilState stencil;
  friend bool operator==(const DrawState&, const DrawState&) = default;
  friend auto operator<=>(const DrawState&, const DrawState&) = default;
};

struct DrawItem {
  ProgramHandle program;
  MeshHandle mesh;  // ignored (and may be empty) for a full-screen program
  std::vector<UniformBinding> uniforms;
  std::vector<TextureBinding> textures;
  DrawState state;
  std::vector<StorageBufferBinding> storage_buffers = {};
};

// A draw's bindings matched to its program's layout by name: per layout slot, the binding that
// fills it. Fails, naming `where` and the slot, when a name matches no slot, a uniform block has
// the wrong size, a storage buffer is not whole words, or a slot is bound twice or not at all.
// Every backend checks draws with this.
struct MatchedBindings {
  std::vector<const UniformBinding*> uniforms;               // per ProgramLayout::uniform_blocks entry
  std::vector<const TextureBinding*> textures;               // per ProgramLayout::textures entry
  std::vector<const StorageBufferBinding*> storage_buffers;  // per ProgramLayout::storage_buffers entry
};
Result<MatchedBindings> match_bindings(const ProgramLayout& layout, const DrawItem& draw, const std::string& where);

// What a draw binds to a texture slot, as far as the slot's checks need it.
struct BoundTextureFacts {
  TextureShape shape = {};
  TextureFormat format = TextureFormat::Rgba8Unorm;
  std::string label;  // "texture 3", "the depth of target 2"
};
// Fails, naming `where`, the slot and both shapes (or formats), when the bound texture is not
// what the slot declares: another shape, another texel kind, a comparison slot without a depth
// texture, or linear filtering of integer texels (undefined on OpenGL, invalid on Vulkan).
// Every backend checks each texture binding with this before the driver sees it.
Result<void> check_bound_texture(const TextureSlot& slot, const BoundTextureFacts& bound, const SamplerDesc& sampler,
                                 const std::string& where);

// A mesh every backend can draw: not empty, whole triangles, every index within the vertices.
Result<void> validate_mesh(const MeshData& mesh);

struct TargetDesc {
  uint32_t width = 0;
  uint32_t height = 0;
  bool depth = true;  // a D32F depth attachment beside the RGBA32F colour
  // A second RGBA32F colour attachment, written by fragment output location 1 and cleared to
  // zero with every pass (whatever the pass's clear colour): what a traced program records
  // beside its colour (glsl::EmitOptions::trace_nonfinite). Where a draw's program does not
  // write location 1 the attachment's value is undefined (on both APIs; llvmpipe leaves what an
  // earlier draw wrote), so every program drawn into it must.
  bool second_color = false;
  // An 8-bit stencil buffer with the depth (D32F + S8; needs `depth`), cleared with every pass.
  // Sampling the target's depth still reads the depth.
  bool stencil = false;
};

// Which edge of clip space a pass's mesh draws put in the target's row 0: the top (clip +y:
// Direct3D's orientation, every lane's default) or the bottom (clip -y: OpenGL's window origin, as
// Unity's GLCore draws). Only where the rows land changes: a front face still runs counter-
// clockwise in clip space, SV_Position.y still counts rows from row 0 and ddy runs along them, and
// a full-screen program's uv (0, 0) is still row 0.
enum class RowOrigin { Top, Bottom };

// One pass into one target: clear, then the draws in order, each with its DrawState (the depth
// test and write only where the target has depth, the stencil test only where it has stencil). A pass may sample any
// target but its own.
struct RenderPass {
  TargetHandle target;
  glm::vec4 clear_color{0.0f};
  float clear_depth = 1.0f;
  std::vector<DrawItem> draws;
  uint8_t clear_stencil = 0;
  RowOrigin row_origin = RowOrigin::Top;
};

// What a lane reports about its driver, carried by every report.
struct DriverInfo {
  std::string api;             // "OpenGL 4.5 core (OSMesa)" or "Vulkan 1.3 (lavapipe)"
  std::string renderer;        // e.g. "llvmpipe (LLVM 15.0.6, 256 bits)"
  std::string api_version;     // what the driver reports, e.g. "4.5 (Core Profile) Mesa 22.3.6"
  std::string driver_version;  // e.g. "Mesa 22.3.6"
  std::string llvm_version;    // e.g. "15.0.6", empty if the renderer does not say
};
// "llvmpipe (LLVM 15.0.6, 256 bits)" -> "15.0.6": DriverInfo::llvm_version from a renderer string
// (both Mesa drivers name their LLVM this way); empty when there is no "LLVM x.y.z".
std::string llvm_version_of(const std::string& renderer);

class Backend {
 public:
  virtual ~Backend() = default;
  Backend() = default;
  Backend(const Backend&) = delete;
  Backend& operator=(const Backend&) = delete;

  virtual const DriverInfo& driver_info() const = 0;

  virtual Result<TargetHandle> create_target(const TargetDesc& desc) = 0;
  virtual Result<MeshHandle> upload_mesh(const MeshData& mesh) = 0;
  virtual Result<TextureHandle> upload_texture(const TextureData& texture) = 0;
  // Fails with the driver's compile or link log when the program is rejected.
  virtual Result<ProgramHandle> create_program(const ProgramDesc& desc) = 0;

  // Frees the object and its driver memory now (a backend finishes any work that uses it
  // first). Its handle is then refused by every call, destroy included: destroying twice, or
  // destroying a handle never given out, is an error and changes nothing. Handles are never
  // reused. A target a later pass samples, or a texture a draw binds, must outlive that pass
  // only; programs usually stay for the backend's life (render/ProgramCache).
  virtual Result<void> destroy(TargetHandle target) = 0;
  virtual Result<void> destroy(MeshHandle mesh) = 0;
  virtual Result<void> destroy(TextureHandle texture) = 0;
  virtual Result<void> destroy(ProgramHandle program) = 0;

  // Runs the pass to completion.
  virtual Result<void> render(const RenderPass& pass) = 0;
  // RGBA32F, row 0 at the top.
  virtual Result<FloatImage> read_color(TargetHandle target) = 0;
  // The second colour attachment (TargetDesc::second_color) the same way; fails for a target
  // without one.
  virtual Result<FloatImage> read_second_color(TargetHandle target) = 0;

  // Messages the driver's debug or validation layer reported since the last call, oldest first.
  // An empty list is the only acceptable state for a correct program.
  virtual std::vector<std::string> take_driver_messages() = 0;
};

}  // namespace xshade::harness
