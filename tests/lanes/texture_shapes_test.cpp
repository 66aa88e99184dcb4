// Every texture shape and method the front end compiles, evaluated on every lane (gl, vk and
// vk-hlsl) and checked pixel by pixel against the value the host computes from HLSL's
// definition: the texel a coordinate addresses, Direct3D's cube-face selection, Gather's
// component order, comparison as `reference <= texel`. Each texel holds a value distinct per
// coordinate, layer and level, and sampling is nearest at texel centres (or where the method
// is defined to be exact), so the expected values are exact and a wrong texel, face, layer,
// level, offset or order shows.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <functional>
#include <map>

#include <gtest/gtest.h>
#include <glm/glm.hpp>

#include "harness/render/evaluate.h"
#include "harness/render/shader_program.h"
#include "harness/vulkan/vulkan_backend.h"
#include "hlsl_like/compiler.h"
#include "tests/lanes/lane_fixture.h"

namespace xshade::tests {
namespace {

using harness::Filter;
using harness::Lane;
using harness::TextureData;
using harness::TextureDimension;
using harness::TextureFormat;

const harness::SamplerDesc kPoint{Filter::Nearest, harness::AddressMode::ClampToEdge};

// The value of texel (x, y) of layer (or slice) `layer` of level `level`: each coordinate in a
// channel of its own, with a fraction that says which channel it is, all exact in fp32.
glm::vec4 texel_value(uint32_t x, uint32_t y, uint32_t layer, uint32_t level) {
  return {float(x) + 0.5f, float(y) + 0.25f, float(layer) + 0.125f, float(level) + 0.0625f};
}

template <class T>
void append(std::vector<std::byte>& bytes, const T& value) {
  const auto* first = reinterpret_cast<const std::byte*>(&value);
  bytes.insert(bytes.end(), first, first + sizeof value);
}

// An RGBA32F texture of texel_value, every level filled: `layers` array layers (or the depth of
// a 3D texture, which halves per level).
TextureData float_texture(TextureDimension dimension, uint32_t width, uint32_t height, uint32_t layers, uint32_t levels,
                          uint32_t samples = 1) {
  TextureData texture;
  texture.format = TextureFormat::Rgba32Float;
  texture.dimension = dimension;
  texture.width = width;
  texture.height = height;
  texture.layers = layers;
  texture.samples = samples;
  for (uint32_t level = 0; level < levels; ++level) {
    const uint32_t w = std::max(1u, width >> level), h = std::max(1u, height >> level);
    const uint32_t d = dimension == TextureDimension::Tex3D ? std::max(1u, layers >> level) : layers;
    std::vector<std::byte>& bytes = texture.levels.emplace_back();
    for (uint32_t layer = 0; layer < d; ++layer)
      for (uint32_t y = 0; y < h; ++y)
        for (uint32_t x = 0; x < w; ++x) append(bytes, texel_value(x, y, layer, level));
  }
  return texture;
}

// A one-level D32F texture whose texel i (layers, then rows, then columns) holds (i + 0.5) / n.
TextureData depth_texture(TextureDimension dimension, uint32_t size, uint32_t layers) {
  TextureData texture;
  texture.format = TextureFormat::Depth32Float;
  texture.dimension = dimension;
  texture.width = size;
  texture.height = dimension == TextureDimension::Tex1D ? 1 : size;
  texture.layers = layers;
  const uint32_t n = texture.width * texture.height * layers;
  std::vector<std::byte>& bytes = texture.levels.emplace_back();
  for (uint32_t i = 0; i < n; ++i) append(bytes, (float(i) + 0.5f) / float(n));
  return texture;
}
float depth_value(uint32_t x, uint32_t y, uint32_t layer, uint32_t size, uint32_t layers) {
  const uint32_t n = size * size * layers;
  return (float((layer * size + y) * size + x) + 0.5f) / float(n);
}

// ---- Direct3D's cube-face selection (the table OpenGL and Vulkan share) -----------------------

struct CubeTexel {
  uint32_t face;  // +X, -X, +Y, -Y, +Z, -Z
  uint32_t x, y;  // of a size x size face, row 0 at t = 0
};
CubeTexel cube_texel(glm::vec3 r, uint32_t size) {
  const glm::vec3 a = glm::abs(r);
  uint32_t face;
  float sc, tc, ma;
  if (a.x >= a.y && a.x >= a.z) {
    face = r.x >= 0 ? 0 : 1;
    ma = a.x, sc = r.x >= 0 ? -r.z : r.z, tc = -r.y;
  } else if (a.y >= a.z) {
    face = r.y >= 0 ? 2 : 3;
    ma = a.y, sc = r.x, tc = r.y >= 0 ? r.z : -r.z;
  } else {
    face = r.z >= 0 ? 4 : 5;
    ma = a.z, sc = r.z >= 0 ? r.x : -r.x, tc = -r.y;
  }
  const float s = (sc / ma + 1.0f) * 0.5f, t = (tc / ma + 1.0f) * 0.5f;
  const auto texel = [size](float coordinate) {
    return std::min(size - 1, uint32_t(std::max(0.0f, std::floor(coordinate * float(size)))));
  };
  return {face, texel(s), texel(t)};
}

// The direction the cube shaders look along from cell (x, y) of an 8 x 8 grid (kCubeDirection
// below, in HLSL). Every face is hit, no two components tie for the major axis, and no
// coordinate lands on a texel edge of a 2 x 2 face (sc is never 0).
glm::vec3 cube_direction(uint32_t x, uint32_t y) {
  return {float(x) - 3.5f, (float(y) - 3.5f) * 0.9f, y < 4 ? 3.0f : -3.0f};
}
constexpr const char* kCubeDirection = R"(
float3 cube_direction(int2 cell) {
  return float3(cell.x - 3.5, (cell.y - 3.5) * 0.9, cell.y < 4 ? 3.0 : -3.0);
}
)";

// ---- Running a shader on every lane -----------------------------------------------------------

struct Input {
  TextureData data;
  harness::SamplerDesc sampler = kPoint;
};

using Expected = std::function<glm::vec4(uint32_t x, uint32_t y)>;
using ConstantBuffers = std::map<std::string, std::vector<std::byte>>;

class TextureShapes : public LaneTest {
 protected:
  // `source` as a full-screen pass of width x height on `lane`, with `inputs` bound by name.
  harness::FloatImage run(Lane lane, const std::string& source, uint32_t width, uint32_t height,
                          const std::map<std::string, Input>& inputs, const ConstantBuffers& constant_buffers = {}) {
    auto module = hlsl::compile_text("texture_shapes.hlsl", source, {});
    if (!module->ok()) {
      std::string diagnostics;
      for (const Diagnostic& d : module->diagnostics.diagnostics()) diagnostics += d.message + "\n";
      ADD_FAILURE() << "the shader does not compile:\n" << diagnostics;
      return {};
    }
    std::map<std::string, harness::TextureSource> textures;
    for (const auto& [name, input] : inputs) {
      auto handle = backend(lane).upload_texture(input.data);
      if (!handle) {
        ADD_FAILURE() << harness::lane_name(lane) << ": " << handle.error().to_string();
        return {};
      }
      textures[name] = harness::TextureSource::texture(*handle, input.sampler);
    }
    auto image = harness::evaluate(*module, lane, backend(lane), width, height, constant_buffers, {}, textures);
    if (!image) {
      ADD_FAILURE() << harness::lane_name(lane) << ": " << image.error().to_string();
      return {};
    }
    return *image;
  }

