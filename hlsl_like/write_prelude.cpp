// Writes the prelude as an HLSL file of #defines (installed as shaders/include/xshade_prelude.hlsl),
// so that another HLSL compiler or an editor can read an xshade source: xshade defines the same
// macros itself before every file, from the same list (hlsl_like/prelude.h).
#include <cstdio>

#include "hlsl_like/prelude.h"

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: xshade_write_prelude FILE\n");
    return 2;
  }
  FILE* out = std::fopen(argv[1], "w");
  if (!out) {
    std::perror(argv[1]);
    return 1;
  }
  std::fputs(
      "// The prelude xshade defines before every hlsl_like file (docs/hlsl_like.md, \"The prelude\").\n"
      "// Generated from the compiler's own list when xshade is built; xshade does not need this file.\n"
      "// Include it where another HLSL compiler or an editor reads an xshade shader.\n"
      "#ifndef XSHADE_PRELUDE_HLSL\n"
      "#define XSHADE_PRELUDE_HLSL\n",
      out);
  for (const xshade::hlsl::MacroDefinition& macro : xshade::hlsl::prelude_macros())
    std::fprintf(out, "#ifndef %s\n#define %s %s\n#endif\n", macro.name.c_str(), macro.name.c_str(),
                 macro.value.c_str());
  std::fputs("#endif\n", out);
  return std::fclose(out) == 0 ? 0 : 1;
}
