#version 450
// Filtering alone: the interpolated uv, unchanged, into the sampler.
layout(set = 0, binding = 1) uniform texture2D values;
layout(set = 0, binding = 2) uniform sampler values_sampler;
layout(location = 0) in vec2 uv;
layout(location = 0) out vec4 target;
void main() {
  target = texture(sampler2D(values, values_sampler), uv);
}
