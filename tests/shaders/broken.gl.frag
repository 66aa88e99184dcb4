#version 450 core
layout(location = 0) out vec4 target;
void main() {
  target = vec4(not_declared_anywhere, 1.0);
}