  // Runs on every lane and compares every pixel with `expected`, within `tolerance` per channel.
  void check(const std::string& source, uint32_t width, uint32_t height, const std::map<std::string, Input>& inputs,
             const Expected& expected, float tolerance = 0.0f, const ConstantBuffers& constant_buffers = {}) {
    for (Lane lane : harness::all_lanes()) {
      SCOPED_TRACE(harness::lane_name(lane));
      const harness::FloatImage image = run(lane, source, width, height, inputs, constant_buffers);
      ASSERT_EQ(image.width, width);
      ASSERT_EQ(image.height, height);
      int reported = 0;
      for (uint32_t y = 0; y < height; ++y)
        for (uint32_t x = 0; x < width; ++x) {
          const glm::vec4 want = expected(x, y), got = image.at(x, y);
          bool same = true;
          for (int c = 0; c < 4; ++c) same = same && std::fabs(got[c] - want[c]) <= tolerance;
          if (!same && reported++ < 6)
            ADD_FAILURE() << "pixel " << x << "," << y << ": got (" << got.x << ", " << got.y << ", " << got.z << ", "
                          << got.w << "), expected (" << want.x << ", " << want.y << ", " << want.z << ", " << want.w
                          << ")";
        }
      EXPECT_EQ(reported, 0) << reported << " pixels differ";
    }
  }
};

// ---- Shapes -----------------------------------------------------------------------------------

TEST_F(TextureShapes, Texture1DSampleSampleLevelAndLoad) {
  const char* source = R"(
#pragma fragment frag
Texture1D<float4> line_texture;
SamplerState point_sampler;
float4 frag(float2 uv : TEXCOORD0, float4 pos : SV_Position) : SV_Target {
  int2 p = int2(pos.xy);
  float u = (p.x + 0.5) / 8.0;
  float4 sampled = line_texture.Sample(point_sampler, u);
  float4 level1 = line_texture.SampleLevel(point_sampler, u, 1);
  float4 loaded = line_texture.Load(int2(p.x / 2, 1));
  return p.y == 0 ? sampled : (p.y == 1 ? level1 : loaded);
}
)";
  check(source, 8, 3, {{"line_texture", {float_texture(TextureDimension::Tex1D, 8, 1, 1, 2)}}},
        [](uint32_t x, uint32_t y) { return y == 0 ? texel_value(x, 0, 0, 0) : texel_value(x / 2, 0, 0, 1); });
}

TEST_F(TextureShapes, Texture1DArraySampleAndLoadByLayer) {
  const char* source = R"(
#pragma fragment frag
Texture1DArray<float4> lines;
SamplerState point_sampler;
float4 frag(float2 uv : TEXCOORD0, float4 pos : SV_Position) : SV_Target {
  int2 p = int2(pos.xy);
  float u = (p.x + 0.5) / 8.0;
  float4 sampled = lines.Sample(point_sampler, float2(u, p.y));
  float4 loaded = lines.Load(int3(p.x - 8, p.y, 0));
  return p.x < 8 ? sampled : loaded;
}
)";
  check(source, 16, 3, {{"lines", {float_texture(TextureDimension::Tex1DArray, 8, 1, 3, 1)}}},
        [](uint32_t x, uint32_t y) { return texel_value(x % 8, 0, y, 0); });
}

TEST_F(TextureShapes, Texture2DArraySampleAndSampleLevelPerLayer) {
  const char* source = R"(
#pragma fragment frag
Texture2DArray<float4> layers;
SamplerState point_sampler;
float4 frag(float2 uv : TEXCOORD0, float4 pos : SV_Position) : SV_Target {
  int2 p = int2(pos.xy);
  int layer = p.y / 4;
  float2 st = (float2(p.x % 4, p.y % 4) + 0.5) / 4.0;
  float4 sampled = layers.Sample(point_sampler, float3(st, layer));
  float4 level1 = layers.SampleLevel(point_sampler, float3(st, layer), 1);
  return p.x < 4 ? sampled : level1;
}
)";
  check(source, 8, 12, {{"layers", {float_texture(TextureDimension::Tex2DArray, 4, 4, 3, 2)}}},
        [](uint32_t x, uint32_t y) {
          return x < 4 ? texel_value(x, y % 4, y / 4, 0) : texel_value((x - 4) / 2, (y % 4) / 2, y / 4, 1);
        });
}

// A 4 x 4 x 4 volume of two levels: slices of 4 rows down the target, level 0 on the left and
// level 1 (2 x 2 x 2) on the right.
Expected volume_expected() {
  return [](uint32_t x, uint32_t y) {
    const uint32_t row = y % 4, slice = y / 4;
    return x < 4 ? texel_value(x, row, slice, 0) : texel_value((x - 4) / 2, row / 2, slice / 2, 1);
  };
}

