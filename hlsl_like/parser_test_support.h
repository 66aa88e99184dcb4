// What the parser tests share: source text through the real lexer into the parser (or its tokens
// alone), an expression's tree as one line, and a Unity-style shader to parse whole.
#pragma once

#include <deque>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "hlsl_like/parser.h"

namespace xshade::hlsl::parser_test {

// Source text through the real lexer into the parser; everything the tree points into lives here.
struct Parsed {
  SourceManager sources;
  DiagnosticEngine diagnostics{sources};
  std::deque<std::string> text_store;
  std::vector<Token> tokens;
  TranslationUnit unit;

  // "line:col: message" for each error, in order.
  std::vector<std::string> errors() const {
    std::vector<std::string> out;
    for (const Diagnostic& d : diagnostics.diagnostics())
      if (d.severity == Severity::Error)
        out.push_back(std::to_string(d.where.line) + ":" + std::to_string(d.where.column) + ": " + d.message);
    return out;
  }

  template <class T>
  const T& decl(size_t index) const {
    EXPECT_LT(index, unit.decls.size());
    return static_cast<const T&>(*unit.decls.at(index));
  }
  const FunctionDecl& function(std::string_view name) const {
    for (const auto& d : unit.decls)
      if (d->kind == DeclKind::Function && d->name == name && static_cast<const FunctionDecl&>(*d).body)
        return static_cast<const FunctionDecl&>(*d);
    throw std::runtime_error("no function " + std::string(name));
  }
  const VarDecl& var(std::string_view name) const {
    for (const auto& d : unit.decls)
      if (d->kind == DeclKind::Var && d->name == name) return static_cast<const VarDecl&>(*d);
    throw std::runtime_error("no variable " + std::string(name));
  }
};

// The tokens only, for a test that starts a Parser at one production.
std::unique_ptr<Parsed> lex_text(const std::string& text);
std::unique_ptr<Parsed> parse_text(const std::string& text);

// The tree of an expression as an S-expression, to pin shapes in one line.
std::string sexpr(const Expr& e);
// The trees of a list's expressions, each after a space.
template <class List>
std::string sexpr_list(const List& list) {
  std::string out;
  for (const ExprPtr& item : list) out += " " + sexpr(*item);
  return out;
}
// The expression of `float __e = EXPR;` inside a function whose locals a..z are declared.
std::string expr_tree(const std::string& expression);

inline constexpr const char* kUnityShader = R"(
// A Unity-style lit shader, preprocessed.
typedef half4 fixed4;

struct appdata {
  float4 vertex : POSITION;
  float3 normal : NORMAL;
  float2 uv : TEXCOORD0;
};

struct v2f {
  float4 pos : SV_POSITION;
  float2 uv : TEXCOORD0;
  float3 worldNormal : TEXCOORD1;
  nointerpolation int id : TEXCOORD2;
  float w[4];
};

cbuffer UnityPerMaterial : register(b0) {
  float4 _Color;
  row_major float4x4 _ObjectToWorld;
  float _Metallic <string UIName = "Metallic"; float UIMin = 0.0; float UIMax = 1.0;> = 0.5;
  float _Bias <float UIMin = -1.5; int Steps = -2;>;
};

Texture2D _MainTex : register(t0);
SamplerState sampler_MainTex : register(s0, space1);
Texture2D<float4> _ShadowTex;
sampler2D _RampTex;
uniform float4 _Tint;
static const float PI = 3.14159;

v2f vert(appdata v) {
  v2f o;
  o.pos = mul(_ObjectToWorld, v.vertex);
  o.uv = v.uv;
  o.worldNormal = normalize(mul((float3x3)_ObjectToWorld, v.normal));
  o.id = 0;
  [unroll] for (int k = 0; k < 4; ++k) o.w[k] = 0;
  return o;
}

fixed4 frag(v2f i) : SV_Target {
  float3 n = normalize(i.worldNormal);
  float nd = dot(n, float3(0, 1, 0)) * 0.5 + 0.5;
  fixed4 albedo = _MainTex.Sample(sampler_MainTex, i.uv) * _Color;
  albedo.rgb *= tex2D(_RampTex, float2(nd, 0.5)).rgb;
  if (albedo.a < 0.01) discard;
  return albedo * _Tint;
}
)";

}  // namespace xshade::hlsl::parser_test
