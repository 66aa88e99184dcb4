#version 450
// Positions are already in clip space; uv passes through.
layout(location = 0) in vec3 position;
layout(location = 3) in vec2 texcoord;
layout(location = 0) out vec2 uv;
void main() {
  uv = texcoord;
  gl_Position = vec4(position, 1.0);
}