TEST_F(TextureShapes, Texture3DSampleAndSampleLevel) {
  const char* source = R"(
#pragma fragment frag
Texture3D<float4> volume;
SamplerState point_sampler;
float4 frag(float2 uv : TEXCOORD0, float4 pos : SV_Position) : SV_Target {
  int2 p = int2(pos.xy);
  float3 uvw = (float3(p.x % 4, p.y % 4, p.y / 4) + 0.5) / 4.0;
  float4 sampled = volume.Sample(point_sampler, uvw);
  float4 level1 = volume.SampleLevel(point_sampler, uvw, 1);
  return p.x < 4 ? sampled : level1;
}
)";
  check(source, 8, 16, {{"volume", {float_texture(TextureDimension::Tex3D, 4, 4, 4, 2)}}}, volume_expected());
}

TEST_F(TextureShapes, Sampler3DTex3DAndTex3Dlod) {
  const char* source = R"(
#pragma fragment frag
sampler3D volume;
float4 frag(float2 uv : TEXCOORD0, float4 pos : SV_Position) : SV_Target {
  int2 p = int2(pos.xy);
  float3 uvw = (float3(p.x % 4, p.y % 4, p.y / 4) + 0.5) / 4.0;
  float4 sampled = tex3D(volume, uvw);
  float4 level1 = tex3Dlod(volume, float4(uvw, 1));
  return p.x < 4 ? sampled : level1;
}
)";
  check(source, 8, 16, {{"volume", {float_texture(TextureDimension::Tex3D, 4, 4, 4, 2)}}}, volume_expected());
}

// Cubes of 2 x 2 faces (level 1: 1 x 1), looked at along cube_direction: both APIs select the
// face and the texel as Direct3D does, from the same upload.
TEST_F(TextureShapes, TextureCubeSampleAndSampleLevelSelectFacesAsDirect3D) {
  const std::string source = std::string(R"(
#pragma fragment frag
TextureCube one_level;
TextureCube two_levels;
SamplerState point_sampler;
SamplerState point_sampler_2;
)") + kCubeDirection + R"(
float4 frag(float2 uv : TEXCOORD0, float4 pos : SV_Position) : SV_Target {
  int2 p = int2(pos.xy);
  float3 direction = cube_direction(int2(p.x % 8, p.y));
  float4 sampled = one_level.Sample(point_sampler, direction);
  float4 level0 = two_levels.SampleLevel(point_sampler_2, direction, 0);
  float4 level1 = two_levels.SampleLevel(point_sampler_2, direction, 1);
  return p.x < 8 ? sampled : (p.x < 16 ? level0 : level1);
}
)";
  check(source, 24, 8,
        {{"one_level", {float_texture(TextureDimension::Cube, 2, 2, 6, 1)}},
         {"two_levels", {float_texture(TextureDimension::Cube, 2, 2, 6, 2)}}},
        [](uint32_t x, uint32_t y) {
          const CubeTexel t = cube_texel(cube_direction(x % 8, y), 2);
          return x < 16 ? texel_value(t.x, t.y, t.face, 0) : texel_value(0, 0, t.face, 1);
        });
}

TEST_F(TextureShapes, TextureCubeArraySampleLevelPerCube) {
  const std::string source = std::string(R"(
#pragma fragment frag
TextureCubeArray cubes;
SamplerState point_sampler;
)") + kCubeDirection + R"(
float4 frag(float2 uv : TEXCOORD0, float4 pos : SV_Position) : SV_Target {
  int2 p = int2(pos.xy);
  float4 coordinate = float4(cube_direction(int2(p.x % 8, p.y % 8)), p.y / 8);
  float4 level0 = cubes.SampleLevel(point_sampler, coordinate, 0);
  float4 level1 = cubes.SampleLevel(point_sampler, coordinate, 1);
  return p.x < 8 ? level0 : level1;
}
)";
  check(source, 16, 16, {{"cubes", {float_texture(TextureDimension::CubeArray, 2, 2, 12, 2)}}},
        [](uint32_t x, uint32_t y) {
          const CubeTexel t = cube_texel(cube_direction(x % 8, y % 8), 2);
          const uint32_t layer = (y / 8) * 6 + t.face;
          return x < 8 ? texel_value(t.x, t.y, layer, 0) : texel_value(0, 0, layer, 1);
        });
}

TEST_F(TextureShapes, SamplerCubeTexCubeLodAndBias) {
  // A bias of +8 reaches past the last level whatever the implicit level of detail (below 3 for
  // a 2 x 2 face), and one of -8 stays below level 0: the level is known without derivatives.
  const std::string source = std::string(R"(
#pragma fragment frag
samplerCUBE one_level;
samplerCUBE two_levels;
)") + kCubeDirection + R"(
float4 frag(float2 uv : TEXCOORD0, float4 pos : SV_Position) : SV_Target {
  int2 p = int2(pos.xy);
  float3 direction = cube_direction(int2(p.x % 8, p.y));
  float4 sampled = texCUBE(one_level, direction);
  float4 lod1 = texCUBElod(two_levels, float4(direction, 1));
  float4 biased_up = texCUBEbias(two_levels, float4(direction, 8));
  float4 biased_down = texCUBEbias(two_levels, float4(direction, -8));
  int mode = p.x / 8;
  return mode == 0 ? sampled : (mode == 1 ? lod1 : (mode == 2 ? biased_up : biased_down));
}
)";
  check(source, 32, 8,
        {{"one_level", {float_texture(TextureDimension::Cube, 2, 2, 6, 1)}},
         {"two_levels", {float_texture(TextureDimension::Cube, 2, 2, 6, 2)}}},
        [](uint32_t x, uint32_t y) {
          const CubeTexel t = cube_texel(cube_direction(x % 8, y), 2);
          const uint32_t mode = x / 8;
          return mode == 0 || mode == 3 ? texel_value(t.x, t.y, t.face, 0) : texel_value(0, 0, t.face, 1);
        });
}

