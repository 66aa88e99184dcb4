// The tracing variant's text and its table of sites (emit_trace.cpp); what it records on the
// drivers is tested in tests/lanes/nonfinite_trace_test.cpp.
#include <gtest/gtest.h>

#include <sstream>
#include <string>

#include "glsl/glsl_emitter.h"

namespace xshade::glsl {
namespace {

constexpr const char* kShader = R"(#pragma fragment frag
float _Scale = 2.0;
float ratio(float a, float b) {
  return a / b;
}
float4 frag(float2 uv : TEXCOORD0) : SV_Target {
  float x = uv.x * _Scale;
  x += ratio(uv.y, x);
  float3 n = normalize(float3(uv, x));
  return float4(n, 1.0);
}
)";

EmittedProgram emit_shader(bool traced) {
  auto module = hlsl::compile_text("trace.hlsl", kShader, {});
  EXPECT_TRUE(module->ok()) << module->diagnostics.render_all();
  auto program = emit(*module, {.flavour = Flavour::Vk, .trace_nonfinite = traced});
  EXPECT_TRUE(program) << program.error().to_string();
  return program ? *program : EmittedProgram{};
}

TEST(TraceVariant, HoldsThePlainFunctionsAsTheUntracedVariantWritesThem) {
  const std::string plain = emit_shader(false).fragment->text;
  const std::string traced = emit_shader(true).fragment->text;
  EXPECT_EQ(plain.find("xs_trace"), std::string::npos);
  // Every line of the untraced functions is in the traced stage as it is: the plain copy that
  // makes the colour.
  const size_t first = plain.find("float ratio(");
  const size_t main = plain.find("void main()");
  ASSERT_NE(first, std::string::npos);
  std::istringstream functions(plain.substr(first, main - first));
  for (std::string line; std::getline(functions, line);)
    if (!line.empty() && line[0] != '#') {
      EXPECT_NE(traced.find(line), std::string::npos) << line;
    }
  EXPECT_NE(traced.find("float xs_traced_ratio(float a, float b, uint xs_path)"), std::string::npos);
  EXPECT_NE(traced.find("layout(location = 1) out vec4 xs_trace_record;"), std::string::npos);
  // The plain copy's colour is written before the traced copy runs.
  EXPECT_LT(traced.find("xs_target0 = xs_result;"), traced.find("= xs_traced_frag("));
}

TEST(TraceVariant, NamesEverySiteWithItsKindLineAndFunction) {
  const NonfiniteTrace trace = emit_shader(true).trace;
  auto find = [&](TraceSite::Kind kind, uint32_t line) {
    for (const TraceSite& site : trace.sites)
      if (site.kind == kind && site.line == line) return &site;
    return static_cast<const TraceSite*>(nullptr);
  };
  const TraceSite* returned = find(TraceSite::Kind::Return, 4);
  ASSERT_NE(returned, nullptr);
  EXPECT_EQ(returned->function, "ratio");
  EXPECT_EQ(returned->source_line, "  return a / b;");
  EXPECT_EQ(describe_site(*returned), "the value ratio returns");
  const TraceSite* initialised = find(TraceSite::Kind::Initialization, 7);
  ASSERT_NE(initialised, nullptr);
  EXPECT_EQ(initialised->what, "x");
  ASSERT_NE(find(TraceSite::Kind::CompoundAssignment, 8), nullptr);
  const TraceSite* call = find(TraceSite::Kind::Call, 9);
  ASSERT_NE(call, nullptr);
  EXPECT_EQ(call->what, "normalize");
  EXPECT_NE(find(TraceSite::Kind::Input, 6), nullptr);
  EXPECT_NE(find(TraceSite::Kind::Output, 6), nullptr);
  EXPECT_NE(find(TraceSite::Kind::NegativeOutput, 6), nullptr);
  // A user function's call is not a site (its return is), but it is a call the path names.
  ASSERT_EQ(trace.calls.size(), 1u);
  EXPECT_EQ(trace.calls[0].callee, "ratio");
  EXPECT_EQ(trace.calls[0].caller, "frag");
  EXPECT_EQ(trace.calls[0].line, 8u);
}

TEST(TraceVariant, AShaderThatWritesSvTarget1CannotBeTraced) {
  auto module = hlsl::compile_text("two.hlsl",
                                   "#pragma fragment frag\n"
                                   "struct O { float4 a : SV_Target0; float4 b : SV_Target1; };\n"
                                   "O frag(float2 uv : TEXCOORD0) { O o; o.a = uv.xyxy; o.b = uv.yxyx; return o; }\n",
                                   {});
  ASSERT_TRUE(module->ok()) << module->diagnostics.render_all();
  auto program = emit(*module, {.flavour = Flavour::Gl, .trace_nonfinite = true});
  ASSERT_FALSE(program);
  EXPECT_NE(program.error().message.find("location 1"), std::string::npos) << program.error().message;
}

}  // namespace
}  // namespace xshade::glsl
