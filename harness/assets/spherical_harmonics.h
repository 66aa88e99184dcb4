// Diffuse environment light as 9 real spherical-harmonic coefficients (bands 0..2).
//
// Convention (the shaders evaluate the same sum): coefficients c_i, linear RGB, such that
//   sum_i c_i * Y_i(n)  ~=  irradiance(n) / pi,
// so a constant environment of radiance L gives exactly L (Unity's convention, where diffuse
// reflectance is not divided by pi). The cosine-lobe convolution (Ramamoorthi and Hanrahan:
// A0 = pi, A1 = 2 pi / 3, A2 = pi / 4) and the 1 / pi are folded into the coefficients.
// Basis order and constants, for a unit normal n = (x, y, z):
//   Y0 = 0.282095          Y1 = 0.488603 y        Y2 = 0.488603 z        Y3 = 0.488603 x
//   Y4 = 1.092548 x y      Y5 = 1.092548 y z      Y6 = 0.315392 (3 z^2 - 1)
//   Y7 = 1.092548 x z      Y8 = 0.546274 (x^2 - y^2)
#pragma once

#include <array>

#include <glm/vec3.hpp>

#include "harness/image/image.h"

namespace xshade::harness {

using ShCoefficients = std::array<glm::vec3, 9>;

// The nine basis functions at a unit direction, in the order above.
std::array<float, 9> sh_basis(glm::vec3 n);

// sum_i c_i * Y_i(n): irradiance(n) / pi for coefficients from irradiance_sh.
glm::vec3 sh_evaluate(const ShCoefficients& coefficients, glm::vec3 n);

// The coefficients of an equirect radiance image (see equirect.h for the mapping). Each texel
// is taken as constant radiance over its area, and each basis function is integrated over that
// area exactly (sin(theta) dtheta dphi), so a constant image projects to a constant without
// quadrature error.
ShCoefficients irradiance_sh(const FloatImage& equirect_radiance);

}  // namespace xshade::harness