TEST_F(TextureShapes, Texture2DMSLoadReadsEverySampleOfTheUpload) {
  // A multisampled texture is filled by a draw of its level-0 data into every sample: each of
  // the four samples of every texel, in both a 2D and a 2D-array texture, reads the texel.
  const char* source = R"(
#pragma fragment frag
Texture2DMS<float4> plain;
Texture2DMSArray<float4, 4> layered;
float4 frag(float2 uv : TEXCOORD0, float4 pos : SV_Position) : SV_Target {
  int2 p = int2(pos.xy);
  int2 texel = int2(p.x / 4, p.y % 4);
  int sample_index = p.x % 4;
  float4 from_plain = plain.Load(texel, sample_index);
  float4 from_layered = layered.Load(int3(texel, p.y / 4 - 1), sample_index);
  return p.y < 4 ? from_plain : from_layered;
}
)";
  check(source, 16, 12,
        {{"plain", {float_texture(TextureDimension::Tex2D, 4, 4, 1, 1, 4)}},
         {"layered", {float_texture(TextureDimension::Tex2DArray, 4, 4, 2, 1, 4)}}},
        [](uint32_t x, uint32_t y) { return texel_value(x / 4, y % 4, y < 4 ? 0 : y / 4 - 1, 0); });
}

// ---- Loads, offsets, typed texels ---------------------------------------------------------

constexpr uint32_t kUintBase = 3000000000u;  // above INT_MAX: read as int it would be negative
uint32_t uint_texel(uint32_t x, uint32_t y, uint32_t c) { return kUintBase + (x + 8 * y) * 512u + c * 65536u; }
int32_t int_texel(uint32_t x, uint32_t y, uint32_t c) { return -int32_t(x + 8 * y) * 3 - int32_t(c) * 1000 - 7; }
float single_texel(uint32_t x, uint32_t y) { return float(x) * 10.0f + float(y) + 0.5f; }

TEST_F(TextureShapes, LoadWithOffsetIndexingAndTypedTexels) {
  // Blocks of 7 rows: Load at level 0 with an offset, Load at level 1 with an offset, t[int2],
  // a uint4 texture, an int4 texture by index, a single-channel float texture. The uint values
  // are multiples of 512 below 2^32, exact as floats, and above INT_MAX.
  const char* source = R"(
#pragma fragment frag
Texture2D<float4> colors;
Texture2D<uint4> ids;
Texture2D<int4> signed_ids;
Texture2D<float> single;
float4 frag(float2 uv : TEXCOORD0, float4 pos : SV_Position) : SV_Target {
  int2 p = int2(pos.xy);
  int2 q = int2(p.x, p.y % 7);
  int mode = p.y / 7;
  float4 offset0 = colors.Load(int3(q.x, q.y + 1, 0), int2(1, -1));
  float4 offset1 = colors.Load(int3(min(q / 2, 2), 1), int2(1, 1));
  float4 indexed = colors[q];
  float4 unsigned_texel = float4(ids.Load(int3(q, 0)));
  float4 signed_texel = float4(signed_ids[q]);
  float4 one_channel = float4(single.Load(int3(q, 0)), single[q], 0, 1);
  return mode == 0 ? offset0 : mode == 1 ? offset1 : mode == 2 ? indexed
       : mode == 3 ? unsigned_texel : mode == 4 ? signed_texel : one_channel;
}
)";
  TextureData ids{TextureFormat::Rgba32Uint, 8, 8, {{}}};
  TextureData signed_ids{TextureFormat::Rgba32Sint, 8, 8, {{}}};
  TextureData single{TextureFormat::R32Float, 8, 8, {{}}};
  for (uint32_t y = 0; y < 8; ++y)
    for (uint32_t x = 0; x < 8; ++x) {
      for (uint32_t c = 0; c < 4; ++c) append(ids.levels[0], uint_texel(x, y, c));
      for (uint32_t c = 0; c < 4; ++c) append(signed_ids.levels[0], int_texel(x, y, c));
      append(single.levels[0], single_texel(x, y));
    }
  check(source, 7, 42,
        {{"colors", {float_texture(TextureDimension::Tex2D, 8, 8, 1, 2)}},
         {"ids", {ids}},
         {"signed_ids", {signed_ids}},
         {"single", {single}}},
        [](uint32_t x, uint32_t y) {
          const uint32_t row = y % 7;
          switch (y / 7) {
            case 0: return texel_value(x + 1, row, 0, 0);
            case 1: return texel_value(std::min(x / 2, 2u) + 1, std::min(row / 2, 2u) + 1, 0, 1);
            case 2: return texel_value(x, row, 0, 0);
            case 3:
              return glm::vec4(float(uint_texel(x, row, 0)), float(uint_texel(x, row, 1)), float(uint_texel(x, row, 2)),
                               float(uint_texel(x, row, 3)));
            case 4:
              return glm::vec4(float(int_texel(x, row, 0)), float(int_texel(x, row, 1)), float(int_texel(x, row, 2)),
                               float(int_texel(x, row, 3)));
            default: return glm::vec4(single_texel(x, row), single_texel(x, row), 0.0f, 1.0f);
          }
        });
}

TEST_F(TextureShapes, LoadOffsetsMoveTexelsNotLayers) {
  // Blocks of 3 rows: a 2D array, a 1D array, a volume and a multisampled 2D array, each Loaded
  // at layer (or slice) 1 with an offset; the offset moves the texel, never the layer.
  const char* source = R"(
#pragma fragment frag
Texture2DArray<float4> layers;
Texture1DArray<float4> lines;
Texture3D<float4> volume;
Texture2DMSArray<float4> ms_layers;
float4 frag(float2 uv : TEXCOORD0, float4 pos : SV_Position) : SV_Target {
  int2 p = int2(pos.xy);
  int2 q = int2(p.x, p.y % 3);
  int mode = p.y / 3;
  float4 from_layers = layers.Load(int4(q, 1, 0), int2(1, 1));
  float4 from_lines = lines.Load(int3(q.x, 1, 0), 1);
  float4 from_volume = volume.Load(int4(q, 1, 0), int3(1, 1, 1));
  float4 from_ms = ms_layers.Load(int3(q, 1), 2, int2(1, 1));
  return mode == 0 ? from_layers : mode == 1 ? from_lines : mode == 2 ? from_volume : from_ms;
}
)";
  check(source, 3, 12,
        {{"layers", {float_texture(TextureDimension::Tex2DArray, 4, 4, 2, 1)}},
         {"lines", {float_texture(TextureDimension::Tex1DArray, 4, 1, 2, 1)}},
         {"volume", {float_texture(TextureDimension::Tex3D, 4, 4, 4, 1)}},
         {"ms_layers", {float_texture(TextureDimension::Tex2DArray, 4, 4, 2, 1, 4)}}},
        [](uint32_t x, uint32_t y) {
          const uint32_t row = y % 3;
          switch (y / 3) {
            case 0: return texel_value(x + 1, row + 1, 1, 0);
            case 1: return texel_value(x + 1, 0, 1, 0);
            case 2: return texel_value(x + 1, row + 1, 2, 0);
            default: return texel_value(x + 1, row + 1, 1, 0);
          }
        });
}

