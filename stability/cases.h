// The cases of the stability suite, by the part of the library they exercise.
#pragma once

#include <vector>

#include "stability/case.h"

namespace xshade::stability {

std::vector<Case> brdf_cases();     // include/brdf.hlsl, materials/standard_pbr.hlsl: 5.1-5.7, 5.10, 5.11
std::vector<Case> toon_cases();     // include/toon.hlsl: 5.12
std::vector<Case> furnace_cases();  // integrals of the BRDF and the white furnace: 5.8, 5.9
std::vector<Case> dof_cases();      // post/depth_of_field.hlsl: 5.13-5.15

// Every case, in SHADERS.md's order.
std::vector<Case> all_cases();

}  // namespace xshade::stability
