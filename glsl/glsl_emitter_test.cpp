#include "glsl/glsl_emitter.h"

#include <gtest/gtest.h>
#include <fstream>
#include <sstream>
#include <cstdlib>

TEST(GlslEmitter, Dump) {
  const char* path = std::getenv("XS_FILE");
  if (!path) return;
  std::ifstream f(path);
  std::stringstream ss; ss << f.rdbuf();
  auto module = xshade::hlsl::compile_text("test.hlsl", ss.str(), {});
  for (auto& d : module->diagnostics.diagnostics()) std::cout << d.to_string() << "\n";
  for (auto flavour : {xshade::glsl::Flavour::Gl, xshade::glsl::Flavour::Vk}) {
    auto program = xshade::glsl::emit(*module, {flavour});
    if (!program) { std::cout << program.error().to_string() << "\n"; continue; }
    if (program->vertex) std::cout << program->vertex->text << "\n-----\n";
    if (program->fragment) std::cout << program->fragment->text << "\n=====\n";
  }
}
