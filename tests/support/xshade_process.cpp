#include "tests/support/xshade_process.h"

#include <sys/wait.h>

#include <array>
#include <cstdio>

namespace xshade::tests {

namespace {

Outcome run_command(const std::string& command) {
  Outcome outcome;
  FILE* pipe = popen(command.c_str(), "r");
  if (!pipe) return outcome;
  std::array<char, 4096> buffer;
  while (size_t n = fread(buffer.data(), 1, buffer.size(), pipe)) outcome.output.append(buffer.data(), n);
  const int status = pclose(pipe);
  outcome.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return outcome;
}

}  // namespace

const char* xshade_binary() { return XSHADE_BINARY; }

std::string xshade_command(const std::string& environment, const std::string& arguments) {
  return environment + " '" XSHADE_BINARY "' " + arguments + " 2>&1";
}

Outcome run_xshade(const std::string& environment, const std::string& arguments) {
  return run_command(xshade_command(environment, arguments));
}

Outcome run_xshade_in(const std::filesystem::path& folder, const std::string& arguments) {
  return run_command("cd '" + folder.string() + "' && " + xshade_command("", arguments));
}

}  // namespace xshade::tests
