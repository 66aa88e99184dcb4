// A Unity pass's render state (ShaderLab's Cull, ZWrite, ZTest, Blend, BlendOp, ColorMask,
// Offset, Stencil) as the DrawState the backends draw with, and a SubShader's Queue as the order Unity's
// forward renderer draws objects in.
#pragma once

#include <functional>
#include <optional>
#include <string>

#include "base/result.h"
#include "harness/backend/backend.h"
#include "shaderlab/shader.h"

namespace xshade::harness {

// The value of a material property a state names in brackets (`Cull [_Cull]`): the scene's, else
// the shader's Properties default; nullopt when the material has no such property.
using StatePropertyLookup = std::function<std::optional<float>(const std::string& name)>;

// `state` (a Pass's own over its SubShader's over its Category's) with Unity's defaults for what
// nothing sets: Cull Back, ZWrite On, ZTest LEqual, Blend Off, ColorMask RGBA, Offset 0, 0, no
// stencil test. A property's value is read as Unity's enums number them (UnityEngine.Rendering's
// CullMode, CompareFunction, BlendMode, BlendOp, ColorWriteMask, StencilOp). What xshade does not
// draw yet is an error at the command: a logical or advanced BlendOp, a render target's own blend
// other than the first's.
Result<DrawState> unity_draw_state(const shaderlab::RenderState& state, const StatePropertyLookup& property);

// `state` as Unity sets it on a render target of Direct3D's conventions (render_target_convention:
// y flipped, depth reversed): the faces the flip turns over swap (Cull Back culls what was Front,
// and the stencil's front and back faces swap), the depth test turns round (LEqual is GEqual), and
// the depth bias changes sign, so that Offset -1, -1 still pulls toward the camera.
DrawState on_direct3d_render_target(DrawState state);

// Whether the state turns AlphaToMask (alpha to coverage) on. It masks the samples of a pixel,
// and xshade's targets have one: OpenGL skips it there, Vulkan and Direct3D leave the one
// sample's fate to the driver, and Unity calls the result unpredictable without MSAA. So it is
// drawn as Off on every lane, and the plan says so (unity_draw_state leaves it out).
Result<bool> unity_alpha_to_mask(const shaderlab::RenderState& state, const StatePropertyLookup& property);

// Unity's render queues: Background 1000, Geometry 2000, AlphaTest 2450, Transparent 3000,
// Overlay 4000, with an offset ("Transparent+1"); a number as it is. A shader without the tag is
// Geometry. Errors name the tag's value.
inline constexpr int kGeometryQueue = 2000;
// Queues above this one are drawn back to front (Unity's transparent queues); the others in the
// scene's order.
inline constexpr int kLastOpaqueQueue = 2500;
Result<int> render_queue(const std::string& tag);

}  // namespace xshade::harness
