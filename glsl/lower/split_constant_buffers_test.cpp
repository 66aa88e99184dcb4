#include "glsl/lower/split_constant_buffers.h"

#include <gtest/gtest.h>

namespace xshade::glsl::lower {
namespace {

TEST(SplitConstantBuffers, AVectorStd140CannotPlaceIsReadAsScalars) {
  // HLSL puts b at offset 4, in a's register; std140 would align a vec2 to 8.
  auto module = hlsl::compile_text("packing.hlsl", R"(#pragma fragment frag
cbuffer Params {
  float a;
  float2 b;
  float4 c;
};
int _Loose;
float4 frag() : SV_Target { return float4(a, b, c.x + _Loose); }
)",
                                   {});
  ASSERT_TRUE(module->ok()) << module->diagnostics.render_all();
  const ConstantBufferMembers members = split_constant_buffers(*module);
  for (const char* name : {"a", "b", "c", "_Loose"}) EXPECT_TRUE(members.by_name.count(name)) << name;
  ASSERT_EQ(members.split.size(), 1u);
  const auto& [decl, split] = *members.split.begin();
  EXPECT_EQ(decl, members.by_name.at("b"));
  EXPECT_EQ(split.scalar, hlsl::ScalarType::Float);
  EXPECT_EQ(split.count, 2u);
}

TEST(SplitConstantBuffers, VectorsInPlaceStayVectors) {
  auto module = hlsl::compile_text("aligned.hlsl", R"(#pragma fragment frag
float2 a;
float2 b;
float3 c;
float d;
float4 frag() : SV_Target { return float4(a + b, c.x, d); }
)",
                                   {});
  ASSERT_TRUE(module->ok()) << module->diagnostics.render_all();
  EXPECT_TRUE(split_constant_buffers(*module).split.empty());
}

}  // namespace
}  // namespace xshade::glsl::lower
