// Running one fragment shader as a full-screen pass on a lane: what `xshade eval` and the
// semantics conformance tests do.
#pragma once

#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "harness/backend/backend.h"
#include "harness/render/lanes.h"
#include "harness/render/shader_interface.h"
#include "harness/render/shader_program.h"
#include "hlsl_like/compiler.h"

namespace xshade::harness {

// The bytes of a constant buffer with every member at its property's default value (zero when
// it has none), laid out at the HLSL offsets reflection gives.
std::vector<std::byte> default_constant_buffer(const hlsl::ConstantBuffer& buffer,
                                               const std::vector<hlsl::Property>& properties);

// What a full-screen program reads besides its defaults, each by its HLSL name: constant buffers'
// bytes (each the buffer's size), textures (uploaded to the backend by the caller) and read-only
// buffers' bytes (whole 32-bit words laid out as Direct3D lays the buffer out).
struct FullscreenInputs {
  std::map<std::string, std::vector<std::byte>> constant_buffers = {};
  std::map<std::string, TextureSource> textures = {};
  std::map<std::string, std::vector<std::byte>> storage_buffers = {};
};

// A module's fragment entry made into a full-screen program on one backend, to run as often as
// needed: the driver compiles it once. The shader reads uv (TEXCOORD0, (0,0) at the top-left)
// and the pixel position (SV_Position); constant buffers hold their defaults unless given, and
// every texture not given is one white texel of the shape and texel kind the shader declared
// (a depth texel of 1 for a texture read with a comparison sampler). A read-only buffer has no
// default: one the shader reads must be given.
class FullscreenProgram {
 public:
  static Result<FullscreenProgram> create(const hlsl::Module& module, Lane lane, Backend& backend,
                                          const ProgramOptions& options = {});

  // Renders a width x height RGBA32F target with `inputs` in place of the defaults; a name the
  // program does not read is an error.
  // A program made with ProgramOptions::trace_nonfinite also records where non-finite values
  // were born: into `record` (glsl::NonfiniteTrace says how it reads) when given.
  Result<FloatImage> run(Backend& backend, uint32_t width, uint32_t height, const FullscreenInputs& inputs = {},
                         FloatImage* record = nullptr) const;

  // The same with every constant buffer, texture and read-only buffer made from `seed`
  // (synthetic_inputs.h) in place of the defaults: what corpus execution feeds a real shader.
  Result<FloatImage> run_seeded(Backend& backend, uint32_t width, uint32_t height, uint32_t seed,
                                FloatImage* record = nullptr) const;

  // A traced program's sites and calls (empty otherwise).
  const glsl::NonfiniteTrace& trace() const { return trace_; }

  // The size in bytes of the constant buffer `name`, if the program has one.
  std::optional<uint32_t> constant_buffer_size(const std::string& name) const;

  // The backend's program: the caller destroys it when it is done with the program.
  ProgramHandle handle() const { return program_; }

 private:
  struct Buffer {
    std::string name;  // HLSL, the layout's name for it
    std::vector<std::byte> defaults;
    hlsl::ConstantBuffer declared;  // its members, for seeded bytes (decl cleared: the module may go)
  };
  ProgramHandle program_;
  bool traced_ = false;
  glsl::NonfiniteTrace trace_;
  std::vector<Buffer> buffers_;
  std::vector<TextureSlot> texture_slots_;
  std::vector<StorageBufferInput> storage_buffers_;  // the ones read
};

// FullscreenProgram::create then run, once, then the program destroyed: what `xshade eval` and the
// conformance tests do.
Result<FloatImage> evaluate(const hlsl::Module& module, Lane lane, Backend& backend, uint32_t width, uint32_t height,
                            const std::map<std::string, std::vector<std::byte>>& constant_buffers = {},
                            const ProgramOptions& options = {},
                            const std::map<std::string, TextureSource>& textures = {},
                            const std::map<std::string, std::vector<std::byte>>& storage_buffers = {});

// One texel of value 1 in every channel (a depth of 1 for a comparison slot) in the shape and
// texel kind `slot` declares: what a texture the caller does not give reads.
TextureData default_texture(const TextureSlot& slot);

}  // namespace xshade::harness
