#version 450
// Reads a varying at location 1 that mesh.vk.vert never writes: a pipeline the Vulkan
// validation layer must object to, which proves its messages reach the test.
layout(location = 1) in vec4 never_written;
layout(location = 0) out vec4 target;
void main() {
  target = never_written;
}
