// Options several verbs share, each registered by the verb that takes it (commands.h's add_*_command).
#pragma once

#include <CLI/CLI.hpp>

#include <string>

#include "cli/commands.h"

namespace xshade::cli {

// --gl-platform: how the gl lane gets its OpenGL context.
void add_gl_platform_option(CLI::App& command, std::string& platform);
// --lane, --vk-validation and --gl-platform.
void add_lane_options(CLI::App& command, LaneSelection& selection);
// How many renders run at once, and how long each may take (cli/workers.h): -j, --timeout.
void add_worker_options(CLI::App& command, WorkerLimits& limits, const char* what);
// The folders of run and bless (cli/folders.h): --scenes, --golden, --shaders, --project, --no-project.
void add_folder_options(CLI::App& command, FolderOptions& folders);

}  // namespace xshade::cli
