// Deterministic inputs from a seed, for running a shader whose engine is not there (xshade eval
// --seed, corpus execution): the same seed gives the same bytes on every lane and every run.
#pragma once

#include <cstdint>
#include <vector>

#include "harness/backend/backend.h"
#include "harness/render/shader_interface.h"
#include "hlsl_like/reflection.h"

namespace xshade::harness {

// Every member of the buffer from the seed and the member's name, in a range real shaders mean
// such values for: a float in [0.1, 1] (no zero to divide by, no negative under a square root or
// a log), a matrix the identity plus up to 0.1 in each component, an int or uint in 0..3 (loop
// counts, indices), a bool 0 or 1. HLSL packing, as reflection gives it.
std::vector<std::byte> seeded_constant_buffer(const hlsl::ConstantBuffer& buffer, uint32_t seed);

// The bytes of a read-only buffer from the seed and the buffer's name: 64 elements, or 256 of one
// word each (a ByteAddressBuffer's, a StructuredBuffer<float>'s), each word by its type in the ranges of a constant
// buffer's (a float in [0.1, 1], an int or uint in 0..3, a bool 0 or 1); a ByteAddressBuffer's words are floats
// (StorageBufferInput::words), what raw buffers mostly hold.
std::vector<std::byte> seeded_storage_buffer(const StorageBufferInput& buffer, uint32_t seed);

// Noise of the slot's shape and texel kind from the seed and the slot's name: 16 texels a side
// (1D: 16 x 1; arrays 2 layers; cubes 6 faces; 3D 16 slices), a full mip chain (one level when
// multisampled, 4 samples). Float texels in [0, 1); int and uint ones in 0..7; a comparison slot a
// depth texture of values in (0, 1). A texture whose name says depth (Unity's _CameraDepthTexture)
// is noise in (0, 1) too, as a depth buffer holds.
TextureData seeded_texture(const TextureSlot& slot, uint32_t seed);

// How a seeded texture is sampled: linear for float texels (trilinear with its mips), nearest
// for integer ones (which no API filters), repeating.
SamplerDesc seeded_sampler(const TextureSlot& slot);

}  // namespace xshade::harness
