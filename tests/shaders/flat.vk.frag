#version 450
layout(std140, set = 0, binding = 0) uniform Flat { vec4 color; };
layout(location = 0) out vec4 target;
void main() {
  target = color;
}
