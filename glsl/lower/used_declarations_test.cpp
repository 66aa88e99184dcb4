#include "glsl/lower/used_declarations.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace xshade::glsl::lower {
namespace {

constexpr const char* kShader = R"(#pragma vertex vert
#pragma fragment frag
struct Light { float3 color; };
struct Unreached { int2x2 m; };
float twice(float x) { return 2 * x; }
static float gain = twice(0.5);
static float unused_static = 2;
float3 shade(Light light) { return light.color * gain; }
Unreached never(Unreached u) { return u; }
float4 vert(float4 p : POSITION) : SV_Position { return p; }
float4 frag() : SV_Target { Light l; l.color = 1; return float4(shade(l), 1); }
)";

std::vector<std::string> names_of(const auto& decls) {
  std::vector<std::string> names;
  for (const auto* decl : decls) names.push_back(decl->name);
  return names;
}

TEST(UsedDeclarations, WhatTheEntryPointReachesCalleesFirst) {
  auto module = hlsl::compile_text("used.hlsl", kShader, {});
  ASSERT_TRUE(module->ok()) << module->diagnostics.render_all();
  const UsedDeclarations fragment = used_declarations(*module, module->entry_points.fragment);
  // shade before frag, which calls it; twice, which only a static's initializer calls, after.
  EXPECT_EQ(names_of(fragment.functions), (std::vector<std::string>{"shade", "frag", "twice"}));
  EXPECT_EQ(names_of(fragment.statics), (std::vector<std::string>{"gain"}));
  EXPECT_EQ(names_of(fragment.structs), (std::vector<std::string>{"Light"}));  // not Unreached

  const UsedDeclarations vertex = used_declarations(*module, module->entry_points.vertex);
  EXPECT_EQ(names_of(vertex.functions), (std::vector<std::string>{"vert"}));
  EXPECT_TRUE(vertex.statics.empty());
  EXPECT_TRUE(vertex.structs.empty());
}

TEST(UsedDeclarations, NoEntryPointUsesNothing) {
  auto module = hlsl::compile_text("used.hlsl", kShader, {});
  ASSERT_TRUE(module->ok());
  const UsedDeclarations none = used_declarations(*module, nullptr);
  EXPECT_TRUE(none.functions.empty() && none.statics.empty() && none.structs.empty());
}

}  // namespace
}  // namespace xshade::glsl::lower