TEST_F(TextureShapes, SampleLevelAndSampleWithOffsets) {
  // An offset moves the addressed texel by whole texels of the level read, before clamping.
  const char* source = R"(
#pragma fragment frag
Texture2D<float4> colors;
SamplerState point_sampler;
float4 frag(float2 uv : TEXCOORD0, float4 pos : SV_Position) : SV_Target {
  int2 p = int2(pos.xy);
  float2 st = (float2(p.x, p.y % 8) + 0.5) / 8.0;
  float4 level0 = colors.SampleLevel(point_sampler, st, 0, int2(-1, 2));
  float4 level1 = colors.SampleLevel(point_sampler, st, 1, int2(-1, 2));
  float4 sampled = colors.Sample(point_sampler, st, int2(2, -3));
  int mode = p.y / 8;
  return mode == 0 ? level0 : (mode == 1 ? level1 : sampled);
}
)";
  const auto clamped = [](int v, int size) { return uint32_t(std::clamp(v, 0, size - 1)); };
  check(source, 8, 24, {{"colors", {float_texture(TextureDimension::Tex2D, 8, 8, 1, 2)}}}, [&](uint32_t x, uint32_t y) {
    const int row = int(y % 8), column = int(x);
    switch (y / 8) {
      case 0: return texel_value(clamped(column - 1, 8), clamped(row + 2, 8), 0, 0);
      case 1: return texel_value(clamped(column / 2 - 1, 4), clamped(row / 2 + 2, 4), 0, 1);
      default: return texel_value(clamped(column + 2, 8), clamped(row - 3, 8), 0, 0);
    }
  });
}

TEST_F(TextureShapes, GatherReturnsTheFootprintInDirect3DOrder) {
  // Blocks of 7 columns: Gather, GatherRed, GatherGreen, GatherBlue, GatherAlpha, then the same
  // with an offset of (1, 2). Each gathers at the corner shared by texels (x, y) and (x+1, y+1),
  // where the footprint is unambiguous. Direct3D's order starts at the lower left texel and goes
  // counter-clockwise: (x, y+1), (x+1, y+1), (x+1, y), (x, y), rows growing downwards.
  const char* source = R"(
#pragma fragment frag
Texture2D<float4> colors;
SamplerState point_sampler;
float4 frag(float2 uv : TEXCOORD0, float4 pos : SV_Position) : SV_Target {
  int2 p = int2(pos.xy);
  int mode = p.x / 7;
  float2 corner = (float2(p.x % 7, p.y) + 1.0) / 8.0;
  float4 result = 0;
  if (mode == 0) result = colors.Gather(point_sampler, corner);
  else if (mode == 1) result = colors.GatherRed(point_sampler, corner);
  else if (mode == 2) result = colors.GatherGreen(point_sampler, corner);
  else if (mode == 3) result = colors.GatherBlue(point_sampler, corner);
  else if (mode == 4) result = colors.GatherAlpha(point_sampler, corner);
  else if (mode == 5) result = colors.Gather(point_sampler, corner, int2(1, 2));
  else if (mode == 6) result = colors.GatherRed(point_sampler, corner, int2(1, 2));
  else if (mode == 7) result = colors.GatherGreen(point_sampler, corner, int2(1, 2));
  else if (mode == 8) result = colors.GatherBlue(point_sampler, corner, int2(1, 2));
  else result = colors.GatherAlpha(point_sampler, corner, int2(1, 2));
  return result;
}
)";
  check(source, 70, 7, {{"colors", {float_texture(TextureDimension::Tex2D, 8, 8, 1, 1)}}}, [](uint32_t x, uint32_t y) {
    const uint32_t mode = x / 7;
    const int offset_x = mode >= 5 ? 1 : 0, offset_y = mode >= 5 ? 2 : 0;
    const int component = mode % 5 == 0 ? 0 : int(mode % 5) - 1;
    const auto fetch = [&](int i, int j) {
      return texel_value(uint32_t(std::clamp(i + offset_x, 0, 7)), uint32_t(std::clamp(j + offset_y, 0, 7)), 0,
                         0)[component];
    };
    const int i = int(x % 7), j = int(y);
    return glm::vec4(fetch(i, j + 1), fetch(i + 1, j + 1), fetch(i + 1, j), fetch(i, j));
  });
}

// ---- Comparison -------------------------------------------------------------------------------

// Columns in blocks of 4: the reference below, at and above the texel; rows in blocks of 4:
// SampleCmp, then SampleCmpLevelZero, on a 4 x 4 depth texture.
constexpr const char* kCompare2D = R"(
#pragma fragment frag
Texture2D<float> shadow;
SamplerComparisonState compare_sampler;
float4 frag(float2 uv : TEXCOORD0, float4 pos : SV_Position) : SV_Target {
  int2 p = int2(pos.xy);
  int2 texel = int2(p.x % 4, p.y % 4);
  float depth = (texel.y * 4 + texel.x + 0.5) / 16.0;
  float reference = depth + (p.x / 4 - 1) / 32.0;
  float2 st = (float2(texel) + 0.5) / 4.0;
  float sampled = shadow.SampleCmp(compare_sampler, st, reference);
  float level_zero = shadow.SampleCmpLevelZero(compare_sampler, st, reference);
  return float4(p.y < 4 ? sampled : level_zero, reference, 0, 1);
}
)";

float compare(harness::CompareOp op, float reference, float texel) {
  switch (op) {
    case harness::CompareOp::LessEqual: return reference <= texel ? 1.0f : 0.0f;
    case harness::CompareOp::Greater: return reference > texel ? 1.0f : 0.0f;
    default: return -1.0f;  // not used here
  }
}

