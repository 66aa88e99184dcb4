// The multisample fill's fragment shader (vk_support.h): the layer a push constant names, read
// from a 2D array of texels; compiled when xshade is built once per texel kind, SAMPLER and TEXEL
// defined to isampler2DArray and ivec4 (int), usampler2DArray and uvec4 (uint) or sampler2DArray
// and vec4 (float).
#version 450
layout(set = 0, binding = 0) uniform SAMPLER source;
layout(push_constant) uniform Fill { int layer; } fill;
layout(location = 0) out TEXEL color;
void main() { color = texelFetch(source, ivec3(ivec2(gl_FragCoord.xy), fill.layer), 0); }
