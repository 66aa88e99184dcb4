#include "cli/command_options.h"

#include <string>

namespace xshade::cli {

void add_gl_platform_option(CLI::App& command, std::string& platform) {
  command
      .add_option("--gl-platform", platform,
                  "How the gl lane gets its OpenGL context: osmesa, egl (surfaceless; the only route on Mesa "
                  "25.1 and later), or auto (OSMesa when its library opens, else EGL)")
      ->check(CLI::IsMember({"auto", "osmesa", "egl"}))
      ->capture_default_str();
}

void add_lane_options(CLI::App& command, LaneSelection& selection) {
  // One lane per --lane (repeat it, or list them with commas): a bare word after it is a scene name.
  command
      .add_option("--lane", selection.lanes,
                  "Only these lanes (gl, vk, vk-hlsl): --lane gl,vk or --lane gl --lane vk; default: all")
      ->type_name("LANE")
      ->allow_extra_args(false)
      ->delimiter(',');
  command.add_flag("--vk-validation", selection.validation,
                   "Enable the Vulkan validation layer (when installed); any message fails the run");
  add_gl_platform_option(command, selection.gl_platform);
}

// How many renders run at once, and how long each may take (cli/workers.h).
void add_worker_options(CLI::App& command, WorkerLimits& limits, const char* what) {
  command
      .add_option("-j,--jobs", limits.jobs,
                  std::string("Render up to N ") + what +
                      " at once, each in a worker process (default: one per core); "
                      "results do not depend on N")
      ->type_name("N")
      ->check(CLI::Range(1, 256));
  command
      .add_option("--timeout", limits.timeout_seconds,
                  std::string("Stop a ") + (what[0] == 'l' ? "lane's render" : "scene's render on a lane") +
                      " after SECONDS and fail it (default: 120; a scene may set its own with a reason)")
      ->type_name("SECONDS")
      ->check(CLI::Range(0.1, 86400.0));
}

// The folders of run and bless (cli/folders.h).
void add_folder_options(CLI::App& command, FolderOptions& folders) {
  command
      .add_option("--scenes", folders.scenes,
                  "Folder of scene files (default: the project file's, else xshade's own fixed scenes)")
      ->type_name("DIR");
  command
      .add_option("--golden", folders.golden,
                  "Folder of golden images and MANIFEST.toml (default: the project file's, else xshade's own "
                  "goldens, which serve only xshade's own scenes)")
      ->type_name("DIR");
  command
      .add_option("--shaders", folders.shaders,
                  "A folder of shaders (materials/, post/, include/), searched before xshade's shader library; "
                  "repeat for more (default: the project file's)")
      ->type_name("DIR")
      ->allow_extra_args(false);
  command
      .add_option("--project", folders.project,
                  "The project file (default: xshade.toml in the working folder or above it, up to the "
                  "repository's root)")
      ->type_name("FILE");
  command.add_flag("--no-project", folders.no_project, "Read no project file");
}

}  // namespace xshade::cli
