#version 450 core
// Values a float target must keep: above 1, negative, NaN and +Inf (built from their bits so that
// no compiler folds them away), and -Inf in the second row.
layout(location = 0) out vec4 target;
void main() {
  float nan_value = uintBitsToFloat(0x7fc00000u);
  float infinity = uintBitsToFloat(0x7f800000u);
  target = gl_FragCoord.y < 1.0 ? vec4(2.5, -1.0, nan_value, infinity) : vec4(-infinity, 65504.0, 1e-30, 0.0);
}
