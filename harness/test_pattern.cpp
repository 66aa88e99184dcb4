#include "harness/test_pattern.h"

#include "harness/meshes.h"

#include <array>

namespace xshade::harness::test_pattern {
namespace {

const GlslStagePair kVertex{
    R"(#version 450 core
layout(location = 0) in vec3 position;
layout(location = 3) in vec2 texcoord;
layout(location = 0) out vec2 uv;
void main() {
  uv = texcoord;
  gl_Position = vec4(position, 1.0);
}
)",
    R"(#version 450
layout(location = 0) in vec3 position;
layout(location = 3) in vec2 texcoord;
layout(location = 0) out vec2 uv;
void main() {
  uv = texcoord;
  gl_Position = vec4(position, 1.0);
}
)",
    "test_pattern.vert"};

const GlslStagePair kFragment{
    R"(#version 450 core
layout(std140, binding = 0) uniform Quad { vec4 color; vec4 use_texture; };
layout(binding = 1) uniform sampler2D pattern;
layout(location = 0) in vec2 uv;
layout(location = 0) out vec4 target;
void main() {
  target = use_texture.x > 0.5 ? texture(pattern, uv) : color;
}
)",
    R"(#version 450
layout(std140, set = 0, binding = 0) uniform Quad { vec4 color; vec4 use_texture; };
layout(set = 0, binding = 1) uniform texture2D pattern;
layout(set = 0, binding = 2) uniform sampler pattern_sampler;
layout(location = 0) in vec2 uv;
layout(location = 0) out vec4 target;
void main() {
  target = use_texture.x > 0.5 ? texture(sampler2D(pattern, pattern_sampler), uv) : color;
}
)",
    "test_pattern.frag"};

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
  auto vertex = stage_for_lane(lane, spirv::Stage::Vertex, kVertex);
  if (!vertex) return fail(vertex.error());
  auto fragment = stage_for_lane(lane, spirv::Stage::Fragment, kFragment);
  if (!fragment) return fail(fragment.error());

  ProgramDesc desc;
  desc.name = "test_pattern";
  desc.vertex = std::move(*vertex);
  desc.fragment = std::move(*fragment);
  desc.layout.uniform_blocks = {{"Quad", 0, 32}};
  desc.layout.textures = {{"pattern", 1, 2}};
  auto program = backend.create_program(desc);
  if (!program) return fail(program.error());

  TextureData texture;
  texture.format = TextureFormat::Rgba8Unorm;
  texture.width = texture.height = kTextureSize;
  auto& level = texture.levels.emplace_back(kTextureSize * kTextureSize * 4);
  for (uint32_t row = 0; row < kTextureSize; ++row)
    for (uint32_t column = 0; column < kTextureSize; ++column)
      for (int c = 0; c < 4; ++c)
        level[(row * kTextureSize + column) * 4 + c] =
            std::byte(uint8_t(texel(column, row)[c] * 255.0f + 0.5f));
  auto pattern = backend.upload_texture(texture);
  if (!pattern) return fail(pattern.error());

  auto target = backend.create_target({size, size, true});
  if (!target) return fail(target.error());

  RenderPass pass;
  pass.target = *target;
  const TextureBinding texture_binding{
      "pattern", TextureSource::texture(*pattern, {Filter::Nearest, AddressMode::ClampToEdge})};
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
    auto mesh = backend.upload_mesh(spec.mesh);
    if (!mesh) return fail(mesh.error());
    pass.draws.push_back({*program, *mesh, {{"Quad", quad_uniforms(spec.color, spec.textured)}},
                          {texture_binding}});
  }
  if (auto rendered = backend.render(pass); !rendered) return fail(rendered.error());
  return backend.read_color(*target);
}

}  // namespace xshade::harness::test_pattern
