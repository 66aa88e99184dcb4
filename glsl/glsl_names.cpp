#include "glsl/glsl_names.h"

#include <algorithm>
#include <array>
#include <iterator>
#include <string_view>

#include "base/string_index.h"

namespace xshade::glsl {
namespace {

// GLSL 4.50 and Vulkan GLSL: keywords, reserved words, types, and built-in functions. An HLSL
// author may use any of them as a name (`input`, `texture`, `sample`, `mix`, `mod`, `filter`).
constexpr std::string_view kReservedWords[] = {
    // keywords
    "attribute", "const", "uniform", "varying", "buffer", "shared", "coherent", "volatile", "restrict",
    "readonly", "writeonly", "atomic_uint", "layout", "centroid", "flat", "smooth", "noperspective", "patch",
    "sample", "break", "continue", "do", "for", "while", "switch", "case", "default", "if", "else",
    "subroutine", "in", "out", "inout", "float", "double", "int", "void", "bool", "true", "false", "invariant",
    "precise", "discard", "return", "lowp", "mediump", "highp", "precision", "struct", "uint",
    // reserved for future use
    "common", "partition", "active", "asm", "class", "union", "enum", "typedef", "template", "this", "resource",
    "goto", "inline", "noinline", "public", "static", "extern", "external", "interface", "long", "short", "half",
    "fixed", "unsigned", "superp", "input", "output", "hvec2", "hvec3", "hvec4", "fvec2", "fvec3", "fvec4",
    "sampler3DRect", "filter", "sizeof", "cast", "namespace", "using", "demote", "nonuniformEXT",
    // vector and matrix types
    "vec2", "vec3", "vec4", "ivec2", "ivec3", "ivec4", "bvec2", "bvec3", "bvec4", "uvec2", "uvec3", "uvec4",
    "dvec2", "dvec3", "dvec4", "mat2", "mat3", "mat4", "mat2x2", "mat2x3", "mat2x4", "mat3x2", "mat3x3",
    "mat3x4", "mat4x2", "mat4x3", "mat4x4", "dmat2", "dmat3", "dmat4", "dmat2x2", "dmat2x3", "dmat2x4",
    "dmat3x2", "dmat3x3", "dmat3x4", "dmat4x2", "dmat4x3", "dmat4x4",
    "float16_t", "float32_t", "float64_t", "int8_t", "int16_t", "int32_t", "int64_t", "uint8_t", "uint16_t",
    "uint32_t", "uint64_t", "f16vec2", "f16vec3", "f16vec4", "i64vec2", "u64vec2",
    // opaque types
    "sampler1D", "sampler2D", "sampler3D", "samplerCube", "sampler1DShadow", "sampler2DShadow",
    "samplerCubeShadow", "sampler1DArray", "sampler2DArray", "sampler1DArrayShadow", "sampler2DArrayShadow",
    "isampler1D", "isampler2D", "isampler3D", "isamplerCube", "isampler1DArray", "isampler2DArray",
    "usampler1D", "usampler2D", "usampler3D", "usamplerCube", "usampler1DArray", "usampler2DArray",
    "sampler2DRect", "sampler2DRectShadow", "isampler2DRect", "usampler2DRect", "samplerBuffer",
    "isamplerBuffer", "usamplerBuffer", "sampler2DMS", "isampler2DMS", "usampler2DMS", "sampler2DMSArray",
    "isampler2DMSArray", "usampler2DMSArray", "samplerCubeArray", "samplerCubeArrayShadow", "isamplerCubeArray",
    "usamplerCubeArray", "image1D", "iimage1D", "uimage1D", "image2D", "iimage2D", "uimage2D", "image3D",
    "iimage3D", "uimage3D", "image2DRect", "iimage2DRect", "uimage2DRect", "imageCube", "iimageCube",
    "uimageCube", "imageBuffer", "iimageBuffer", "uimageBuffer", "image1DArray", "iimage1DArray",
    "uimage1DArray", "image2DArray", "iimage2DArray", "uimage2DArray", "imageCubeArray", "iimageCubeArray",
    "uimageCubeArray", "image2DMS", "iimage2DMS", "uimage2DMS", "image2DMSArray", "iimage2DMSArray",
    "uimage2DMSArray", "sampler", "samplerShadow", "texture1D", "texture2D", "texture3D", "textureCube",
    "texture2DRect", "texture1DArray", "texture2DArray", "textureBuffer", "texture2DMS", "texture2DMSArray",
    "textureCubeArray", "itexture1D", "itexture2D", "itexture3D", "itextureCube", "itexture2DArray",
    "utexture1D", "utexture2D", "utexture3D", "utextureCube", "utexture2DArray", "subpassInput",
    "isubpassInput", "usubpassInput", "subpassInputMS", "isubpassInputMS", "usubpassInputMS",
    // built-in functions
    "radians", "degrees", "sin", "cos", "tan", "asin", "acos", "atan", "sinh", "cosh", "tanh", "asinh", "acosh",
    "atanh", "pow", "exp", "log", "exp2", "log2", "sqrt", "inversesqrt", "abs", "sign", "floor", "trunc", "round",
    "roundEven", "ceil", "fract", "mod", "modf", "min", "max", "clamp", "mix", "step", "smoothstep", "isnan",
    "isinf", "floatBitsToInt", "floatBitsToUint", "intBitsToFloat", "uintBitsToFloat", "fma", "frexp", "ldexp",
    "packUnorm2x16", "packSnorm2x16", "packUnorm4x8", "packSnorm4x8", "unpackUnorm2x16", "unpackSnorm2x16",
    "unpackUnorm4x8", "unpackSnorm4x8", "packHalf2x16", "unpackHalf2x16", "packDouble2x32",
    "unpackDouble2x32", "length", "distance", "dot", "cross", "normalize", "faceforward", "reflect", "refract",
    "matrixCompMult", "outerProduct", "transpose", "determinant", "inverse", "lessThan", "lessThanEqual",
    "greaterThan", "greaterThanEqual", "equal", "notEqual", "any", "all", "not", "uaddCarry", "usubBorrow",
    "umulExtended", "imulExtended", "bitfieldExtract", "bitfieldInsert", "bitfieldReverse", "bitCount",
    "findLSB", "findMSB", "textureSize", "textureQueryLod", "textureQueryLevels", "textureSamples", "texture",
    "textureProj", "textureLod", "textureOffset", "texelFetch", "texelFetchOffset", "textureProjOffset",
    "textureLodOffset", "textureProjLod", "textureProjLodOffset", "textureGrad", "textureGradOffset",
    "textureProjGrad", "textureProjGradOffset", "textureGather", "textureGatherOffset", "textureGatherOffsets",
    "texture1DProj", "texture1DLod", "texture1DProjLod", "texture2DProj", "texture2DLod", "texture2DProjLod",
    "texture3DProj", "texture3DLod", "texture3DProjLod", "textureCubeLod", "shadow1D", "shadow2D",
    "shadow1DProj", "shadow2DProj", "shadow1DLod", "shadow2DLod", "shadow1DProjLod", "shadow2DProjLod",
    "atomicCounterIncrement", "atomicCounterDecrement", "atomicCounter", "atomicAdd", "atomicMin", "atomicMax",
    "atomicAnd", "atomicOr", "atomicXor", "atomicExchange", "atomicCompSwap", "imageSize", "imageSamples",
    "imageLoad", "imageStore", "imageAtomicAdd", "imageAtomicMin", "imageAtomicMax", "imageAtomicAnd",
    "imageAtomicOr", "imageAtomicXor", "imageAtomicExchange", "imageAtomicCompSwap", "dFdx", "dFdy",
    "dFdxFine", "dFdyFine", "dFdxCoarse", "dFdyCoarse", "fwidth", "fwidthFine", "fwidthCoarse",
    "interpolateAtCentroid", "interpolateAtSample", "interpolateAtOffset", "noise1", "noise2", "noise3",
    "noise4", "EmitStreamVertex", "EndStreamPrimitive", "EmitVertex", "EndPrimitive", "barrier",
    "memoryBarrier", "memoryBarrierAtomicCounter", "memoryBarrierBuffer", "memoryBarrierShared",
    "memoryBarrierImage", "groupMemoryBarrier", "subpassLoad", "anyInvocation", "allInvocations",
    "allInvocationsEqual",
    // the stage's entry function is main(); the author's `main` must not collide with it
    "main",
};

bool starts_with(std::string_view text, std::string_view prefix) { return text.substr(0, prefix.size()) == prefix; }

// The reserved words in a StringIndex. Every name the emitter writes is looked up here; most
// are told apart by their first character alone (`_MainTex`, `Light`) or their length, before
// any hashing.
class ReservedWords {
 public:
  ReservedWords() : words_(std::size(kReservedWords)) {
    for (std::string_view word : kReservedWords) {
      words_.insert(word);
      longest_ = std::max(longest_, word.size());
      first_chars_[static_cast<unsigned char>(word[0])] = true;
    }
  }

