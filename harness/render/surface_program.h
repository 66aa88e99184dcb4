// A surface shader's passes, generated (shaderlab/surface_shader.h) from what the front end reads
// of the author's program: its Input struct, the surface function's output struct and whether it
// writes a normal, the lighting function's form, the vertex modifier's input.
#pragma once

#include <filesystem>
#include <vector>

#include "base/result.h"
#include "hlsl_like/compiler.h"
#include "shaderlab/compile_environment.h"
#include "shaderlab/shader.h"
#include "shaderlab/surface_shader.h"

namespace xshade::harness {

// The shape of `sub`'s surface program (read with `options`, whose include folders find Unity's
// include files), or an error at the pragma that says what the program lacks: the surface
// function, an Input struct, a lighting function of a form Unity's manual lists.
Result<shaderlab::SurfaceProgramShape> read_surface_program(const std::filesystem::path& file,
                                                            const shaderlab::SubShader& sub,
                                                            const shaderlab::SurfaceDirective& directive,
                                                            hlsl::CompileOptions options,
                                                            shaderlab::UnityPlatform platform);

// `sub` with the passes Unity generates from its surface program in the place of the program,
// after the passes written before it and before those after it.
Result<shaderlab::SubShader> with_surface_passes(const std::filesystem::path& file, const shaderlab::SubShader& sub,
                                                 const hlsl::CompileOptions& options,
                                                 shaderlab::UnityPlatform platform);

}  // namespace xshade::harness
