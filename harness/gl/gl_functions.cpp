#include "harness/gl/gl_functions.h"

#include <cstdio>

namespace xshade::harness::gl {

std::vector<std::string> load_functions(Functions& functions, ProcAddressFunction get_proc_address) {
  std::vector<std::string> missing;
  // A function pointer travels through void* here, as with dlsym; POSIX guarantees this works.
#define XSHADE_GL_LOAD(type, name)                                       \
  functions.name = reinterpret_cast<type>(get_proc_address("gl" #name)); \
  if (functions.name == nullptr) missing.push_back("gl" #name);
  XSHADE_GL_FUNCTIONS(XSHADE_GL_LOAD)
#undef XSHADE_GL_LOAD
  return missing;
}

std::string error_name(GLenum error) {
  switch (error) {
    case GL_NO_ERROR: return "GL_NO_ERROR";
    case GL_INVALID_ENUM: return "GL_INVALID_ENUM";
    case GL_INVALID_VALUE: return "GL_INVALID_VALUE";
    case GL_INVALID_OPERATION: return "GL_INVALID_OPERATION";
    case GL_INVALID_FRAMEBUFFER_OPERATION: return "GL_INVALID_FRAMEBUFFER_OPERATION";
    case GL_OUT_OF_MEMORY: return "GL_OUT_OF_MEMORY";
    case GL_STACK_OVERFLOW: return "GL_STACK_OVERFLOW";
    case GL_STACK_UNDERFLOW: return "GL_STACK_UNDERFLOW";
    case GL_CONTEXT_LOST: return "GL_CONTEXT_LOST";
  }
  char text[32];
  std::snprintf(text, sizeof text, "GL error 0x%04X", error);
  return text;
}

}  // namespace xshade::harness::gl
