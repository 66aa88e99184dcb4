#version 450 core
// A uniform block of mixed members and a sampled float texture feed one expression.
layout(std140, binding = 0) uniform Params {
  mat4 transform;   // column-major, as the host uploads it
  vec4 tiling;      // uv * tiling.xy + tiling.zw
  vec4 bias;
  float gain;
};
layout(binding = 1) uniform sampler2D values;
layout(location = 0) in vec2 uv;
layout(location = 0) out vec4 target;
void main() {
  vec4 texel = texture(values, uv * tiling.xy + tiling.zw);
  target = transform * texel * gain + bias;
}
