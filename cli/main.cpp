// xshade: compile shaders once, render them on every lane, and compare the images.
#include <CLI/CLI.hpp>

#include <algorithm>
#include <cstdio>
#include <exception>
#include <new>
#include <optional>
#include <string>

#include "base/heap.h"
#include "base/spelling.h"
#include "base/subprocess.h"

#include "cli/commands.h"

namespace {

// "; did you mean 'bless'?" for a word that is a typo of one of `names`, else empty.
std::string did_you_mean(const std::string& word, const std::vector<std::string>& names) {
  auto near = xshade::nearest(word, names);
  return near ? "; did you mean '" + *near + "'?" : std::string();
}

// A misspelt verb or option, named with the nearest one the command has; nullopt when the
// error is another kind, which CLI11 reports itself.
std::optional<std::string> misspelling(const CLI::App& app, const CLI::ParseError& error, int argc, char** argv) {
  if (argc > 1 && argv[1][0] != '-') {
    std::vector<std::string> verbs;
    for (const CLI::App* verb : app.get_subcommands([](const CLI::App*) { return true; }))
      verbs.push_back(verb->get_name());
    if (std::find(verbs.begin(), verbs.end(), argv[1]) == verbs.end()) {
      std::string list;
      for (const std::string& verb : verbs) list += (list.empty() ? "" : ", ") + verb;
      return "xshade: unknown command '" + std::string(argv[1]) + "'" + did_you_mean(argv[1], verbs) +
             " (commands: " + list + "; xshade --help)";
    }
  }
  if (dynamic_cast<const CLI::ExtrasError*>(&error) == nullptr) return std::nullopt;
  const CLI::App* command = &app;
  for (const CLI::App* verb : app.get_subcommands()) command = verb;
  std::vector<std::string> options;
  for (const CLI::Option* option : command->get_options())
    for (const std::string& name : option->get_lnames()) options.push_back("--" + name);
  for (int i = 2; i < argc; ++i) {
    const std::string word = argv[i];
    if (!word.starts_with("--")) continue;
    const std::string name = word.substr(0, word.find('='));
    if (std::find(options.begin(), options.end(), name) != options.end()) continue;
    return "xshade " + command->get_name() + ": unknown option '" + name + "'" + did_you_mean(name, options) +
           " (xshade " + command->get_name() + " --help)";
  }
  return std::nullopt;
}

}  // namespace

// Everything the command line does; main() below stands guard over it.
static int run_command_line(int argc, char** argv) {
  using namespace xshade::cli;
  CLI::App app{
      "xshade: author a shader once, render it on OpenGL and Vulkan, diff the images.\n"
      "Exit codes: 0 pass, 1 a check failed, 2 bad input or usage, 3 backend or internal error; run and bless stopped "
      "by a signal (^C) exit 128 + it, their workers and temporary files removed.\n"
      "Each xshade process may take half the machine's memory as address space (XSHADE_MEMORY_LIMIT=GiB sets another, "
      "0 none): past it an allocation fails with exit 3.",
      "xshade"};
  app.require_subcommand(1);
  app.set_version_flag("--version", std::string("xshade ") + XSHADE_VERSION);

  // Each verb registers its own options (in its own file), in the order --help lists them.
  const std::vector<Verb> verbs = {add_info_command(app),      add_run_command(app),     add_watch_command(app),
                                   add_bless_command(app),     add_compile_command(app), add_eval_command(app),
                                   add_worker_command(app),    add_report_command(app),  add_diff_command(app),
                                   add_stability_command(app), add_accuracy_command(app)};

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& error) {
    if (auto message = misspelling(app, error, argc, argv)) {
      std::fprintf(stderr, "%s\n", message->c_str());
      return kBadInput;
    }
    const int code = app.exit(error);
    return code == 0 ? kPass : kBadInput;
  }
  std::string command_line;  // what run, report merge and the studies record of how they were started
  for (int i = 0; i < argc; ++i) command_line += (i ? " " : "") + std::string(argv[i]);
  for (const Verb& verb : verbs)
    if (*verb.command) return verb.run(command_line);
  return kBadInput;
}

int main(int argc, char** argv) {
  const std::string verb = argc > 1 && argv[1][0] != '-' ? std::string(argv[1]) : std::string();
  // Workers are forked only while xshade runs no thread of its own (scene_workers() counts again
  // once it has loaded the image library for them).
  xshade::remember_startup_threads();
  xshade::keep_freed_heap();
  if (auto limited = xshade::cli::limit_memory(std::getenv("XSHADE_MEMORY_LIMIT")); !limited) {
    std::fprintf(stderr, "xshade: %s\n", limited.error().message.c_str());
    return xshade::cli::kBadInput;
  }
  return xshade::cli::guarded_verb(verb, [&] { return run_command_line(argc, argv); });
}