TEST_F(TextureShapes, SampleCmpOnADepthTextureIsReferenceLessEqualTexel) {
  for (harness::CompareOp op : {harness::CompareOp::LessEqual, harness::CompareOp::Greater}) {
    SCOPED_TRACE(op == harness::CompareOp::LessEqual ? "less-equal" : "greater");
    harness::SamplerDesc sampler = kPoint;
    sampler.compare = op;
    check(kCompare2D, 12, 8, {{"shadow", {depth_texture(TextureDimension::Tex2D, 4, 1), sampler}}},
          [op](uint32_t x, uint32_t y) {
            const float texel = depth_value(x % 4, y % 4, 0, 4, 1);
            const float reference = texel + float(int(x / 4) - 1) / 32.0f;
            return glm::vec4(compare(op, reference, texel), reference, 0.0f, 1.0f);
          });
  }
}

TEST_F(TextureShapes, SampleCmpOnADepthCube) {
  // Columns in blocks of 8: the reference below, at and above the texel of the face the
  // direction selects; rows in blocks of 8: SampleCmp, then SampleCmpLevelZero.
  const std::string source = std::string(R"(
#pragma fragment frag
TextureCube<float> shadow;
SamplerComparisonState compare_sampler;
float texel_depth(float3 r) {
  float3 a = abs(r);
  int face; float sc; float tc; float ma;
  if (a.x >= a.y && a.x >= a.z) { face = r.x >= 0 ? 0 : 1; ma = a.x; sc = r.x >= 0 ? -r.z : r.z; tc = -r.y; }
  else if (a.y >= a.z) { face = r.y >= 0 ? 2 : 3; ma = a.y; sc = r.x; tc = r.y >= 0 ? r.z : -r.z; }
  else { face = r.z >= 0 ? 4 : 5; ma = a.z; sc = r.z >= 0 ? r.x : -r.x; tc = -r.y; }
  int x = sc > 0 ? 1 : 0;
  int y = tc > 0 ? 1 : 0;
  return ((face * 2 + y) * 2 + x + 0.5) / 24.0;
}
)") + kCubeDirection + R"(
float4 frag(float2 uv : TEXCOORD0, float4 pos : SV_Position) : SV_Target {
  int2 p = int2(pos.xy);
  float3 direction = cube_direction(int2(p.x % 8, p.y % 8));
  float reference = texel_depth(direction) + (p.x / 8 - 1) / 64.0;
  float sampled = shadow.SampleCmp(compare_sampler, direction, reference);
  float level_zero = shadow.SampleCmpLevelZero(compare_sampler, direction, reference);
  return float4(p.y < 8 ? sampled : level_zero, reference, 0, 1);
}
)";
  // The shader finds the reference with the same table as the host (to put it just below, at
  // or just above the texel); the comparison result is the GPU's own face selection.
  check(source, 24, 16, {{"shadow", {depth_texture(TextureDimension::Cube, 2, 6)}}}, [](uint32_t x, uint32_t y) {
    const CubeTexel t = cube_texel(cube_direction(x % 8, y % 8), 2);
    const float texel = depth_value(t.x, t.y, t.face, 2, 6);
    const float reference = texel + float(int(x / 8) - 1) / 64.0f;
    return glm::vec4(reference <= texel ? 1.0f : 0.0f, reference, 0.0f, 1.0f);
  });
}

TEST_F(TextureShapes, GatherCmpComparesTheFootprintInDirect3DOrder) {
  // Blocks of 3 columns: the reference is the depth of one texel of the footprint (lower left,
  // lower right, upper right, upper left), so that 1, 2, 3 or 4 of the four pass.
  const char* source = R"(
#pragma fragment frag
Texture2D<float> shadow;
SamplerComparisonState compare_sampler;
float4 frag(float2 uv : TEXCOORD0, float4 pos : SV_Position) : SV_Target {
  int2 p = int2(pos.xy);
  int2 texel = int2(p.x % 3, p.y);
  int mode = p.x / 3;
  int2 chosen = texel + int2(mode == 1 || mode == 2 ? 1 : 0, mode <= 1 ? 1 : 0);
  float reference = (chosen.y * 4 + chosen.x + 0.5) / 16.0;
  return shadow.GatherCmp(compare_sampler, (float2(texel) + 1.0) / 4.0, reference);
}
)";
  const TextureData depth = depth_texture(TextureDimension::Tex2D, 4, 1);
  const auto expected = [](uint32_t x, uint32_t y) {
    const uint32_t i = x % 3, j = y, mode = x / 3;
    const uint32_t ci = i + (mode == 1 || mode == 2 ? 1 : 0), cj = j + (mode <= 1 ? 1 : 0);
    const float reference = depth_value(ci, cj, 0, 4, 1);
    const auto passes = [&](uint32_t a, uint32_t b) { return reference <= depth_value(a, b, 0, 4, 1) ? 1.0f : 0.0f; };
    return glm::vec4(passes(i, j + 1), passes(i + 1, j + 1), passes(i + 1, j), passes(i, j));
  };
  for (Lane lane : harness::all_lanes()) {
    SCOPED_TRACE(harness::lane_name(lane));
    if (lane == Lane::VkHlsl) {
      // glslang 12.0.0's HLSL front end gives GatherCmp's OpImageDrefGather a Bias operand, which
      // only implicit-lod instructions may have: spirv-val rejects the module. Checked to still
      // fail, so that the lane comes back when glslang is fixed (docs/divergences.md).
      auto module = hlsl::compile_text("gather_cmp.hlsl", source, {});
      ASSERT_TRUE(module->ok());
      auto program = harness::program_for_lane(*module, lane);
      ASSERT_FALSE(program) << "glslang compiles GatherCmp now: check it on vk-hlsl like the other lanes";
      EXPECT_NE(program.error().to_string().find("Bias can only be used with ImplicitLod"), std::string::npos)
          << program.error().to_string();
      continue;
    }
    const harness::FloatImage image = run(lane, source, 12, 3, {{"shadow", {depth}}});
    ASSERT_EQ(image.width, 12u);
    for (uint32_t y = 0; y < 3; ++y)
      for (uint32_t x = 0; x < 12; ++x) EXPECT_EQ(image.at(x, y), expected(x, y)) << x << "," << y;
  }
}

// ---- Queries ----------------------------------------------------------------------------------