  bool contains(std::string_view name) const {
    if (name.empty() || name.size() > longest_ || !first_chars_[static_cast<unsigned char>(name[0])]) return false;
    return words_.find(name) != StringIndex::kAbsent;
  }

 private:
  StringIndex words_;
  size_t longest_ = 0;
  std::array<bool, 256> first_chars_{};  // the characters some word starts with
};

}  // namespace

bool is_glsl_reserved_word(std::string_view name) {
  static const ReservedWords kReserved;
  return kReserved.contains(name);
}

bool needs_renaming(std::string_view name) {
  if (name.size() >= 3 && name[2] == '_' && ((name[0] == 'g' && name[1] == 'l') || (name[0] == 'x' && name[1] == 's')))
    return true;  // gl_ or xs_
  for (size_t i = 1; i < name.size(); ++i)
    if (name[i] == '_' && name[i - 1] == '_') return true;
  return is_glsl_reserved_word(name);
}

// Rules, in order, chosen so that the result never needs renaming again:
// 1. each `__` becomes `_0` (`a__b` -> `a_0b`; GLSL reserves names with `__`);
// 2. a reserved word gets a trailing `_` (`input` -> `input_`);
// 3. a `gl_` prefix gets `xs_` in front (`gl_x` -> `xs_gl_x`, then `xs_gl_x_` by rule 4);
// 4. an `xs_` prefix gets a trailing `_` unless it has one: the emitter's own names never end in `_`.
std::string renamed(std::string_view name) {
  std::string result;
  result.reserve(name.size() + 4);
  for (size_t i = 0; i < name.size(); ++i) {
    if (name[i] == '_' && i + 1 < name.size() && name[i + 1] == '_') {
      result += "_0";
      ++i;
    } else {
      result += name[i];
    }
  }
  if (is_glsl_reserved_word(result)) result += '_';
  if (starts_with(result, "gl_")) result = "xs_" + result;
  if (starts_with(result, "xs_") && result.back() != '_') result += '_';
  return result;
}

}  // namespace xshade::glsl
