// The scene-shader contract: the names a scene gives a shader held against the shader's own,
// before anything is compiled for a lane or rendered. Every property, texture, keyword and post
// parameter a scene names must be one the material or effect declares, with the shape it
// declares; every uniform must get a value (from the renderer, the scene or the shader's
// default) and every texture a reached entry point samples an image (the scene's, the
// renderer's, a pass's input or the shader's declared default). A name that breaks it is an
// error at the scene's line, with the nearest name the shader has: a typo in a scene is never a
// silently ignored value that a bless then makes golden.
#pragma once

#include <map>
#include <string>
#include <vector>

#include "base/diagnostic.h"
#include "harness/render/shader_interface.h"
#include "harness/scene/scene.h"
#include "hlsl_like/pass_declarations.h"
#include "hlsl_like/reflection.h"

namespace xshade::harness {

// What one compiled variant of a shader offers a scene by name.
struct ShaderNames {
  struct Uniform {
    UniformMember member;
    std::string type;  // as HLSL spells it, for messages: "float4", "float4x4"
    bool has_default = false;
    bool read = true;  // by the variant's entry points: only a uniform they read needs a value
  };
  struct Texture {
    std::string name;
    bool sampled = false;         // read by the variant's entry points
    std::string default_texture;  // its declared Default, or empty
    bool comparison = false;      // read with a comparison sampler: a shadow map, which holds depth
  };
  std::string source;  // as the scene names it: "materials/toon.hlsl"
  std::vector<Uniform> uniforms;
  std::vector<Texture> textures;
  std::vector<StorageBufferInput> buffers;  // the read-only buffers the variant reads
  // [[vk::constant_id]] constants, which a scene sets by name like a property.
  std::vector<hlsl::SpecializationConstant> specialization_constants;
  std::vector<hlsl::KeywordSet> keyword_sets;
  // A .shader's numeric Properties that no uniform of the program holds, with their component
  // counts (1, or 4 for a Color or Vector): a material's values all the same (a [Toggle] that only
  // sets a keyword, a blend factor that only a render state in brackets reads).
  std::map<std::string, uint32_t> block_properties;

  const Uniform* uniform(const std::string& name) const;
  const Texture* texture(const std::string& name) const;
  const StorageBufferInput* buffer(const std::string& name) const;
  const hlsl::SpecializationConstant* specialization_constant(const std::string& name) const;
};

ShaderNames shader_names(const std::string& source, const hlsl::Reflection& reflection);

// The names of several variants an object is drawn with (a .shader's passes), as one: every
// uniform and texture any of them has, read or sampled where any reads it, with a default where
// any declares one; every keyword set.
ShaderNames merge_names(ShaderNames into, const ShaderNames& other);

// What checking found: each problem at the scene's line; and per checked use, the textures it
// samples from their declared defaults (which the renderer then binds) with a note for the plan.
struct ContractProblems {
  std::vector<Diagnostic> errors;
  std::vector<std::string> notes;  // "texture _ShadowTex: the shader's default \"white\""
};

// An object against its material's variant (the one its keywords select). Returns the textures
// the variant samples that the object gives no image and the shader declares a default for.
std::map<std::string, TextureRef> check_object(const SceneObject& object, const ShaderNames& material,
                                               ContractProblems& problems);

// One post pass of an effect: its declaration and its variant's names.
struct PassNames {
  hlsl::PassDeclaration declaration;
  ShaderNames names;
};

// An effect against its passes: each parameter and texture it gives must be one some pass has,
// each pass's uniforms get a value and its textures a source. Returns, per pass, the textures
// it samples from their declared defaults.
std::vector<std::map<std::string, TextureRef>> check_effect(const PostEffect& effect,
                                                            const std::vector<PassNames>& passes,
                                                            ContractProblems& problems);

// Every keyword a scene asks of `source` must be one its #pragma multi_compile or shader_feature
// lines declare.
void check_keywords(const std::vector<std::string>& keywords, const SceneLocations& where, const ShaderNames& source,
                    const std::string& owner, ContractProblems& problems);

}  // namespace xshade::harness
