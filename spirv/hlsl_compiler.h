// The vk-hlsl lane: the same hlsl_like source through glslang's own HLSL front end to SPIR-V.
//
// It shares nothing with xshade's front end but the source text, so where the two disagree one
// of them mistranslates HLSL (known glslang divergences: docs/divergences.md).
#pragma once

#include <cstdint>
#include <filesystem>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "spirv/spirv_compiler.h"

namespace xshade::spirv {

// Where each HLSL register class lands in Vulkan's descriptor set 0. xshade's reflection assigns
// bindings by the same rule, so both lanes bind the same names at the same numbers.
struct BindingShifts {
  uint32_t constant_buffer = 0;  // register(bN)  -> binding N + constant_buffer
  uint32_t texture = 16;         // register(tN)  -> binding N + texture
  uint32_t sampler = 32;         // register(sN)  -> binding N + sampler
};

// Finds the text of an #include: the name as written, the including file's name, and whether it
// was <angled>. Returns the resolved file's name and text, or nothing when not found.
struct IncludedFile {
  std::string name;
  std::string text;
};
using IncludeResolver =
    std::function<std::optional<IncludedFile>(std::string_view name, std::string_view includer, bool angled)>;

// The resolver that searches as xshade's preprocessor does (hlsl::find_include: the including
// file's folder, then `include_dirs` in order), so that both front ends read the same files.
IncludeResolver include_resolver(std::vector<std::filesystem::path> include_dirs);

struct HlslStage {
  std::string_view source;
  std::string source_name;
  Stage stage = Stage::Fragment;
  std::string entry_point;  // the HLSL function; the SPIR-V entry point keeps its name
  std::vector<std::pair<std::string, std::string>> defines;
  IncludeResolver resolve_include;  // may be empty: then any #include fails
  BindingShifts shifts;
  // Bindings for resources declared without a register, by name ("$Global" for the globals'
  // buffer): the numbers the program's other stage and the other lanes use. glslang would
  // number each stage on its own, so a buffer only the vertex stage reads could take, in the
  // fragment stage, the number another buffer has there, and one program would bind one number
  // twice. Resources not named here get glslang's lowest free slot.
  std::map<std::string, uint32_t> bindings;
  // The location of each varying by its canonical semantic, as the program's other stage and the
  // other lanes place it (hlsl::Reflection::varyings); a varying not named here is placed by
  // hlsl::varying_location.
  std::map<std::string, uint32_t> varying_locations = {};
  // The same for vertex inputs (hlsl::Reflection::vertex_inputs); one not named here is placed
  // by hlsl::vertex_input_location.
  std::map<std::string, uint32_t> vertex_input_locations = {};
  // Run glslang's legalization (SPIRV-Tools passes that forward opaque values to their uses):
  // HLSL that keeps a texture in a local or a struct field needs it, or the SPIR-V is invalid
  // for Vulkan. Off otherwise, so that the lane's code is glslang's translation as it is.
  bool legalize = false;
  // The source reads storage buffers (StructuredBuffer & co.): glslang (12) decorates their blocks
  // BufferBlock, which SPIR-V after 1.3 does not have, so such a module is made as SPIR-V 1.3
  // (Vulkan 1.3 runs it the same).
  bool storage_buffers = false;
  // The byte offset of each member of each constant buffer, by buffer ("$Global" for the globals)
  // and member name: HLSL's packing, which the host writes. glslang packs a declared cbuffer so,
  // but lays the globals' block out by std140 rules (a float3 after a float at 16, not 4); a member
  // the module places elsewhere than given here gets its Offset decoration set to the given one
  // (what DXC emits; Vulkan's relaxed block layout allows it). Buffers not named are left alone.
  std::map<std::string, std::map<std::string, uint32_t>> member_offsets = {};
};

// A resource of the compiled module as glslang reflects it.
struct HlslResource {
  enum class Kind { ConstantBuffer, Texture, Sampler, CombinedSampler };
  Kind kind = Kind::ConstantBuffer;
  std::string name;
  uint32_t binding = 0;
  uint32_t size = 0;           // bytes, for constant buffers
  bool push_constant = false;  // a constant buffer in push constants, which has no binding
};

struct HlslModule {
  SpirvModule module;
  std::vector<HlslResource> resources;
};

// Compiles with EShSourceHlsl, EShMsgReadHlsl, EShMsgHlslDX9Compatible (sampler2D and tex2D) and
// EShMsgHlslOffsets (HLSL constant-buffer packing), then validates the SPIR-V.
Result<HlslModule> compile_hlsl(const HlslStage& stage);

}  // namespace xshade::spirv
