// Surface shaders: a SubShader's CGPROGRAM outside any Pass with `#pragma surface surfFunc
// lightModel [options]`, from which Unity generates the passes. xshade generates them as Unity's
// manual documents them and as the Editor's "Show generated code" shows them (docs/unity.md,
// "Surface shaders"): a ForwardBase pass, a ForwardAdd pass unless `noforwardadd`, a ShadowCaster
// with `addshadow`; each a vertex and fragment program that fills the author's Input struct, calls
// the surface function and then the lighting model's function, with the author's text behind a
// `#line` to where it is in the .shader file.
//
// What the generated code needs to know of the author's program (the Input struct's fields, the
// output struct, which form the lighting function has, whether the surface function writes a
// normal) comes from the front end (SurfaceProgramShape); this file reads the pragma and writes
// the text.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "base/result.h"
#include "shaderlab/shader.h"

namespace xshade::shaderlab {

// `#pragma surface surf Lambert alpha:fade vertex:vert`, read.
struct SurfaceDirective {
  std::string function;        // surf
  std::string lighting_model;  // Lambert: the function Lighting<model>
  // The options as written, `name` or `name:value`, in order.
  std::vector<std::pair<std::string, std::string>> options;
  SourceLocation where;  // of the pragma

  bool has(std::string_view option) const;
  // The value of `option:value`; empty when absent or without a value.
  std::string value(std::string_view option) const;
};

// The `#pragma surface` of a surface program; an error at its line when it has no function or
// model, names an option Unity does not have, or asks for what xshade does not generate
// (`tessellate:`, a geometry stage).
Result<SurfaceDirective> read_surface_directive(const ProgramBlock& program);

// A field of a struct of the author's program, as the front end read it.
struct SurfaceField {
  std::string type;      // float2, fixed4, ...
  std::string name;      // uv_MainTex
  std::string semantic;  // COLOR, VFACE or empty
};

// The lighting function's form, of those Unity's manual lists for Lighting<Name>.
enum class LightingForm {
  Gi,          // half4 Lighting<Name>(SurfaceOutput s, UnityGI gi), with Lighting<Name>_GI
  ViewGi,      // half4 Lighting<Name>(SurfaceOutput s, half3 viewDir, UnityGI gi), with _GI
  Legacy,      // half4 Lighting<Name>(SurfaceOutput s, half3 lightDir, half atten)
  LegacyView,  // half4 Lighting<Name>(SurfaceOutput s, half3 lightDir, half3 viewDir, half atten)
};

// What the generated code needs to know of the author's program.
struct SurfaceProgramShape {
  std::vector<SurfaceField> input;         // struct Input
  std::string output_type;                 // the surface function's second parameter's type
  std::vector<std::string> output_fields;  // its fields' names
  LightingForm lighting = LightingForm::Gi;
  bool writes_normal = false;  // the surface function writes o.Normal (tangent space)
  // vertex:func: the type its first parameter takes (appdata_full) with its fields' names, and
  // whether it has a second, `out Input`, parameter that fills Input's own fields.
  std::string vertex_input_type = "appdata_full";
  std::vector<std::string> vertex_input_fields;
  bool vertex_fills_input = false;
  std::vector<std::string> globals;  // names declared at file scope (an alphatest property)
};

// The passes Unity generates in `forward` (ForwardBase, ForwardAdd unless noforwardadd;
// ShadowCaster with addshadow), their programs CGPROGRAMs made of `includes` (the CGINCLUDE blocks
// in scope, in order), the surface program and the generated code. `shape` is the front end's
// reading of the program with those includes (surface_program_for_analysis).
std::vector<Pass> generate_surface_passes(const ProgramBlock& surface, const std::vector<ProgramBlock>& includes,
                                          const SurfaceDirective& directive, const SurfaceProgramShape& shape);

// The text the front end reads to learn a surface program's shape: Unity's includes that the
// generated code has (UnityCG, Lighting, UnityPBSLighting, AutoLight), the CGINCLUDE blocks and
// the program, with the generated code's macros (INTERNAL_DATA, WorldNormalVector) defined.
std::string surface_program_for_analysis(const ProgramBlock& surface, const std::vector<ProgramBlock>& includes);

}  // namespace xshade::shaderlab
