#version 450 core
// Filtering alone: the interpolated uv, unchanged, into the sampler.
layout(binding = 1) uniform sampler2D values;
layout(location = 0) in vec2 uv;
layout(location = 0) out vec4 target;
void main() {
  target = texture(values, uv);
}
