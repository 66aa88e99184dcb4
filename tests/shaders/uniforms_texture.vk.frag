#version 450
// A uniform block of mixed members and a sampled float texture feed one expression.
layout(std140, set = 0, binding = 0) uniform Params {
  mat4 transform;   // column-major, as the host uploads it
  vec4 tiling;      // uv * tiling.xy + tiling.zw
  vec4 bias;
  float gain;
};
layout(set = 0, binding = 1) uniform texture2D values;
layout(set = 0, binding = 2) uniform sampler values_sampler;
layout(location = 0) in vec2 uv;
layout(location = 0) out vec4 target;
void main() {
  vec4 texel = texture(sampler2D(values, values_sampler), uv * tiling.xy + tiling.zw);
  target = transform * texel * gain + bias;
}
