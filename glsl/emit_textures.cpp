// Textures in GLSL: the types of each texture shape per flavour (gl combines texture and sampler,
// vk keeps them apart; a texture compared on gl is a shadow sampler), and every texture method
// and DX9 tex* function as a template for StageEmitter::expand_template.
#include "glsl/stage_emitter.h"
#include "hlsl_like/ast_walk.h"

namespace xshade::glsl::detail {

using namespace hlsl;

namespace {

using I = IntrinsicId;

std::string dimension(TextureShape shape) {
  switch (shape) {
    case TextureShape::Tex1D: return "1D";
    case TextureShape::Tex1DArray: return "1DArray";
    case TextureShape::Tex2D: return "2D";
    case TextureShape::Tex2DArray: return "2DArray";
    case TextureShape::Tex2DMS: return "2DMS";
    case TextureShape::Tex2DMSArray: return "2DMSArray";
    case TextureShape::Tex3D: return "3D";
    case TextureShape::Cube: return "Cube";
    case TextureShape::CubeArray: return "CubeArray";
    case TextureShape::Subpass: return "2D";  // gl reads the attachment as a texture at the pixel
    case TextureShape::SubpassMS: return "2DMS";
  }
  return "2D";
}

// GLSL's prefix for the sampled type: isampler2D reads ints, usampler2D uints.
std::string texel_prefix(ScalarType texel) {
  if (texel == ScalarType::Int) return "i";
  if (texel == ScalarType::Uint || texel == ScalarType::Bool) return "u";
  return "";
}

std::string combined_type(TextureShape shape, ScalarType texel, bool shadow) {
  return texel_prefix(texel) + "sampler" + dimension(shape) + (shadow ? "Shadow" : "");
}

// ".x", ".xy", ".xyz" for the first n components; "" for 4.
std::string first_components(uint32_t n) { return n >= 4 ? "" : "." + std::string(kComponents, n); }

// The shadow lookup's coordinate: the reference value goes after the coordinate (a 1D one
// takes an unused second component first).
std::string shadow_coordinate(TextureShape shape) {
  switch (shape) {
    case TextureShape::Tex1D: return "vec3($2, 0.0, $3)";
    case TextureShape::Tex1DArray:
    case TextureShape::Tex2D: return "vec3($2, $3)";
    default: return "vec4($2, $3)";
  }
}

// A 2D comparison read (coordinate $2, reference $3, constant offset operand `offset` if not 0)
// as a linear comparison sampler filters it, in the shader (EmitOptions::filter_comparisons):
// the 2x2 texels a bilinear read weights, compared by one textureGather at their shared corner,
// then weighted by xs_compare_bilinear. Level 0, which is all a shadow map has; SampleCmp's
// derivatives do not choose a level here.
std::string bilinear_comparison(const std::string& sampler, size_t offset) {
  const std::string size = "vec2(textureSize(" + sampler + ", 0))";
  const std::string coordinate = offset ? "($2 + vec2($" + std::to_string(offset) + ") / " + size + ")" : "$2";
  const std::string texel = coordinate + " * " + size;
  return "xs_compare_bilinear(textureGather(" + sampler + ", (floor(" + texel + " - 0.5) + 1.0) / " + size + ", $3), " +
         texel + ")";
}

}  // namespace

std::string StageEmitter::resource_type(const Type& type, const Decl* decl, Loc loc) {
  switch (type.kind()) {
    case TypeKind::Texture: {
      const ScalarType texel = type.scalar_type() == ScalarType::Half ? ScalarType::Float : type.scalar_type();
      const TextureShape shape = type.texture_shape();
      if (flavour_ == Flavour::Vk && (shape == TextureShape::Subpass || shape == TextureShape::SubpassMS))
        return texel_prefix(texel) + (shape == TextureShape::Subpass ? "subpassInput" : "subpassInputMS");
      if (flavour_ == Flavour::Vk) return texel_prefix(texel) + "texture" + dimension(shape);
      return combined_type(type.texture_shape(), texel, decl && compared_.count(decl) > 0);
    }
    case TypeKind::Sampler: return combined_type(type.texture_shape(), ScalarType::Float, false);
    case TypeKind::SamplerState:
      if (flavour_ == Flavour::Gl) fail(loc, "a SamplerState has no GLSL type on OpenGL");
      return type.is_comparison() ? "samplerShadow" : "sampler";
    default: return type_name(type, loc);
  }
}

void StageEmitter::check_struct_of_resources(const Type& type, Loc loc) {
  if (std::optional<std::string> message = lower::mixed_struct_message(type)) fail(loc, *message);
}

Code StageEmitter::resource_text(const Expr* e, const std::vector<uint32_t>& leaf) {
  if (std::optional<std::string> name = lower::resource_name(module_, e, leaf, names_)) return {std::move(*name)};
  fail_internal(e->loc, "no resource is known for this expression");
  return {"0"};
}

Code StageEmitter::texture_index(const IndexExpr& index) {
  const Type& type = index.object->type;
  const uint32_t n = coordinate_components(type.texture_shape());
  if (flavour_ == Flavour::Vk) require_extension("GL_EXT_samplerless_texture_functions");
  const std::string coordinate = n == 1 ? "int(" + expr(index.index.get()).text + ")"
                                        : "ivec" + std::to_string(n) + "(" + expr(index.index.get()).text + ")";
  return {"texelFetch(" + expr(index.object.get()).text + ", " + coordinate + ", 0)" +
              first_components(type.texel_type().component_count()),
          kPostfix};
}

Code StageEmitter::texture_call(const CallExpr& call) {
  if (call.object && call.object->type.kind() == TypeKind::Buffer &&
      is_read_only_buffer(call.object->type.buffer_kind()))
    return buffer_call(call);
  const auto id = IntrinsicId(call.intrinsic);
  const std::string name(intrinsic_info(id).name);
  std::vector<const Expr*> operands;
  if (call.object) operands.push_back(call.object.get());
  for (const ExprPtr& arg : call.args) operands.push_back(arg.get());
  std::vector<bool> out(operands.size(), false);
  const size_t args = call.args.size();

  if (is_dx9_sampling(id)) {
    std::string text;
    switch (id) {
      case I::Tex1D:
      case I::Tex2D:
      case I::Tex3D:
      case I::TexCUBE: text = args == 4 ? "textureGrad($0, $1, $2, $3)" : "texture($0, $1)"; break;
      case I::Tex1Dgrad:
      case I::Tex2Dgrad:
      case I::Tex3Dgrad:
      case I::TexCUBEgrad: text = "textureGrad($0, $1, $2, $3)"; break;
      case I::Tex1Dbias: text = "texture($0, $1.x, $1.w)"; break;
      case I::Tex2Dbias: text = "texture($0, $1.xy, $1.w)"; break;
      case I::Tex3Dbias:
      case I::TexCUBEbias: text = "texture($0, $1.xyz, $1.w)"; break;
      case I::Tex1Dlod: text = "textureLod($0, $1.x, $1.w)"; break;
      case I::Tex2Dlod: text = "textureLod($0, $1.xy, $1.w)"; break;
      case I::Tex3Dlod:
      case I::TexCUBElod: text = "textureLod($0, $1.xyz, $1.w)"; break;
      // textureProj divides the coordinate by its last component; a cube map's direction needs no division.
      case I::Tex1Dproj:
      case I::Tex2Dproj:
      case I::Tex3Dproj: text = "textureProj($0, $1)"; break;
      case I::TexCUBEproj: text = "texture($0, $1.xyz)"; break;
      default: break;
    }
    return expand_template(text, call, operands, out);
  }

  const Type& texture = call.object->type;
  if (texture.kind() != TypeKind::Texture) {
    fail(call.loc, in_quotes(texture.name()) + " is not supported on this target");
    return {"0"};
  }
  const TextureShape shape = texture.texture_shape();
  const uint32_t n = coordinate_components(shape);
  const ScalarType texel = texture.scalar_type() == ScalarType::Half ? ScalarType::Float : texture.scalar_type();
  const bool compare = lower::is_comparison_method(id);
  const Decl* object_decl = lower::named_decl(call.object.get());
  if (flavour_ == Flavour::Gl && !compare && id != I::GetDimensions && object_decl && compared_.count(object_decl))
    fail(call.loc, "texture " + in_quotes(object_decl->name) +
                       " is read both with and without a SamplerComparisonState; "
                       "OpenGL declares a texture one way, as a shadow sampler or not: use two textures");
  // The sampler a Sample-like method reads through: the texture itself on gl (the sampler state
  // belongs to the texture unit), a combined sampler made of texture and sampler state on vk.
  const std::string sampler = flavour_ == Flavour::Gl ? "$0" : combined_type(shape, texel, compare) + "($0, $1)";
  // An offset must be a constant expression for GLSL's *Offset functions.
  auto constant_offset = [&](size_t arg) {
    if (arg < args && !is_constant(call.args[arg].get()))
      fail(call.args[arg]->loc,
           "the texel offset of " + in_quotes(name) + " must be a constant expression on this target");
  };
  auto no_clamp = [&](size_t arg) {
    if (arg < args)
      fail(call.args[arg]->loc, "the level-of-detail clamp of " + in_quotes(name) + " is not supported on this target");
  };
  const std::string texel_part = first_components(call.type.component_count());
  std::string text;
  // A comparison the shader filters is a helper on every call: glslang (12) types a texture first
  // used in a shadow sampler's constructor as a depth image, and a helper that takes it as a
  // texture2D after that no longer matches it in SPIR-V; used only in helpers, it never is.
  bool filtered_in_helper = false;
  switch (id) {
    case I::Sample:
      no_clamp(3);
      constant_offset(2);
      text = (args >= 3 ? "textureOffset(" + sampler + ", $2, $3)" : "texture(" + sampler + ", $2)") + texel_part;
      break;
    case I::SampleBias:
      no_clamp(4);
      constant_offset(3);
      text =
          (args >= 4 ? "textureOffset(" + sampler + ", $2, $4, $3)" : "texture(" + sampler + ", $2, $3)") + texel_part;
      break;
    case I::SampleLevel:
      constant_offset(3);
      text = (args >= 4 ? "textureLodOffset(" + sampler + ", $2, $3, $4)" : "textureLod(" + sampler + ", $2, $3)") +
             texel_part;
      break;
    case I::SampleGrad:
      no_clamp(5);
      constant_offset(4);
      text = (args >= 5 ? "textureGradOffset(" + sampler + ", $2, $3, $4, $5)"
                        : "textureGrad(" + sampler + ", $2, $3, $4)") +
             texel_part;
      break;
    case I::SampleCmp:
      no_clamp(4);
      constant_offset(3);
      if (filter_comparisons_ && shape == TextureShape::Tex2D) {
        text = bilinear_comparison(sampler, args >= 4 ? 4 : 0);
        filtered_in_helper = true;
      } else if (shape == TextureShape::CubeArray) {
        if (args >= 4) fail(call.loc, "'SampleCmp' of a TextureCubeArray takes no offset");
        text = "texture(" + sampler + ", $2, $3)";
      } else {
        text = args >= 4 ? "textureOffset(" + sampler + ", " + shadow_coordinate(shape) + ", $4)"
                         : "texture(" + sampler + ", " + shadow_coordinate(shape) + ")";
      }
      break;
    case I::SampleCmpLevelZero: {
      // GLSL has textureLod only for 1D and 2D shadow samplers; zero gradients give level 0 too.
      constant_offset(3);
      const std::string coordinate = shadow_coordinate(shape);
      if (filter_comparisons_ && shape == TextureShape::Tex2D) {
        text = bilinear_comparison(sampler, args >= 4 ? 4 : 0);
        filtered_in_helper = true;
      } else if (shape == TextureShape::CubeArray) {
        fail(call.loc, "'SampleCmpLevelZero' of a TextureCubeArray is not supported on this target");
      } else if (shape == TextureShape::Tex2DArray || shape == TextureShape::Cube) {
        const std::string zero = shape == TextureShape::Cube ? "vec3(0.0)" : "vec2(0.0)";
        text = args >= 4 ? "textureGradOffset(" + sampler + ", " + coordinate + ", " + zero + ", " + zero + ", $4)"
                         : "textureGrad(" + sampler + ", " + coordinate + ", " + zero + ", " + zero + ")";
      } else {
        text = args >= 4 ? "textureLodOffset(" + sampler + ", " + coordinate + ", 0.0, $4)"
                         : "textureLod(" + sampler + ", " + coordinate + ", 0.0)";
      }
      break;
    }
    case I::SubpassLoad:
      // Vulkan reads the input attachment at the fragment's pixel; OpenGL, which has no subpasses,
      // reads the previous pass's target bound as a texture at the same pixel.
      if (flavour_ == Flavour::Vk)
        text = std::string(shape == TextureShape::SubpassMS ? "subpassLoad($0, $1)" : "subpassLoad($0)") + texel_part;
      else
        text = std::string(shape == TextureShape::SubpassMS ? "texelFetch($0, ivec2(gl_FragCoord.xy), $1)"
                                                            : "texelFetch($0, ivec2(gl_FragCoord.xy), 0)") +
               texel_part;
      break;
    case I::Load: {
      // texelFetch takes no sampler, so on vk it needs GL_EXT_samplerless_texture_functions. An
      // offset is added to the coordinate: texelFetch neither filters nor wraps, so that is what
      // HLSL's offset means, and it need not be a constant.
      // An array's layer takes no offset: only the texel coordinates before it move.
      if (flavour_ == Flavour::Vk) require_extension("GL_EXT_samplerless_texture_functions");
      const auto offset_coordinate = [&](const std::string& offset) {
        const std::string coordinate = "$1" + first_components(n);
        if (!is_array_shape(shape)) return coordinate + " + " + offset;
        const uint32_t moved = offset_components(shape);
        return "ivec" + std::to_string(n) + "($1" + first_components(moved) + " + " + offset + ", $1." +
               kComponents[moved] + ")";
      };
      if (is_multisampled(shape)) {
        text = "texelFetch($0, " + (args >= 3 ? offset_coordinate("$3") : std::string("$1")) + ", $2)";
      } else {
        const std::string level = std::string("$1.") + kComponents[n];
        text =
            "texelFetch($0, " + (args >= 2 ? offset_coordinate("$2") : "$1" + first_components(n)) + ", " + level + ")";
      }
      text += texel_part;
      break;
    }
    case I::Gather:
    case I::GatherRed:
    case I::GatherGreen:
    case I::GatherBlue:
    case I::GatherAlpha: {
      const std::string component = std::to_string(int(id) - int(id == I::Gather ? I::Gather : I::GatherRed));
      text = args >= 3 ? "textureGatherOffset(" + sampler + ", $2, $3, " + component + ")"
                       : "textureGather(" + sampler + ", $2, " + component + ")";
      break;
    }
    case I::GatherCmp:
    case I::GatherCmpRed:
      text = args >= 4 ? "textureGatherOffset(" + sampler + ", $2, $3, $4)" : "textureGather(" + sampler + ", $2, $3)";
      break;
    case I::GatherCmpGreen:
    case I::GatherCmpBlue:
    case I::GatherCmpAlpha:
      fail(call.loc,
           in_quotes(name) + " is not supported on this target: a GLSL shadow gather compares the first component");
      return {"vec4(0.0)"};
    case I::CalculateLevelOfDetail: text = "textureQueryLod(" + sampler + ", $2).x"; break;
    case I::CalculateLevelOfDetailUnclamped: text = "textureQueryLod(" + sampler + ", $2).y"; break;
    case I::GetDimensions: {
      // textureSize gives width, height and depth or layers as one int vector; HLSL's out
      // parameters take them one by one, then the level count (or the sample count).
      if (flavour_ == Flavour::Vk) require_extension("GL_EXT_samplerless_texture_functions");
      const bool ms = is_multisampled(shape);
      uint32_t sizes = 3;
      switch (shape) {
        case TextureShape::Tex1D: sizes = 1; break;
        case TextureShape::Tex1DArray:
        case TextureShape::Tex2D:
        case TextureShape::Tex2DMS:
        case TextureShape::Cube: sizes = 2; break;
        default: break;
      }
      const bool mip_form = !ms && args == sizes + 2;  // (mip, sizes..., levels)
      const size_t first_out = mip_form ? 1 : 0;
      if (mip_form && !is_simple(call.args[0].get()))
        fail(call.args[0]->loc, "GetDimensions' mip level must be a variable or a constant here");
      const std::string texture_text = expr(call.object.get()).text;
      const std::string size = ms ? "textureSize(" + texture_text + ")"
                                  : "textureSize(" + texture_text + ", " +
                                        (mip_form ? "int(" + expr(call.args[0].get()).text + ")" : std::string("0")) +
                                        ")";
      std::string parts;
      for (size_t i = first_out; i < args; ++i) {
        const Expr* target = call.args[i].get();
        const Type& param_type = target->type;
        if (target->kind == ExprKind::Conversion) target = static_cast<const ConversionExpr*>(target)->operand.get();
        const size_t k = i - first_out;
        Code value;
        if (k < sizes)
          value = {sizes == 1 ? size : size + "." + kComponents[k], kPostfix};
        else
          value = {ms ? "textureSamples(" + texture_text + ")" : "textureQueryLevels(" + texture_text + ")", kPostfix};
        const Code as_param = convert(value, Type::scalar(ScalarType::Int), param_type, call.loc);
        parts += (i == first_out ? "" : ", ") + operand(expr(target), kUnary) + " = " +
                 operand(convert(as_param, param_type, target->type, call.loc), kAssign);
      }
      return {"(" + parts + ")"};
    }
    default: fail(call.loc, in_quotes(name) + " is not supported on this target"); return {"0"};
  }
  return expand_template(text, call, operands, out, filtered_in_helper);
}

}  // namespace xshade::glsl::detail
