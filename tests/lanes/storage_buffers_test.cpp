// Read-only buffers drawn on every lane: the bytes a caller gives (and those a seed makes, what
// `xshade eval --seed` feeds) read back as Direct3D lays a structured, raw and typed buffer out,
// against the host's own reading of the same bytes.
#include <cstring>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "harness/render/evaluate.h"
#include "harness/render/shader_interface.h"
#include "harness/render/synthetic_inputs.h"
#include "hlsl_like/compiler.h"
#include "tests/lanes/lane_fixture.h"

namespace xshade::tests {
namespace {

using harness::Lane;

// Row 0 reads a structured element (a float3, a float, a 2x2 matrix stored column by column,
// an int: 36 bytes), row 1 two words of the raw buffer and the structured buffer's dimensions,
// row 2 a typed element; column x reads element x. glslang reads a typed buffer as a texel
// buffer, which the harness does not bind: without TYPED, the vk-hlsl lane's source.
constexpr const char* kBuffersSource = R"(
#pragma fragment f
struct Item { float3 color; float weight; float2x2 m; int tag; };
StructuredBuffer<Item> items : register(t0);
ByteAddressBuffer raw : register(t1);
#ifdef TYPED
Buffer<float4> typed : register(t2);
#endif
float4 f(float4 pos : SV_Position) : SV_Target {
  uint i = uint(pos.x);
  if (pos.y < 1) {
    Item it = items[i];
    return float4(it.color * it.weight, it.m[1].x + float(it.tag));
  }
  if (pos.y < 2) {
    uint count, stride;
    items.GetDimensions(count, stride);
    return float4(asfloat(raw.Load2(8 * i)), float(count), float(stride));
  }
#ifdef TYPED
  return typed[i];
#else
  return float4(0, 0, 0, 0);
#endif
}
)";

// The source as `lane` draws it: with the typed buffer where the lane reads one.
std::unique_ptr<hlsl::Module> buffers_module(Lane lane) {
  hlsl::CompileOptions options;
  if (lane != Lane::VkHlsl) options.keywords = {"TYPED"};
  return hlsl::compile_text("buffers.hlsl", kBuffersSource, options);
}

constexpr uint32_t kItemWords = 9;
constexpr uint32_t kColumns = 5;

float word_float(const std::vector<std::byte>& bytes, size_t word) {
  if ((word + 1) * 4 > bytes.size()) return 0.0f;  // past the end reads 0
  float value = 0.0f;
  std::memcpy(&value, bytes.data() + word * 4, 4);
  return value;
}
int32_t word_int(const std::vector<std::byte>& bytes, size_t word) {
  if ((word + 1) * 4 > bytes.size()) return 0;
  int32_t value = 0;
  std::memcpy(&value, bytes.data() + word * 4, 4);
  return value;
}

// What the shader computes from the buffers' bytes, pixel (x, y), as the host reads them.
glm::vec4 expected_pixel(const std::vector<std::byte>& items, const std::vector<std::byte>& raw,
                         const std::vector<std::byte>& typed, uint32_t x, uint32_t y) {
  if (y == 0) {
    const size_t base = size_t(x) * kItemWords;
    const float weight = word_float(items, base + 3);
    // m[1].x is element (1, 0): in column 0, after element (0, 0).
    return {word_float(items, base + 0) * weight, word_float(items, base + 1) * weight,
            word_float(items, base + 2) * weight, word_float(items, base + 5) + float(word_int(items, base + 8))};
  }
  if (y == 1)
    return {word_float(raw, 2 * x), word_float(raw, 2 * x + 1), float(items.size() / (kItemWords * 4)),
            float(kItemWords * 4)};
  return {word_float(typed, 4 * x), word_float(typed, 4 * x + 1), word_float(typed, 4 * x + 2),
          word_float(typed, 4 * x + 3)};
}

std::vector<std::byte> float_words(const std::vector<float>& values) {
  std::vector<std::byte> bytes(values.size() * 4);
  std::memcpy(bytes.data(), values.data(), bytes.size());
  return bytes;
}

// Every pixel on gl and vk. glslang lays a structured buffer's element out by std430 (a float3
// aligned to 16 bytes: Item is 48 bytes there, as DXC lays it out without -fvk-use-dx-layout;
// docs/divergences.md), so vk-hlsl agrees on the raw buffer's words alone.
void expect_image(const harness::FloatImage& image, Lane lane, const std::vector<std::byte>& items,
                  const std::vector<std::byte>& raw, const std::vector<std::byte>& typed) {
  for (uint32_t y = 0; y < 3; ++y)
    for (uint32_t x = 0; x < kColumns; ++x) {
      const glm::vec4 want = expected_pixel(items, raw, typed, x, y);
      const glm::vec4 got = image.at(x, y);
      const int channels = lane != Lane::VkHlsl ? 4 : y == 1 ? 2 : 0;
      for (int c = 0; c < channels; ++c)
        EXPECT_FLOAT_EQ(got[c], want[c]) << "pixel " << x << "," << y << " channel " << c;
    }
}

class StorageBuffersDraw : public LaneTest {};

TEST_F(StorageBuffersDraw, GivenBytesReadAsDirect3DLaysThemOutAndPastTheEndReadsZero) {
  // Four items: column 4 reads past the end. Every word distinct, so a wrong offset shows.
  std::vector<float> item_values;
  for (uint32_t i = 0; i < 4 * kItemWords; ++i) item_values.push_back(0.25f + float(i));
  std::vector<std::byte> items = float_words(item_values);
  for (uint32_t i = 0; i < 4; ++i) {  // each tag an int
    const int32_t tag = int32_t(10 * i + 1);
    std::memcpy(items.data() + (i * kItemWords + 8) * 4, &tag, 4);
  }
  const std::vector<std::byte> raw = float_words({1, 2, 3, 4, 5, 6, 7});  // Load2 at 24 reads word 6, then past the end
  const std::vector<std::byte> typed = float_words({0.5f, 1.5f, 2.5f, 3.5f, 4.5f, 5.5f, 6.5f, 7.5f});
  for (Lane lane : harness::all_lanes()) {
    SCOPED_TRACE(harness::lane_name(lane));
    auto module = buffers_module(lane);
    ASSERT_TRUE(module->ok());
    std::map<std::string, std::vector<std::byte>> given = {{"items", items}, {"raw", raw}};
    if (lane != Lane::VkHlsl) given["typed"] = typed;
    auto image = harness::evaluate(*module, lane, backend(lane), kColumns, 3, {}, {}, {}, given);
    ASSERT_TRUE(image) << image.error().to_string();
    expect_image(*image, lane, items, raw, typed);
    // The divergence docs/divergences.md lists, still there: glslang reads element 1 from byte 48.
    if (lane == Lane::VkHlsl) {
      EXPECT_NE(image->at(1, 0).x, expected_pixel(items, raw, typed, 1, 0).x);
    }
  }
}

TEST_F(StorageBuffersDraw, SeededBuffersReadAsTheHostReadsTheSeedsBytes) {
  constexpr uint32_t kSeed = 7;
  for (Lane lane : harness::all_lanes()) {
    SCOPED_TRACE(harness::lane_name(lane));
    auto module = buffers_module(lane);
    ASSERT_TRUE(module->ok());
    std::map<std::string, std::vector<std::byte>> seeded = {{"typed", {}}};
    for (const harness::StorageBufferInput& buffer : harness::shader_interface(module->reflection).storage_buffers)
      seeded[buffer.name] = harness::seeded_storage_buffer(buffer, kSeed);
    auto program = harness::FullscreenProgram::create(*module, lane, backend(lane));
    ASSERT_TRUE(program) << program.error().to_string();
    auto image = program->run_seeded(backend(lane), kColumns, 3, kSeed);
    (void)backend(lane).destroy(program->handle());
    ASSERT_TRUE(image) << image.error().to_string();
    expect_image(*image, lane, seeded.at("items"), seeded.at("raw"), seeded.at("typed"));
  }
}

TEST_F(StorageBuffersDraw, ABufferTheShaderReadsMustBeGiven) {
  auto module = buffers_module(Lane::Gl);
  ASSERT_TRUE(module->ok());
  auto image = harness::evaluate(*module, Lane::Gl, backend(Lane::Gl), 1, 1);
  ASSERT_FALSE(image);
  EXPECT_NE(image.error().message.find("'items', which has no default"), std::string::npos) << image.error().message;
}

TEST_F(StorageBuffersDraw, TheVkHlslLaneRefusesATypedBufferByName) {
  auto module = buffers_module(Lane::Gl);  // with the typed buffer
  ASSERT_TRUE(module->ok());
  auto image = harness::evaluate(*module, Lane::VkHlsl, backend(Lane::VkHlsl), 1, 1);
  ASSERT_FALSE(image);
  EXPECT_NE(image.error().message.find("'typed' is a Buffer<T>"), std::string::npos) << image.error().message;
}

}  // namespace
}  // namespace xshade::tests
