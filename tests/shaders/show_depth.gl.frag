#version 450 core
// Reads an earlier pass's depth and writes it to every channel.
layout(binding = 0) uniform sampler2D scene_depth;
layout(location = 0) in vec2 uv;
layout(location = 0) out vec4 target;
void main() {
  float depth = texture(scene_depth, uv).r;
  target = vec4(depth, depth, depth, 1.0);
}
