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

void add_gl_platform_option(CLI::App& command, std::string& platform) {
  command
      .add_option("--gl-platform", platform,
                  "How the gl lane gets its OpenGL context: osmesa, egl (surfaceless; the only route on Mesa "
                  "25.1 and later), or auto (OSMesa when its library opens, else EGL)")
      ->check(CLI::IsMember({"auto", "osmesa", "egl"}))
      ->capture_default_str();
}

void add_lane_options(CLI::App& command, xshade::cli::LaneSelection& selection) {
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
void add_worker_options(CLI::App& command, xshade::cli::WorkerLimits& limits, const char* what) {
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
void add_folder_options(CLI::App& command, xshade::cli::FolderOptions& folders) {
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

  LaneSelection info_selection;
  CLI::App* info = app.add_subcommand(
      "info",
      "Print each lane's driver (route, renderer, API, Mesa and LLVM versions) and the folders a run here "
      "would use (the project file's, xshade's own)");
  add_lane_options(*info, info_selection);

  RunOptions run_options;
  CLI::App* run =
      app.add_subcommand("run", "Render scenes on each of their lanes, write PNG and EXR images, compare the lanes");
  run->add_option("scene", run_options.scenes, "Scene names (in --scenes) or .toml files; default: every scene")
      ->type_name("SCENE");
  add_lane_options(*run, run_options.selection);
  run->add_option("--report", run_options.report_dir, "Folder for images and the report")
      ->type_name("DIR")
      ->capture_default_str();
  add_folder_options(*run, run_options.folders);
  run->add_option("--cache", run_options.cache_dir,
                  "Compiled-shader cache (default: $XSHADE_CACHE_DIR, else $XDG_CACHE_HOME/xshade or ~/.cache/xshade)")
      ->type_name("DIR");
  run->add_flag("--no-cache", run_options.no_cache, "Compile every shader, read and write no cache");
  run->add_option("--precision", run_options.precision,
                  "half: round every half/min16float/fixed result to fp16 on gl and vk (vk-hlsl is skipped); "
                  "goldens are fp32 renders and are not compared")
      ->check(CLI::IsMember({"float", "half"}))
      ->capture_default_str();
  run->add_option("--shard", run_options.shard, "Run every N-th scene from the i-th (name order), for CI matrices")
      ->type_name("i/N");
  run->add_flag("--trace-nonfinite", run_options.trace_nonfinite,
                "Render every gl and vk lane again with the tracing variant and report where its NaN, Inf and negative "
                "values were born (without it, only lanes whose images have them are traced)");
  run->add_flag("--pass-images", run_options.pass_images,
                "Also write every pass's own output as REPORT/SCENE/passes/PASS.LANE.exr, to find where lanes part");
  add_worker_options(*run, run_options.workers, "scene-and-lane renders");
  run->add_flag("--plan", run_options.plan_only,
                "Print each scene's plan (variants to compile or found in the cache, passes, what is left out) "
                "and render nothing");

  BlessOptions bless_options;
  CLI::App* bless = app.add_subcommand(
      "bless", "Render a scene and accept it as its golden (the common one from lanes that agree, or one lane's)");
  bless->add_option("scene", bless_options.scene, "Scene name (in --scenes) or .toml file")
      ->required()
      ->type_name("SCENE");
  bless->add_option("--lane", bless_options.lane, "Bless this lane's own golden (needs a reason it differs)")
      ->check(CLI::IsMember({"gl", "vk", "vk-hlsl"}))
      ->type_name("LANE");
  add_gl_platform_option(*bless, bless_options.gl_platform);
  bless->add_option("--reason", bless_options.reason, "Why this image is right (recorded in golden/MANIFEST.toml)")
      ->required()
      ->type_name("TEXT");
  add_folder_options(*bless, bless_options.folders);
  bless->add_option("--cache", bless_options.cache_dir, "Compiled-shader cache (as for run)")->type_name("DIR");
  bless->add_option("--report", bless_options.report_dir, "Folder for the rendered images")
      ->type_name("DIR")
      ->capture_default_str();
  add_worker_options(*bless, bless_options.workers, "lanes");

  CompileOptions compile_options;
  CLI::App* compile =
      app.add_subcommand("compile", "Compile one shader to GLSL (gl, vk), SPIR-V (spirv, vk-hlsl) or reflection");
  compile->footer(
      "Every output is validated before it is written: gl's GLSL by glslang as OpenGL GLSL 4.50 core, vk's as Vulkan "
      "GLSL, the SPIR-V of spirv and vk-hlsl by spirv-val. Exit 0: the output, valid. Exit 2: the shader is wrong, or "
      "the target cannot express it. Exit 3: a validator refused xshade's own output, an internal error: the output is "
      "not written, and the message gives the validator's words and the generated lines they name, for a bug report.");
  compile->add_option("file", compile_options.file, "The hlsl_like source")->required()->type_name("FILE");
  compile->add_option("-I", compile_options.include_dirs, "Search DIR for #include files")
      ->type_name("DIR")
      ->allow_extra_args(false);
  compile->add_option("-D", compile_options.defines, "Enable KEYWORD (a variant), or define KEY=VALUE")
      ->type_name("KEYWORD")
      ->allow_extra_args(false);
  compile->add_option("--target", compile_options.target, "gl, vk (GLSL text), spirv or vk-hlsl (SPIR-V)")
      ->check(CLI::IsMember({"gl", "vk", "spirv", "vk-hlsl"}))
      ->capture_default_str();
  compile
      ->add_option("--precision", compile_options.precision,
                   "half: round every half/min16float/fixed result to fp16 (gl, vk, spirv; vk-hlsl cannot)")
      ->check(CLI::IsMember({"float", "half"}))
      ->capture_default_str();
  compile->add_flag("--trace-nonfinite", compile_options.trace_nonfinite,
                    "Emit the fragment stage's tracing variant, which records where each pixel's first NaN or infinity "
                    "is born (gl, vk, spirv; docs/stability.md)");
  compile->add_flag("--reflect", compile_options.reflect, "Print the reflection (JSON) instead of code");
  compile
      ->add_option(
          "--entry", compile_options.entry,
          "Compile this fragment function as a full-screen pass (as eval runs it), whatever #pragma fragment says")
      ->type_name("FUNCTION");
  compile
      ->add_option("--pass", compile_options.pass,
                   "Compile this post pass of the effect (its #pragma pass name), or this pass of a Unity .shader "
                   "(its index or Name; default: every pass with a program)")
      ->type_name("NAME");
  compile
      ->add_option("--unity-platform", compile_options.unity_platform,
                   "Compile a Unity .shader for this platform, as a scene's [unity] platform does: glcore (default), "
                   "d3d11 or vulkan")
      ->check(CLI::IsMember({"glcore", "d3d11", "vulkan"}))
      ->type_name("PLATFORM");
  compile->add_flag("--generated", compile_options.generated,
                    "Print each pass's HLSL as a Unity .shader composes it (its include blocks, and a surface shader's "
                    "generated passes, with #line back to the .shader's lines) instead of compiling it");
  compile->add_flag("--all-variants", compile_options.all_variants,
                    "Compile every keyword combination the file declares for --target and report each; exit 2 if any "
                    "fails, 3 if any output is invalid (an internal error)");
  compile
      ->add_option("--shaders", compile_options.folders.shaders,
                   "A shader folder to include from and find FILE in, before xshade's library; repeat for more "
                   "(default: the project file's)")
      ->type_name("DIR")
      ->allow_extra_args(false);
  compile
      ->add_option("--project", compile_options.folders.project,
                   "The project file (default: xshade.toml here or above)")
      ->type_name("FILE");
  compile->add_flag("--no-project", compile_options.folders.no_project, "Read no project file");
  compile
      ->add_option(
          "-o", compile_options.output,
          "Write OUT.vert.glsl / OUT.frag.glsl (or .spv, or OUT.json) instead of standard output; each pass of a "
          ".shader to OUT.passN.vert.glsl / OUT.passN.frag.glsl")
      ->type_name("OUT");

  EvalOptions eval_options;
  CLI::App* eval = app.add_subcommand(
      "eval", "Run fragment shaders as full-screen passes on each lane, write EXR images, compare the lanes");
  eval->add_option("file", eval_options.files,
                   "The hlsl_like sources, each evaluated on its own with these options (with several, each one's "
                   "lines come between `== FILE` and `== FILE: exit CODE`, and the exit code is the worst)")
      ->required()
      ->type_name("FILE");
  eval->add_option("--entry", eval_options.entry, "The fragment function (default: #pragma fragment)")
      ->type_name("NAME");
  eval->add_option("--size", eval_options.size, "Image size")->type_name("WxH")->capture_default_str();
  eval->add_option("--precision", eval_options.precision,
                   "half: round every half/min16float/fixed result to fp16 (gl and vk lanes; vk-hlsl cannot)")
      ->check(CLI::IsMember({"float", "half"}))
      ->capture_default_str();
  add_gl_platform_option(*eval, eval_options.selection.gl_platform);
  eval->add_option("--lane", eval_options.selection.lanes,
                   "gl, vk, vk-hlsl or all (default: all); --lane gl,vk for two")
      ->type_name("LANE")
      ->allow_extra_args(false)
      ->delimiter(',');
  eval->add_option("-I", eval_options.include_dirs, "Search DIR for #include files")
      ->type_name("DIR")
      ->allow_extra_args(false);
  eval->add_option("-D", eval_options.keywords, "Enable KEYWORD")->type_name("KEYWORD")->allow_extra_args(false);
  eval->add_option("-o", eval_options.output_dir, "Folder for the EXR images")->type_name("DIR")->capture_default_str();
  eval->add_option(
          "--seed", eval_options.seed,
          "Fill every constant buffer, texture and read-only buffer from seed N (values in ranges shaders mean, "
          "noise of each texture's declared shape) instead of the defaults and a white texel; a shader that "
          "reads a buffer needs it")
      ->type_name("N");
  eval->add_option(
          "--specialize", eval_options.specializations,
          "Give the [[vk::constant_id]] constant NAME the value VALUE (a specialization constant on the Vulkan "
          "lanes, the constant's value in the GLSL on gl); repeat for more")
      ->type_name("NAME=VALUE")
      ->allow_extra_args(false);
  eval->add_flag("--trace-nonfinite", eval_options.trace_nonfinite,
                 "Render the tracing variant too (gl, vk) and print the source line where each pixel's first NaN, Inf "
                 "(or negative output) was born, with a map of them as <file>.<lane>.origins.png");
  eval->add_flag(
      "--allow-nonfinite", eval_options.allow_non_finite,
      "NaN, Inf and negative output values are expected (a test of a hazard): print their counts, do not fail");
  eval->add_flag("--no-images{false}", eval_options.write_images,
                 "Compare the lanes and print, write no image (for scripts that read the comparisons: the image "
                 "library is then never loaded, a third of a second saved)");
  add_worker_options(*eval, eval_options.workers, "lanes");
  eval->add_flag("--in-worker", eval_options.in_worker)->group("");  // eval's own workers (cli/workers.h)

  // Started by run, bless and eval for each render (cli/worker_command.cpp); not in --help.
  WorkerOptions worker_options;
  CLI::App* worker = app.add_subcommand("worker", "One lane of one scene, for the run that started it");
  worker->group("");
  worker->add_option("--scene", worker_options.scene);
  worker->add_option("--lane", worker_options.lane);
  worker->add_option("--result", worker_options.result_dir);
  worker->add_flag("--serve", worker_options.serve);
  worker->add_option("--shader-folder", worker_options.shader_folders)->allow_extra_args(false);
  worker->add_option("--golden", worker_options.golden);
  worker->add_option("--report", worker_options.report_dir)->required();
  worker->add_option("--cache", worker_options.cache_dir);
  worker->add_option("--gl-platform", worker_options.gl_platform);
  worker->add_flag("--vk-validation", worker_options.validation);
  worker->add_flag("--pass-images", worker_options.pass_images);
  worker->add_flag("--half-emulation", worker_options.half_emulation);
  worker->add_flag("--trace-nonfinite", worker_options.trace_nonfinite);

  ReportMergeOptions merge_options;
  CLI::App* report = app.add_subcommand("report", "Work on reports that runs wrote");
  report->require_subcommand(1);
  CLI::App* merge = report->add_subcommand(
      "merge",
      "Merge the reports of several runs (the shards of a CI matrix, a CTest run's per-test folders) into "
      "one index, junit.xml and results.json");
  merge
      ->add_option("report", merge_options.folders,
                   "A report folder (it holds results.json), or a folder of them (each of its folders that holds one)")
      ->required()
      ->type_name("DIR");
  merge->add_option("--out", merge_options.out, "Folder for the merged report")->required()->type_name("DIR");
  merge->add_flag("--cross-lane", merge_options.cross_lane,
                  "Hold the lanes of each scene whose lanes came from separate runs (one per lane, as CTest's tests) "
                  "against each other, as one run of all of them would");
  merge->add_flag("--exit-code", merge_options.exit_code,
                  "Exit with the merged results' code, as xshade run would (default: 0 once the report is written)");

  DiffOptions diff_options;
  CLI::App* diff = app.add_subcommand(
      "diff",
      "Hold image B against image A (PNG, EXR, HDR) with the layers a run uses on a golden: exit 0 pass, 1 "
      "fail, 2 an image that does not read");
  diff->add_option("a", diff_options.a, "The reference image (a golden)")->required()->type_name("A");
  diff->add_option("b", diff_options.b, "The image under test")->required()->type_name("B");
  diff->add_option("--tolerance", diff_options.tolerance, "Steps of 8-bit sRGB a channel may differ")
      ->type_name("STEPS")
      ->check(CLI::Range(0, 255))
      ->capture_default_str();
  diff->add_option("--budget", diff_options.budget, "Fraction of the pixels that may fail, 0 to 1")
      ->type_name("FRACTION")
      ->check(CLI::Range(0.0, 1.0))
      ->capture_default_str();
  diff->add_option("--radius", diff_options.radius,
                   "A failing pixel passes when A has a matching pixel this near (an edge that moved)")
      ->type_name("PIXELS")
      ->check(CLI::Range(0, 8))
      ->capture_default_str();
  diff->add_option("--float-tolerance", diff_options.float_tolerance, "Relative error allowed a value above 1")
      ->type_name("RELATIVE")
      ->check(CLI::Range(0.0, 1.0))
      ->capture_default_str();
  diff->add_option("--heat-map", diff_options.heat_map, "Write the difference's heat map (PNG) here")
      ->type_name("FILE");
  diff->add_option("--mask", diff_options.mask, "Write the failing pixels' mask (PNG, white where failing) here")
      ->type_name("FILE");
  diff->add_flag("--json", diff_options.json, "Print the verdict, layers and metrics as JSON");

  StabilityOptions stability_options;
  CLI::App* stability = app.add_subcommand(
      "stability",
      "Run the library's shader code on the hard numeric cases of SHADERS.md section 5 and check each "
      "case's property on every lane, in fp32 and in fp16 emulation");
  stability->add_option("case", stability_options.cases, "Case ids (see --list); default: every case")
      ->type_name("CASE");
  add_lane_options(*stability, stability_options.selection);
  stability
      ->add_option("--precision", stability_options.precision,
                   "float, half (fp16 emulation on gl and vk; vk-hlsl cannot) or all")
      ->check(CLI::IsMember({"float", "half", "all"}))
      ->capture_default_str();
  stability->add_flag("--list", stability_options.list, "Print the cases with their forms and run nothing");
  stability
      ->add_option("--markdown", stability_options.markdown,
                   "Write the results as Markdown (docs/stability.md is this output)")
      ->type_name("FILE");
  stability->add_option("--shaders", stability_options.shaders_dir, "The shader library (default: xshade's own)")
      ->type_name("DIR");
  stability->add_option("--probes", stability_options.probes_dir, "The suite's probe shaders (default: xshade's own)")
      ->type_name("DIR");
  stability
      ->add_option("--scenes", stability_options.scenes_dir,
                   "Folder of the scenes the suite renders (default: xshade's own fixed scenes)")
      ->type_name("DIR");

  AccuracyOptions accuracy_options;
  CLI::App* accuracy = app.add_subcommand(
      "accuracy",
      "For each accuracy knob (DoF kernel, BRDF forms, precision, indirect specular, supersampling, "
      "shadow-map resolution), render its scene in every configuration on each lane and measure error "
      "against a reference and time; tables and Pareto charts");
  accuracy
      ->add_option("study", accuracy_options.studies,
                   "Study ids (dof_kernel, brdf_forms, precision, indirect_specular, supersampling, shadow_map); "
                   "default: all but shadow_map, whose scene of Unity shaders needs --scenes and --shader-folder")
      ->type_name("STUDY");
  add_lane_options(*accuracy, accuracy_options.selection);
  accuracy->add_flag("--quick", accuracy_options.quick,
                     "One round of timing, no reference check, and only the quick studies");
  accuracy
      ->add_option("--rounds", accuracy_options.rounds,
                   "Rounds of timing: the configurations take turns, each turn 1 warm-up frame and 3 timed frames")
      ->check(CLI::Range(1, 100))
      ->capture_default_str();
  accuracy->add_option("--report", accuracy_options.report_dir, "Folder for index.html, accuracy.csv and charts/")
      ->type_name("DIR")
      ->capture_default_str();
  accuracy
      ->add_option("--markdown", accuracy_options.markdown,
                   "Also write the tables as Markdown, with the charts in a folder beside it named after it "
                   "(docs/accuracy.md is this output)")
      ->type_name("FILE");
  accuracy
      ->add_option("--scenes", accuracy_options.scenes_dir,
                   "Folder of the studies' scenes (default: xshade's own fixed scenes)")
      ->type_name("DIR");
  accuracy->add_option("--shaders", accuracy_options.shaders_dir, "The shader library (default: xshade's own)")
      ->type_name("DIR");
  accuracy
      ->add_option("--shader-folder", accuracy_options.shader_folders,
                   "A shader folder searched before the library; repeat for more (a study of Unity shaders, named "
                   "on the command line, needs its .shader files and Unity's include files)")
      ->type_name("DIR")
      ->allow_extra_args(false);

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
  if (*info) return run_info(info_selection);
  if (*run) {
    for (int i = 0; i < argc; ++i) run_options.command_line += (i ? " " : "") + std::string(argv[i]);
    return run_run(run_options);
  }
  if (*bless) return run_bless(bless_options);
  if (*compile) return run_compile(compile_options);
  if (*eval) return run_eval(eval_options);
  if (*worker) return run_worker(worker_options);
  if (*merge) {
    for (int i = 0; i < argc; ++i) merge_options.command_line += (i ? " " : "") + std::string(argv[i]);
    return run_report_merge(merge_options);
  }
  if (*diff) return run_diff(diff_options);
  if (*accuracy) {
    for (int i = 0; i < argc; ++i) accuracy_options.command_line += (i ? " " : "") + std::string(argv[i]);
    return run_accuracy(accuracy_options);
  }
  if (*stability) {
    for (int i = 0; i < argc; ++i) stability_options.command_line += (i ? " " : "") + std::string(argv[i]);
    return run_stability(stability_options);
  }
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
