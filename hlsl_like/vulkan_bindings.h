// Vulkan's own bindings: [[vk::binding(N, set)]] on a cbuffer or a resource, as DXC's SPIR-V
// back end honours it. Reflection gives every other resource its register's binding first.
#pragma once

#include "hlsl_like/ast.h"
#include "hlsl_like/diagnostic_engine.h"
#include "hlsl_like/reflection.h"

namespace xshade::hlsl {

// The attributes of a cbuffer or a global that has [[vk::binding]], else null.
const VulkanAttributes* given_binding(const Decl* decl);

// Sets the binding and set of each constant buffer, texture and sampler that has
// [[vk::binding]]; two the entry points read at one binding of one set are an error at the
// second, except a texture and a sampler (one combined image sampler's descriptor serves both).
// What has no attribute moves off the numbers the attributes took in set 0.
void give_vulkan_bindings(Reflection& reflection, DiagnosticEngine& diagnostics);

}  // namespace xshade::hlsl
