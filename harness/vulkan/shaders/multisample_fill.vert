// The multisample fill's full-screen triangle (vk_support.h), compiled to SPIR-V when xshade is built.
#version 450
void main() {
  vec2 corner = vec2((gl_VertexIndex << 1) & 2, gl_VertexIndex & 2);
  gl_Position = vec4(corner * 2.0 - 1.0, 0.0, 1.0);
}
