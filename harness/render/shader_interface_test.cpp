#include "harness/render/shader_interface.h"

#include <cstring>
#include <map>

#include <gtest/gtest.h>

#include "hlsl_like/compiler.h"

namespace xshade::harness {
namespace {

ShaderInterface interface_of(const std::string& source) {
  auto module = hlsl::compile_text("s.hlsl", source, {});
  EXPECT_TRUE(module->ok()) << module->diagnostics.render_all();
  return shader_interface(module->reflection);
}

float float_at(const std::vector<std::byte>& bytes, size_t offset) {
  float value;
  std::memcpy(&value, bytes.data() + offset, 4);
  return value;
}

UniformLookup from(const std::map<std::string, std::vector<float>>& values) {
  return [&values](const std::string& name) -> const std::vector<float>* {
    auto it = values.find(name);
    return it == values.end() ? nullptr : &it->second;
  };
}

constexpr const char* kShader = R"(
#pragma fragment frag
cbuffer Frame : register(b0) {
  float4x4 _M;
  float3 _V;
  float _S;
  float4 _A[3];
  int _I;
};
float _Smoothness <float UIMin = 0.0; float UIMax = 1.0;> = 0.25;
Texture2D _MainTex;
SamplerState sampler_MainTex;
float4 frag(float2 uv : TEXCOORD0) : SV_Target {
  return mul(_M, float4(_V, _S)) + _A[2] * _I + _Smoothness * _MainTex.Sample(sampler_MainTex, uv);
}
)";

TEST(ShaderInterface, ListsBlocksMembersTexturesAndDefaults) {
  const ShaderInterface interface = interface_of(kShader);
  ASSERT_EQ(interface.uniform_blocks.size(), 2u);
  const UniformBlock& frame = interface.uniform_blocks[0];
  EXPECT_EQ(frame.name, "Frame");
  ASSERT_EQ(frame.members.size(), 5u);
  EXPECT_EQ(frame.members[0].rows, 4u);
  EXPECT_EQ(frame.members[0].cols, 4u);
  EXPECT_EQ(frame.members[3].array_length, 3u);
  EXPECT_EQ(frame.members[3].components(), 12u);
  EXPECT_EQ(frame.members[4].scalar, hlsl::ScalarType::Int);
  EXPECT_EQ(interface.uniform_blocks[1].name, hlsl::kGlobalsBufferName);
  EXPECT_EQ(interface.textures, std::vector<std::string>{"_MainTex"});
  const PropertyDefault* smoothness = interface.find_property("_Smoothness");
  ASSERT_NE(smoothness, nullptr);
  EXPECT_EQ(smoothness->value, std::vector<float>{0.25f});
}

TEST(ShaderInterface, BuildsHlslPackedBytes) {
  const ShaderInterface interface = interface_of(kShader);
  // HLSL M[r][c] = 10 r + c, given row by row.
  std::vector<float> m;
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c) m.push_back(float(10 * r + c));
  const std::map<std::string, std::vector<float>> values{
      {"_M", m}, {"_V", {1, 2, 3}}, {"_S", {4}}, {"_A", {0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11}}, {"_I", {-2}}};
  auto bytes = build_uniform_block(interface.uniform_blocks[0], from(values));
  ASSERT_TRUE(bytes) << bytes.error().to_string();
  // Column-major (HLSL's default): column c is the register at 16 c, row r at 4 r within it.
  EXPECT_EQ(float_at(*bytes, 16 * 2 + 4 * 1), 12.0f);  // M[1][2]
  EXPECT_EQ(float_at(*bytes, 16 * 0 + 4 * 3), 30.0f);  // M[3][0]
  // float3 at 64 and a float sharing its register at 76.
  EXPECT_EQ(float_at(*bytes, 64), 1.0f);
  EXPECT_EQ(float_at(*bytes, 76), 4.0f);
  // Array elements one register apart from 80.
  EXPECT_EQ(float_at(*bytes, 80 + 16 * 2 + 4 * 3), 11.0f);
  int32_t i;
  std::memcpy(&i, bytes->data() + 128, 4);
  EXPECT_EQ(i, -2);
}

TEST(ShaderInterface, AMissingOrMisshapenValueIsAnError) {
  const ShaderInterface interface = interface_of(kShader);
  const std::map<std::string, std::vector<float>> none;
  auto missing = build_uniform_block(interface.uniform_blocks[0], from(none));
  ASSERT_FALSE(missing);
  EXPECT_EQ(missing.error().message,
            "uniform '_M' in 'Frame' has no value: the renderer does not supply it, the scene does not set it and it "
            "has no default");
  const std::map<std::string, std::vector<float>> short_value{{"_Smoothness", {1, 2}}};
  auto wrong = build_uniform_block(interface.uniform_blocks[1], from(short_value));
  ASSERT_FALSE(wrong);
  EXPECT_EQ(wrong.error().message, "uniform '_Smoothness' in '$Globals' has 1 components; the value given has 2");
}

TEST(ShaderInterface, SurvivesJson) {
  const ShaderInterface interface = interface_of(kShader);
  auto back = parse_shader_interface_json(shader_interface_json(interface));
  ASSERT_TRUE(back) << back.error().to_string();
  EXPECT_EQ(shader_interface_json(*back), shader_interface_json(interface));
  EXPECT_EQ(back->uniform_blocks[0].members[4].scalar, hlsl::ScalarType::Int);
  EXPECT_FALSE(parse_shader_interface_json("{\"uniform_blocks\": 3}"));
}

}  // namespace
}  // namespace xshade::harness
