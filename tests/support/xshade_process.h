// Running the real `xshade` binary from a test, as a user or CI would, and reading what it said.
#pragma once

#include <filesystem>
#include <string>

namespace xshade::tests {

struct Outcome {
  int exit_code = -1;
  std::string output;  // standard output and standard error together
};

// The path of the xshade binary the tests run.
const char* xshade_binary();

// Runs `environment xshade arguments` through the shell: `environment` is VAR=value pairs (or
// empty), `arguments` is quoted as the shell needs.
Outcome run_xshade(const std::string& environment, const std::string& arguments);

// The shell command run_xshade runs, for a test that starts xshade itself (several at once, or
// reading its output while it runs).
std::string xshade_command(const std::string& environment, const std::string& arguments);

// The same, with `folder` as the working folder (where xshade looks for a project file).
Outcome run_xshade_in(const std::filesystem::path& folder, const std::string& arguments);

}  // namespace xshade::tests
