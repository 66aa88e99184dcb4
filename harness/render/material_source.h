// The source a scene names as a material or a post effect, through the front end. An .hlsl file
// compiles as it is. A Unity .shader compiles as Unity compiles the pass it draws: the pass's text
// composed as Unity composes it (shaderlab/pass_program.h), in Unity's compile environment
// (shaderlab/compile_environment.h), with the .shader's folder first among the include folders;
// its Properties then give the defaults of the uniforms and textures the program declares, so that
// nothing is written twice.
#pragma once

#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "base/result.h"
#include "hlsl_like/compiler.h"
#include "shaderlab/material_keywords.h"
#include "shaderlab/pass_program.h"
#include "shaderlab/shader.h"

namespace xshade::harness {

bool is_unity_shader(const std::filesystem::path& path);

// The LightModes of the passes Unity's forward renderer draws once for every object: none
// ("Always") and ForwardBase, each pass of the drawn SubShader in its order. ForwardAdd is drawn
// once for each further light (SourceModule::additive_passes); ShadowCaster (a shadow map), Meta,
// Deferred and the rest are for what a scene does not have.
bool forward_renderer_draws(const shaderlab::Pass& pass);

struct SourceModule {
  std::unique_ptr<hlsl::Module> module;
  // What the plan says of the source: the passes of a .shader it leaves out, and why.
  std::vector<std::string> notes;
  // A .shader's: the passes the forward renderer draws (indices in the drawn SubShader, in
  // order) and the one compiled here.
  std::vector<size_t> drawn_passes;
  size_t pass = 0;
  // A .shader's ForwardAdd passes, which the forward renderer draws again for each light besides
  // the main one (forward_lights.h).
  std::vector<size_t> additive_passes;
  // A .shader's ShadowCaster pass: its drawn SubShader's, else its Fallback chain's first (an index
  // past the SubShader's passes then), which a shadow-casting light draws into its shadow map.
  std::optional<size_t> caster_pass;
  // A .shader's: the compiled pass's render state (its own over its SubShader's), its SubShader's
  // Queue tag, and its Properties (their defaults as written are what a state in brackets reads;
  // their attributes set keywords).
  std::optional<shaderlab::RenderState> render_state;
  std::string queue;
  std::vector<shaderlab::Property> properties;
};

// The module of `path` with `options` (its keywords, its fragment entry, its defines); of a
// .shader, compiled for the Unity `platform`, the pass `pass` of its drawn SubShader (by index),
// or the first pass drawn. A .shader
// that cannot be read, has no pass to draw or whose CGPROGRAM finds no Unity include files is an
// error at its place in the file; a program that does not compile is a module with errors, as for
// an .hlsl file.
Result<SourceModule> compile_source(const std::filesystem::path& path, hlsl::CompileOptions options,
                                    std::optional<size_t> pass = std::nullopt,
                                    shaderlab::UnityPlatform platform = shaderlab::UnityPlatform::GLCore);

// The options a pass's program of the .shader `file` compiles with: `options` with the .shader's
// folder first among the include folders and Unity's defines before the caller's (a define the
// caller gives, -D UNITY_VERSION=..., stands instead of Unity's). A CGPROGRAM whose implicit
// includes no folder holds is an error at the program's line that says where to get them.
Result<hlsl::CompileOptions> pass_compile_options(const std::filesystem::path& file,
                                                  const shaderlab::PassProgram& program, hlsl::CompileOptions options,
                                                  shaderlab::UnityPlatform platform = shaderlab::UnityPlatform::GLCore);

// The defaults a .shader's Properties give the uniforms and textures of `reflection` that declare
// none: Float, Int, Integer and Range as they are written; Color converted from sRGB to linear as
// Unity's Linear colour space passes it to a shader (alpha as it is), and so a Float or Vector
// marked [Gamma]; a texture's "white", "black", "gray", "bump", "red" or "" as Unity's built-in
// textures of those names (the scene built-ins "white", "clear", "gray", "normal", "red", and
// "gray" for "" or a name Unity does not know). A uniform an entry point reads that neither the
// Properties block nor the renderer gives reads 0, as in Unity until a script sets it; each such
// uniform adds a line to `notes`.
void apply_properties(const shaderlab::Shader& shader, hlsl::Reflection& reflection, std::vector<std::string>& notes);

// The keywords asked of a .shader material (a scene's, or -D's), with those its [Toggle] and
// [KeywordEnum] properties set as Unity's material inspector does (shaderlab/material_keywords.h)
// from `value`, each only where one of the pass's keyword `sets` declares it and none of that set
// was asked: the variant `xshade run` draws and `xshade compile` shows.
std::vector<std::string> with_inspector_keywords(const std::vector<shaderlab::Property>& properties,
                                                 const std::vector<hlsl::KeywordSet>& sets,
                                                 std::vector<std::string> asked, const shaderlab::PropertyValue& value);

}  // namespace xshade::harness