// Column i is shape i: its width, height, layers (or depth) and levels (or samples) at mip
// level `mip` + row (the shapes with levels) or of the whole texture.
constexpr const char* kDimensions = R"(
#pragma fragment frag
Texture1D<float4> t1;
Texture1DArray<float4> t1a;
Texture2D<float4> t2;
Texture2DArray<float4> t2a;
Texture3D<float4> t3;
TextureCube tc;
TextureCubeArray tca;
Texture2DMS<float4> tms;
Texture2DMSArray<float4> tmsa;
cbuffer Query { uint mip; };
float4 frag(float2 uv : TEXCOORD0, float4 pos : SV_Position) : SV_Target {
  int2 p = int2(pos.xy);
  uint level = mip + p.y;
  uint w = 0, h = 0, e = 0, l = 0;
  if (p.x == 0) { t1.GetDimensions(level, w, l); }
  else if (p.x == 1) { t1a.GetDimensions(level, w, e, l); }
  else if (p.x == 2) { t2.GetDimensions(level, w, h, l); }
  else if (p.x == 3) { t2a.GetDimensions(level, w, h, e, l); }
  else if (p.x == 4) { t3.GetDimensions(level, w, h, e, l); }
  else if (p.x == 5) { tc.GetDimensions(level, w, h, l); }
  else if (p.x == 6) { tca.GetDimensions(level, w, h, e, l); }
  else if (p.x == 7) { tms.GetDimensions(w, h, l); }
  else { tmsa.GetDimensions(w, h, e, l); }
  return float4(w, h, e, l);
}
)";

struct DimensionCase {
  std::string name;
  TextureData data;
  glm::vec4 level0, level1;
};
std::vector<DimensionCase> dimension_cases() {
  return {
      {"t1", float_texture(TextureDimension::Tex1D, 16, 1, 1, 3), {16, 0, 0, 3}, {8, 0, 0, 3}},
      {"t1a", float_texture(TextureDimension::Tex1DArray, 8, 1, 5, 2), {8, 0, 5, 2}, {4, 0, 5, 2}},
      {"t2", float_texture(TextureDimension::Tex2D, 16, 8, 1, 3), {16, 8, 0, 3}, {8, 4, 0, 3}},
      {"t2a", float_texture(TextureDimension::Tex2DArray, 8, 4, 3, 2), {8, 4, 3, 2}, {4, 2, 3, 2}},
      {"t3", float_texture(TextureDimension::Tex3D, 8, 4, 2, 2), {8, 4, 2, 2}, {4, 2, 1, 2}},
      {"tc", float_texture(TextureDimension::Cube, 4, 4, 6, 3), {4, 4, 0, 3}, {2, 2, 0, 3}},
      // A cube array's element count is its number of cubes.
      {"tca", float_texture(TextureDimension::CubeArray, 4, 4, 12, 2), {4, 4, 2, 2}, {2, 2, 2, 2}},
      {"tms", float_texture(TextureDimension::Tex2D, 4, 2, 1, 1, 4), {4, 2, 0, 4}, {4, 2, 0, 4}},
      {"tmsa", float_texture(TextureDimension::Tex2DArray, 4, 2, 3, 1, 4), {4, 2, 3, 4}, {4, 2, 3, 4}},
  };
}

std::vector<std::byte> query_buffer(uint32_t mip) {
  std::vector<std::byte> bytes(16);
  std::memcpy(bytes.data(), &mip, sizeof mip);
  return bytes;
}

TEST_F(TextureShapes, GetDimensionsOfEveryShape) {
  // Row 0 only, with a mip level the same for every pixel of the draw (see the next test for why).
  const std::vector<DimensionCase> cases = dimension_cases();
  std::map<std::string, Input> inputs;
  for (const DimensionCase& c : cases) inputs[c.name] = {c.data};
  for (uint32_t mip : {0u, 1u}) {
    SCOPED_TRACE("mip " + std::to_string(mip));
    check(kDimensions, 9, 1, inputs, [&](uint32_t x, uint32_t) { return mip == 0 ? cases[x].level0 : cases[x].level1; },
          0.0f, {{"Query", query_buffer(mip)}});
  }
}

TEST_F(TextureShapes, DivergenceASizeQueryWithAMipLevelThatVariesAcrossPixelsTakesOneLevelForAll) {
  // Mesa 22.3's llvmpipe and lavapipe (gallivm's size query) take the level of detail of a
  // textureSize / OpImageQuerySizeLod from the first pixel of each group the shader runs at
  // once (two rows of four), so rows 0 and 1, asking for levels 0 and 1 within one group, both
  // get level 0's size: wrong on every lane, the same way (GLSL and SPIR-V say each invocation's
  // own level). The test above keeps the level uniform. This one stays to say when a Mesa update
  // fixes it: then row 1 gets level 1's size, this fails, and the note in docs/divergences.md
  // can go.
  const std::vector<DimensionCase> cases = dimension_cases();
  std::map<std::string, Input> inputs;
  for (const DimensionCase& c : cases) inputs[c.name] = {c.data};
  for (Lane lane : harness::all_lanes()) {
    SCOPED_TRACE(harness::lane_name(lane));
    const harness::FloatImage image = run(lane, kDimensions, 9, 2, inputs, {{"Query", query_buffer(0)}});
    ASSERT_EQ(image.height, 2u);
    for (uint32_t x = 0; x < 7; ++x) {  // the shapes with levels
      EXPECT_EQ(image.at(x, 0), cases[x].level0) << cases[x].name;
      EXPECT_EQ(image.at(x, 1), cases[x].level0) << cases[x].name << ": level 1's size is " << cases[x].level1.x;
    }
  }
}

