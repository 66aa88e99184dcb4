#version 450
// Reads an earlier pass's depth and writes it to every channel.
layout(set = 0, binding = 0) uniform texture2D scene_depth;
layout(set = 0, binding = 1) uniform sampler scene_depth_sampler;
layout(location = 0) in vec2 uv;
layout(location = 0) out vec4 target;
void main() {
  float depth = texture(sampler2D(scene_depth, scene_depth_sampler), uv).r;
  target = vec4(depth, depth, depth, 1.0);
}
