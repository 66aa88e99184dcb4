// A Unity `.shader` file as ShaderLab reads it: the Properties, the SubShaders with their tags,
// LOD and render state, the Passes with theirs and their program blocks, the Fallback. This is
// what the file says, checked against what Unity's manual allows; what a pass compiles to and
// how it is drawn are for the layers above.
#pragma once

#include <array>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "base/diagnostic.h"

namespace xshade::shaderlab {

// Whether two words are the same to ShaderLab, which reads its keywords, values and attribute
// names ignoring case.
bool same_word(std::string_view a, std::string_view b);

// ---- Properties ----

enum class PropertyType {
  Float,
  Int,
  Integer,
  Range,
  Color,
  Vector,
  Texture2D,
  Texture2DArray,
  Texture3D,
  Cube,
  CubeArray,
  Any
};

// A property's attribute as written: [HDR], [Toggle(_FOO_ON)], [KeywordEnum(None, Add)], ...
struct PropertyAttribute {
  std::string name;
  std::vector<std::string> arguments;  // each trimmed; none for [HDR]
  SourceLocation where;
};

struct Property {
  std::string name;          // _MainTex
  std::string display_name;  // "Albedo"
  PropertyType type = PropertyType::Float;
  float range_min = 0.0f, range_max = 0.0f;  // Range(min, max)
  // The default: Float, Int, Integer and Range in value[0]; Color and Vector all four.
  std::array<float, 4> value{};
  // A texture's default: "white", "black", "gray", "grey", "bump", "red", "linearGray", "" ...
  std::string texture_default;
  std::vector<PropertyAttribute> attributes;
  SourceLocation where;

  bool is_texture() const { return type >= PropertyType::Texture2D && type <= PropertyType::Any; }
  const PropertyAttribute* attribute(std::string_view name) const;  // by name, ignoring case
};

// ---- Render state ----

// What a render state command takes: a word or a number as written (its canonical spelling for a
// word Unity knows: "LEqual" for "lequal"), or a property named in brackets whose value the
// material gives (`Cull [_Cull]`).
struct StateValue {
  std::string text;
  bool is_property = false;
  SourceLocation where;
};

struct BlendState {
  int target = -1;  // Blend N ...: one render target; -1 all
  bool off = false;
  StateValue source, destination;
  std::optional<StateValue> source_alpha, destination_alpha;  // Blend a b, c d
};

struct StencilState {
  // Ref, ReadMask, WriteMask, Comp, Pass, Fail, ZFail and their Front and Back forms, by their
  // canonical names.
  std::vector<std::pair<std::string, StateValue>> fields;
  const StateValue* field(std::string_view name) const;
};

// The state one block sets; what it does not set is what the block around it sets (a Pass's
// over its SubShader's over its Category's), and at the outermost Unity's defaults (Cull Back,
// ZWrite On, ZTest LEqual, Blend Off).
struct RenderState {
  std::optional<StateValue> cull, zwrite, ztest, color_mask, alpha_to_mask, zclip, conservative;
  std::optional<std::pair<StateValue, StateValue>> offset;                   // factor, units
  std::vector<BlendState> blend;                                             // in the order written
  std::optional<std::pair<StateValue, std::optional<StateValue>>> blend_op;  // colour, alpha
  std::optional<StencilState> stencil;

  // This state with what it leaves unset taken from `outer`.
  RenderState over(const RenderState& outer) const;
};

// ---- Programs and passes ----

enum class ProgramLanguage { Cg, Hlsl, Glsl };

// CGPROGRAM ... ENDCG and its kin: the text between the two words, and where it starts in the
// .shader file, so that a diagnostic inside it points into the file.
struct ProgramBlock {
  ProgramLanguage language = ProgramLanguage::Cg;
  bool include = false;  // CGINCLUDE / HLSLINCLUDE: given to every program of its scope
  std::string text;
  SourceLocation start;  // of text's first character
};

using Tags = std::vector<std::pair<std::string, std::string>>;
// A tag's value by its name, whose case Unity ignores as it does a ShaderLab keyword's (its own
// Legacy Shaders/VertexLit tags its lightmapped pass "LIGHTMODE", and Unity draws that pass only
// for lightmapped objects); empty when absent.
std::string tag(const Tags& tags, std::string_view name);

enum class PassKind {
  Program,        // a CGPROGRAM or HLSLPROGRAM
  FixedFunction,  // SetTexture, Material, Lighting ...: no program of its own
  Use,            // UsePass "Shader/NAME"
  Grab,           // GrabPass { "_Name" }
};

struct Pass {
  PassKind kind = PassKind::FixedFunction;
  std::string name;  // Name "ShadowCaster" (Unity matches it in upper case for UsePass)
  Tags tags;
  RenderState state;
  std::vector<ProgramBlock> includes;  // CGINCLUDE blocks written inside the pass
  std::optional<ProgramBlock> program;
  std::string used;                         // Use: "Shader/NAME"
  std::string grab_texture;                 // Grab: "_Name", empty for the default _GrabTexture
  std::vector<std::string> fixed_function;  // the fixed-function commands the pass holds
  // Generated from a surface program (surface_shader.h): its program holds the include blocks of
  // its scope itself, after the Unity includes the generated code needs.
  bool generated = false;
  SourceLocation where;
};

struct SubShader {
  Tags tags;
  int lod = 0;
  RenderState state;                   // its own over its Category's
  std::vector<ProgramBlock> includes;  // the shader's, its Category's and its own, in that order
  std::vector<Pass> passes;
  // A CGPROGRAM outside any Pass: a surface shader's program (#pragma surface), from which Unity
  // generates the passes.
  std::optional<ProgramBlock> surface;
  SourceLocation where;
};

struct Shader {
  std::string name;  // Shader "Unlit/Texture"
  std::vector<Property> properties;
  std::vector<SubShader> subshaders;
  std::optional<std::string> fallback;  // empty string: Fallback Off
  std::string custom_editor;
  std::vector<std::pair<std::string, std::string>> dependencies;  // Dependency "name" = "shader"
  // What the reader noticed and went on past: an attribute it does not know, a fixed-function
  // command. Each is a warning at its place in the file.
  std::vector<Diagnostic> notes;

  const Property* property(std::string_view name) const;
};

}  // namespace xshade::shaderlab
