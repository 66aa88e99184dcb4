#include "harness/render/test_pattern.h"

#include "harness/assets/meshes.h"
#include "harness/backend/resource_set.h"
#include "harness/render/shader_program.h"

#include <array>

namespace xshade::harness::test_pattern {
namespace {

// The pattern's shader, in hlsl_like: every lane compiles it the way it compiles any shader.
constexpr const char* kShader = R"(
#pragma vertex vert
#pragma fragment frag

cbuffer Quad : register(b0) {
  float4 color;
  float4 use_texture;  // x > 0.5: show the texture instead of the colour
};
Texture2D pattern : register(t0);
SamplerState pattern_sampler : register(s0);

struct VertexIn {
  float3 position : POSITION;  // already in clip space
  float2 uv : TEXCOORD0;
};
struct VertexOut {
  float4 position : SV_Position;
  float2 uv : TEXCOORD0;
};

VertexOut vert(VertexIn v) {
  VertexOut o;
  o.position = float4(v.position, 1.0);
  o.uv = v.uv;
  return o;
}

float4 frag(VertexOut i) : SV_Target {
  if (use_texture.x > 0.5) return pattern.Sample(pattern_sampler, i.uv);
  return color;
}
)";

std::vector<std::byte> quad_uniforms(glm::vec4 color, bool use_texture) {
  return uniform_bytes(std::array<glm::vec4, 2>{color, glm::vec4(use_texture ? 1.0f : 0.0f)});
}

}  // namespace

glm::vec4 texel(uint32_t column, uint32_t row) {
  if (column == 0 && row == 0) return kFirstTexel;
  // Distinct, dark, and exactly representable in 8 bits.
  return {float(column * 40) / 255.0f, float(row * 40) / 255.0f, 60.0f / 255.0f, 1.0f};
}

Result<FloatImage> render(Backend& backend, Lane lane, uint32_t size) {
  auto module = hlsl::compile_text("test_pattern.hlsl", kShader, {});
  if (!module->ok())
    return fail(ErrorKind::Internal, "the test pattern does not compile:\n" + module->diagnostics.render_all());
  auto desc = program_for_lane(*module, lane);
  if (!desc) return fail(desc.error());
  // Everything here is this render's own: freed when it returns, however it returns.
  ResourceSet resources(backend);
  auto program = resources.create_program(*desc);
  if (!program) return fail(program.error());

  TextureData texture;
  texture.format = TextureFormat::Rgba8Unorm;
  texture.width = texture.height = kTextureSize;
  auto& level = texture.levels.emplace_back(kTextureSize * kTextureSize * 4);
  for (uint32_t row = 0; row < kTextureSize; ++row)
    for (uint32_t column = 0; column < kTextureSize; ++column)
      for (int c = 0; c < 4; ++c)
        level[(row * kTextureSize + column) * 4 + c] = std::byte(uint8_t(texel(column, row)[c] * 255.0f + 0.5f));
  auto pattern = resources.upload_texture(texture);
  if (!pattern) return fail(pattern.error());

  auto target = resources.create_target({size, size, true});
  if (!target) return fail(target.error());

  RenderPass pass;
  pass.target = *target;
  const TextureBinding texture_binding{"pattern",
                                       TextureSource::texture(*pattern, {Filter::Nearest, AddressMode::ClampToEdge})};
  struct QuadSpec {
    MeshData mesh;
    glm::vec4 color;
    bool textured;
  };
  const std::array<QuadSpec, 4> quads{{{clip_rectangle(-1, 0, 0, 1, 0.5f), kTopLeft, false},
                                       {clip_rectangle(0, 0, 1, 1, 0.5f), kTopRight, false},
                                       {clip_rectangle(-1, -1, 0, 0, 0.5f), kBottomLeft, false},
                                       {clip_rectangle(0, -1, 1, 0, 0.5f), glm::vec4(0.0f), true}}};
  for (const QuadSpec& spec : quads) {
    auto mesh = resources.upload_mesh(spec.mesh);
    if (!mesh) return fail(mesh.error());
    pass.draws.push_back(
        {*program, *mesh, {{"Quad", quad_uniforms(spec.color, spec.textured)}}, {texture_binding}, {}});
  }
  if (auto rendered = backend.render(pass); !rendered) return fail(rendered.error());
  return backend.read_color(*target);
}

}  // namespace xshade::harness::test_pattern
