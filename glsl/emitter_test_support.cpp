#include "glsl/emitter_test_support.h"

#include <gtest/gtest.h>

#include <sstream>

namespace xshade::glsl::emitter_test {

std::string diagnostics_of(const hlsl::Module& module) {
  std::string text;
  for (const Diagnostic& d : module.diagnostics.diagnostics()) text += d.to_string() + "\n";
  return text;
}

Result<EmittedProgram> try_emit(const std::string& source, Flavour flavour) {
  auto module = hlsl::compile_text("test.hlsl", source, {});
  if (!module->ok()) {
    ADD_FAILURE() << "the front end rejected the source:\n" << diagnostics_of(*module);
    return fail(ErrorKind::UserInput, "front end");
  }
  return emit(*module, {flavour});
}

EmittedProgram emit_ok(const std::string& source, Flavour flavour) {
  auto program = try_emit(source, flavour);
  if (!program) {
    ADD_FAILURE() << program.error().to_string();
    return {};
  }
  return *program;
}

std::string fragment_source(const std::string& globals, const std::string& body) {
  return "#pragma fragment frag\n" + globals + "\nfloat4 frag(float2 uv : TEXCOORD0) : SV_Target {\n" + body + "\n}\n";
}

std::string fragment(const std::string& globals, const std::string& body, Flavour flavour) {
  EmittedProgram program = emit_ok(fragment_source(globals, body), flavour);
  return program.fragment ? program.fragment->text : "";
}

std::string emit_error(const std::string& source, Flavour flavour) {
  auto program = try_emit(source, flavour);
  if (program) {
    ADD_FAILURE() << "expected an error";
    return "";
  }
  return program.error().to_string();
}

std::string without_line_directives(const std::string& text) {
  std::string result;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);)
    if (line.rfind("#line ", 0) != 0) result += line + "\n";
  return result;
}

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

const char* const kVertexAndFragment = R"(#pragma vertex vert
#pragma fragment frag
struct appdata {
  float4 vertex : POSITION;
  float2 uv : TEXCOORD0;
};
struct v2f {
  float4 pos : SV_Position;
  float2 uv : TEXCOORD0;
  nointerpolation int id : TEXCOORD1;
  centroid float3 n : NORMAL;
};
float4x4 _MVP;
v2f vert(appdata v, uint vid : SV_VertexID) {
  v2f o;
  o.pos = mul(_MVP, v.vertex);
  o.uv = v.uv;
  o.id = int(vid);
  o.n = v.vertex.xyz;
  return o;
}
float4 frag(v2f i) : SV_Target {
  return float4(i.uv, i.n.x, i.pos.w);
}
)";

}  // namespace xshade::glsl::emitter_test