TEST_F(TextureShapes, CalculateLevelOfDetailFollowsTheCoordinateScale) {
  // Blocks of 8 rows scale uv by 1/4, 1/2, 1, 2, 4: on an 8 x 8 target a 16 x 16 texture is
  // minified by 2 texels per pixel at scale 1, so the level of detail is log2(2 * scale):
  // -1, 0, 1, 2, 3 unclamped and 0, 0, 1, 2, 3 clamped to the texture's 5 levels.
  const char* source = R"(
#pragma fragment frag
Texture2D<float4> colors;
SamplerState linear_sampler;
float4 frag(float2 uv : TEXCOORD0, float4 pos : SV_Position) : SV_Target {
  int2 p = int2(pos.xy);
  float scale = exp2(p.y / 8 - 2);
  float2 st = (float2(p.x, p.y % 8) + 0.5) / 8.0 * scale;
  return float4(colors.CalculateLevelOfDetail(linear_sampler, st),
                colors.CalculateLevelOfDetailUnclamped(linear_sampler, st), 0, 1);
}
)";
  const harness::SamplerDesc trilinear{Filter::Linear, harness::AddressMode::Repeat};
  // llvmpipe computes log2 of the derivative's length with a fast approximation; Vulkan asks a
  // level of detail to mipmapPrecisionBits (4 on lavapipe) only. 1/64 is four times finer than
  // that and far below the 1.0 between the levels each block expects.
  check(
      source, 8, 40, {{"colors", {float_texture(TextureDimension::Tex2D, 16, 16, 1, 5), trilinear}}},
      [](uint32_t, uint32_t y) {
        const float lod = float(int(y / 8) - 1);
        return glm::vec4(std::max(lod, 0.0f), lod, 0.0f, 1.0f);
      },
      1.0f / 64.0f);
}

TEST_F(TextureShapes, TwoTexturesReadThroughOneSamplerState) {
  // One SamplerState is one sampler binding on Vulkan, shared by both textures.
  const char* source = R"(
#pragma fragment frag
Texture2D<float4> first;
Texture2DArray<float4> second;
SamplerState shared_sampler;
float4 frag(float2 uv : TEXCOORD0, float4 pos : SV_Position) : SV_Target {
  float2 st = (floor(pos.xy) + 0.5) / 4.0;
  return first.Sample(shared_sampler, st) + second.SampleLevel(shared_sampler, float3(st, 1), 0) * 16;
}
)";
  check(source, 4, 4,
        {{"first", {float_texture(TextureDimension::Tex2D, 4, 4, 1, 1)}},
         {"second", {float_texture(TextureDimension::Tex2DArray, 4, 4, 2, 1)}}},
        [](uint32_t x, uint32_t y) { return texel_value(x, y, 0, 0) + texel_value(x, y, 1, 0) * 16.0f; });
}

TEST_F(TextureShapes, ATextureWhoseNameGlslReservesIsBoundByItsHlslName) {
  // `sample` and `flat` are GLSL keywords: the emitter renames the uniforms, the draw still binds
  // the HLSL names.
  const char* source = R"(
#pragma fragment frag
Texture2D<float4> sample;
SamplerState point_sampler;
sampler2D flat;
float4 frag(float2 uv : TEXCOORD0, float4 pos : SV_Position) : SV_Target {
  float2 st = (floor(pos.xy) + 0.5) / 4.0;
  return sample.Sample(point_sampler, st) + tex2D(flat, st) * 16;
}
)";
  check(source, 4, 4,
        {{"sample", {float_texture(TextureDimension::Tex2D, 4, 4, 1, 1)}},
         {"flat", {float_texture(TextureDimension::Tex2D, 4, 4, 1, 2)}}},
        [](uint32_t x, uint32_t y) { return texel_value(x, y, 0, 0) * 17.0f; });
}

// ---- What a draw refuses ----------------------------------------------------------------------

TEST_F(TextureShapes, ATextureOfAnotherShapeOrKindIsRefusedNamingBoth) {
  const char* cube_source = R"(
#pragma fragment frag
TextureCube environment;
SamplerState point_sampler;
float4 frag(float2 uv : TEXCOORD0) : SV_Target { return environment.SampleLevel(point_sampler, float3(uv, 1), 0); }
)";
  const char* uint_source = R"(
#pragma fragment frag
Texture2D<uint4> ids;
float4 frag(float2 uv : TEXCOORD0, float4 pos : SV_Position) : SV_Target { return float4(ids.Load(int3(pos.xy, 0))); }
)";
  const char* shadow_source = R"(
#pragma fragment frag
Texture2D<float> shadow;
SamplerComparisonState compare_sampler;
float4 frag(float2 uv : TEXCOORD0) : SV_Target { return shadow.SampleCmp(compare_sampler, uv, 0.5); }
)";
  struct Case {
    const char* source;
    const char* texture;
    TextureData bound;
    harness::SamplerDesc sampler;
    std::vector<std::string> message;
  };
  const std::vector<Case> cases = {
      {cube_source,
       "environment",
       float_texture(TextureDimension::Tex2D, 2, 2, 1, 1),
       kPoint,
       {"texture 'environment' is declared TextureCube", "texture 1 is a Texture2D"}},
      {uint_source,
       "ids",
       float_texture(TextureDimension::Tex2D, 2, 2, 1, 1),
       kPoint,
       {"texture 'ids' reads uint texels", "texture 1 is Rgba32Float (float texels)"}},
      {shadow_source,
       "shadow",
       float_texture(TextureDimension::Tex2D, 2, 2, 1, 1),
       kPoint,
       {"texture 'shadow' is read with a comparison sampler", "texture 1 is Rgba32Float"}},
  };
  for (Lane lane : harness::all_lanes()) {
    SCOPED_TRACE(harness::lane_name(lane));
    for (const Case& c : cases) {
      // A backend of its own per case, so that the bound texture is texture 1.
      auto fresh = harness::create_backend(lane, {.validation = harness::vulkan_validation_available()});
      ASSERT_TRUE(fresh) << fresh.error().to_string();
      auto module = hlsl::compile_text("refused.hlsl", c.source, {});
      ASSERT_TRUE(module->ok()) << c.source;
      auto texture = (*fresh)->upload_texture(c.bound);
      ASSERT_TRUE(texture) << texture.error().to_string();
      auto image = harness::evaluate(*module, lane, **fresh, 2, 2, {}, {},
                                     {{c.texture, harness::TextureSource::texture(*texture, c.sampler)}});
      ASSERT_FALSE(image) << c.texture << " was accepted";
      for (const std::string& part : c.message)
        EXPECT_NE(image.error().message.find(part), std::string::npos) << image.error().message;
      EXPECT_TRUE((*fresh)->take_driver_messages().empty()) << "the driver saw the draw";
    }
  }
}

}  // namespace
}  // namespace xshade::tests
