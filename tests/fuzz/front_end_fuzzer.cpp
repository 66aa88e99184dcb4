// libFuzzer target: any bytes through the preprocessor, parser, semantic analysis and reflection,
// and what compiles through the GLSL emitter in both flavours. Both must report, never crash,
// hang or read out of bounds.
#include <cstddef>
#include <cstdint>
#include <string>

#include "glsl/glsl_emitter.h"
#include "hlsl_like/compiler.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  xshade::hlsl::CompileOptions options;
  // The first byte picks a variant keyword, so that keyword handling is fuzzed too.
  if (size > 0 && (data[0] & 1)) options.keywords.push_back("FUZZ_KEYWORD");
  auto module =
      xshade::hlsl::compile_text("fuzz.hlsl", std::string(reinterpret_cast<const char*>(data), size), options);
  (void)module->diagnostics.render_all();
  if (module->ok())
    for (const auto flavour : {xshade::glsl::Flavour::Gl, xshade::glsl::Flavour::Vk})
      (void)xshade::glsl::emit(*module, {flavour});
  return 0;
}
