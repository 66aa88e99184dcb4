#!/usr/bin/env python3
"""The gates proven to fail: apply each wrong change to a gate's code, one at a time, rebuild, run
the tests that should catch it, and report each change that no test caught.

A gate that a wrong change leaves green checks nothing. Each mutation below is the smallest edit
that breaks one gate (a comparison made against itself, a check turned off, a message printed
where it is false); its `tests` are the CTest regex expected to catch it. The source is restored
after each mutation, also when the script is interrupted.

usage: run_mutations.py [--build DIR] [--only NAME] [--full]
  --build DIR  the configured build folder (default: build)
  --only NAME  run only the mutations whose name contains NAME
  --full       run the whole suite for each mutation instead of its tests (slow: minutes each)

Not part of CI: it rebuilds once per mutation. Exit 0 when every mutation was caught, 1 otherwise.
"""
import argparse
import os
import subprocess
import sys
import time

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))

# (name, file, text as it is, text as the mutation makes it, tests that must catch it)
MUTATIONS = [
    # The gates issue 17 lists as unguarded before.
    ('cross-lane compares a lane with itself', 'harness/gate/scene_check.cpp',
     'pairs.push_back({first_lane, lane, compare_images(image, first, settings)})',
     'pairs.push_back({first_lane, lane, compare_images(image, image, settings)})', 'CrossLane'),
    ('determinism always passes', 'harness/gate/scene_check.cpp',
     'if (bitwise_equal(first, second)) return', 'if (true) return', 'Determinism'),
    ('bless accepts lanes that disagree', 'harness/gate/scene_check.cpp',
     '    if (pair.verdict != Verdict::Pass)\n      return BlessRefusal',
     '    if (false)\n      return BlessRefusal', 'Bless\\.'),
    ('bless takes a blank reason on the command line', 'cli/bless_command.cpp',
     'if (blank(options.reason)) {', 'if (blank(options.reason) && false) {', 'Gating.BlessRefuses'),
    ("the cache key leaves out the shader's own file", 'harness/render/shader_cache.cpp',
     '  for (const fs::path& path : dependencies) {\n    const std::optional<std::string> contents',
     '  for (const fs::path& path : std::vector<fs::path>(dependencies.begin() + 1, dependencies.end())) {\n'
     '    const std::optional<std::string> contents', 'ShaderCacheTest'),
    ('vector integer quotients take the wrong sign', 'glsl/intrinsic_mapping.cpp',
     'return mix(q, -q, notEqual(lessThan(a, ', 'return mix(q, -q, equal(lessThan(a, ', 'Conformance.*int_div_mod'),
    ('an effect in the chain is said not to be', 'harness/render/planner.cpp',
     '    if (!used_combinations.count(effect))\n      plan.left_out',
     '    if (true)\n      plan.left_out', 'Planner'),
    # One per check this issue added.
    ('a property the material lacks is accepted', 'harness/render/scene_contract.cpp',
     '    error(problems, where,\n          fmt::format("{} has no property',
     '    if (false) error(problems, where,\n          fmt::format("{} has no property', 'SceneContract|UserMistakes'),
    ('an undeclared keyword is accepted', 'harness/render/scene_contract.cpp',
     'if (std::find(declared.begin(), declared.end(), keyword) != declared.end()) continue;', 'continue;',
     'SceneContract|UserMistakes'),
    ('a value of the wrong size is accepted', 'harness/render/scene_contract.cpp',
     '  if (member.components() != count)', '  if (false)', 'SceneContract|UserMistakes'),
    ('a texture with no source and no default is accepted', 'harness/render/scene_contract.cpp',
     '  error(problems, where,\n        fmt::format("{} samples', '  if (false) error(problems, where,\n        fmt::format("{} samples',
     'SceneContract'),
    ("a user's mistake in a render is a crash", 'harness/gate/scene_check.cpp',
     'return error.kind == ErrorKind::UserInput ? Verdict::Error : Verdict::Crash;',
     'return error.kind == ErrorKind::UserInput ? Verdict::Crash : Verdict::Crash;',
     'UserMistakes'),
    ('a golden of another size is compared', 'harness/gate/scene_check.cpp',
     '} else if ((*golden)->image.width != image.width || (*golden)->image.height != image.height) {',
     '} else if (false) {',
     'UserMistakes.AGoldenOfAnotherSize'),
    ('an empty shard passes', 'cli/run_command.cpp', '    if (mine.empty()) {', '    if (false) {',
     'UserMistakes.AShard'),
    ('a missing golden folder is accepted', 'cli/folders.cpp', 'if (golden == GoldenUse::Read && !fs::is_directory',
     'if (false && !fs::is_directory', 'UserMistakes.AFolder'),
    ('eval passes NaN output', 'cli/eval_command.cpp',
     'if (!options.allow_non_finite) result = std::max<int>(result, kTestFailed);', '',
     'CommandLine.EvalFails'),
    ('bless writes a lane golden equal to the common one', 'cli/bless_command.cpp',
     'if (comparison.verdict == harness::Verdict::Pass) {', 'if (false) {', 'UserMistakes.ALaneGolden'),
    ('a 16-bit PNG is read as linear', 'harness/image/image_io.cpp',
     'return integer && colour && srgb ? srgb_to_linear(pixels[i]) : pixels[i];',
     'return integer && colour && srgb && false ? srgb_to_linear(pixels[i]) : pixels[i];',
     'UserMistakes.ASixteenBit'),
    ("an earlier run's pages are kept", 'harness/report/report.cpp', '  remove_stale(report_dir, files);',
     '  if (false) remove_stale(report_dir, files);',
     'UserMistakes.ARunReplaces'),
    ('a value above 1 may change without limit', 'harness/image/image_compare.cpp',
     'failed = failed || relative > tolerance;', 'failed = failed || (relative > tolerance && false);',
     'CompareImages|UserMistakes.AValueAboveOne'),
    ("the golden's float image is not what is compared", 'harness/gate/golden_store.cpp',
     'Result<FloatImage> image = read_image(has_float ? float_path : path);',
     'Result<FloatImage> image = read_image(has_float ? path : path);', 'GoldenStore|Gating.AnUnchanged'),
    ("the summary's worst is not in the per-pixel layer's steps", 'harness/image/image_compare.cpp',
     'metrics.max_steps = pass.worst_steps;', 'metrics.max_steps = uint32_t(metrics.max_difference * 255.0);',
     'CompareImages|UserMistakes.ABless'),
    ('bless writes the manifest without the golden folder\'s lock', 'harness/gate/golden_store.cpp',
     '  Result<GoldenLock> lock = GoldenLock::acquire(folder_, GoldenLock::Mode::Exclusive, on_wait_);\n'
     '  if (!lock) return fail(lock.error());\n  if (auto recovered',
     '  if (auto recovered', 'BlessCommit.TwoBlesses'),
    ('a misspelt verb gets no suggestion', 'cli/main.cpp',
     'return near ? "; did you mean \'" + *near + "\'?" : std::string();', 'return near ? std::string() : std::string();',
     'CommandLine.Version'),
    # run's --lane (eval's has the same two lines: the text must be found once).
    ('--lane takes no comma list', 'cli/command_options.cpp', 'default: all")\n      ->type_name("LANE")\n      ->allow_extra_args(false)\n      ->delimiter(\',\');',
     'default: all")\n      ->type_name("LANE")\n      ->allow_extra_args(false);', 'UserMistakes.LanesAre'),
    ('a compile error shows no caret', 'base/diagnostic.cpp',
     '    if (!diagnostic.excerpt.empty()) text += "\\n" + diagnostic.excerpt;', '',
     'UserMistakes.AVariantThatDoesNotCompile'),
    # The gates no test guarded, and one per check that nothing is passed that was not checked.
    ('lanes that disagree leave the scene passing', 'harness/gate/scene_check.cpp',
     '  for (const CrossLaneResult& pair : result.cross_lane) result.verdict = worst(result.verdict, pair.verdict);\n}',
     '}', 'BlessCommit.LanesThatDisagree'),
    ('an edited float golden is believed', 'harness/gate/golden_store.cpp',
     '      if (Result<void> same = check_hash(float_path, *entry, entry->float_hash, bless_command(scene, own)); !same)\n'
     '        return fail(same.error());\n', '', 'BlessCommit.AnEditedFloatGolden'),
    ('diff of images of different sizes passes', 'cli/diff_command.cpp',
     'return comparison.verdict == harness::Verdict::Pass ? kPass : kTestFailed;',
     'return comparison.verdict == harness::Verdict::Pass || !same_size ? kPass : kTestFailed;',
     'HostileInput.DiffOfImages'),
    ('an xshade.toml that is not a file is passed over', 'harness/scene/project_file.cpp',
     'if (const std::string kind = not_a_file(candidate); !kind.empty())',
     'if (const std::string kind = not_a_file(candidate); false)', 'ProjectFileTest|HostileInput.AnXshadeToml'),
    ('a cache folder others can write is used', 'base/file_io.cpp',
     '  if (status.st_mode & (S_IWGRP | S_IWOTH))', '  if (false)', 'FileIo|HostileInput.ACacheFolder'),
    ('two runs write one report folder at once', 'harness/report/report_lock.cpp',
     'if (::flock(fd, LOCK_EX | LOCK_NB) != 0) {', 'if (false) {', 'ReportLock|HostileInput.ASecondRun'),
    ('a lane image merge cannot read leaves its checks out', 'harness/report/report_merge.cpp',
     '        if (!missing) continue;', '        if (!missing || true) continue;', 'ReportMerge'),
    ('a manifest past its entry limit is read', 'harness/gate/golden_manifest.cpp',
     '      if (manifest.entries.size() == kMaxManifestEntries)', '      if (false)', 'GoldenManifestTest'),
    ('a second manifest entry for one image is believed', 'harness/gate/golden_manifest.cpp',
     '  if (second != manifest.entries.end()) {', '  if (false) {', 'Manifests/GoldenManifestErrorTest'),
    ("a report encodes an image's float values for each page", 'harness/report/viewer_data.cpp',
     '      if (scripted && scripted->count(path)) {', '      if (false) {', 'WriteReports'),
    ("a page does not load an image's values another page wrote", 'harness/report/report_html.cpp',
     '  for (const ViewerPage::PixelScript& pixels : viewer.pixels)\n',
     '  for (const ViewerPage::PixelScript& pixels : viewer.pixels)\n    if (!pixels.script.empty())\n',
     'WriteReports'),
    ('a run stopped by a signal leaves its workers and folder', 'harness/gate/lane_workers.cpp',
     '    while (next_to_report_ < files_.size() && !interrupt_signal()) {',
     '    while (next_to_report_ < files_.size()) {',
     'Workers.ARunStoppedByASignal'),
    ("dead runs' worker folders are kept", 'harness/gate/lane_workers.cpp',
     '  ScratchFolder::remove_dead_runs();\n', '', 'Workers.ARunRemovesTheWorkersFolders'),
    ('a live run\'s worker folder is removed', 'harness/gate/lane_workers.cpp',
     '&& flock(fd, LOCK_EX | LOCK_NB) == 0)\n        fs::remove_all', ')\n        fs::remove_all',
     'Workers.ARunRemovesTheWorkersFolders'),
    ('a mesh is read unchecked', 'harness/assets/obj_mesh.cpp',
     '  auto text = read_input_file(path, kMaxObjFileBytes, "the OBJ mesh");',
     '  auto text = Result<std::string>(read_file(path).value_or(""));', 'LoadObj.AFifo'),
    ('an image that cannot be written is said to be', 'harness/image/image_io.cpp',
     '  return write_file_atomically(path, std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()));',
     '  (void)write_file_atomically(path, std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()));\n'
     '  return {};', 'HostileInput.AFullDisk'),
    ('the drivers\' cache stays on with a full disk', 'cli/folders.cpp',
     '    setenv("MESA_SHADER_CACHE_DISABLE", "true", 1);', '', 'HostileInput.AFullDisk'),
    ('a merge writes into a report folder in use', 'cli/report_command.cpp',
     '  auto lock = harness::ReportLock::take(options.out, options.command_line);\n  if (!lock) {',
     '  auto lock = harness::ReportLock::take(options.out, options.command_line);\n  if (false) {',
     'HostileInput.ASecondRun'),
    ('a shader source of any size is read', 'hlsl_like/source_manager.cpp',
     '  if (known_size && *known_size > kMaxSourceFileBytes)', '  if (false)', 'HostileInput.AShaderSourceOfGigabytes'),
    ("a damaged driver cache is believed", 'harness/render/driver_cache.cpp',
     '  return bytes && content_hash(*bytes) == recorded.hash;', '  return true;',
     'DriverCache.AnEntryDamaged'),
    ('no memory ceiling', 'cli/main.cpp',
     'xshade::cli::limit_memory(std::getenv("XSHADE_MEMORY_LIMIT"))', 'xshade::cli::limit_memory("0")',
     'HostileInput.XshadesOwnMemoryCeiling'),
    # A scene's Unity platform and its row order: each half of the conventions.
    ('a Unity scene\'s target is read back upside down', 'harness/render/scene_renderer.cpp',
     '    if (rows_bottom_first_) flip_rows(image);', '    if (false) flip_rows(image);',
     'UnityPlatform|ShaderPostEffect'),
    ('a GLCore scene of Unity\'s shaders keeps xshade\'s row order', 'harness/render/scene_renderer.cpp',
     'const RowOrigin row_origin_ = !direct3d_ && draws_unity_shader(scene_) ? RowOrigin::Bottom : RowOrigin::Top;',
     'const RowOrigin row_origin_ = false && draws_unity_shader(scene_) ? RowOrigin::Bottom : RowOrigin::Top;',
     'UnityPlatform|ShaderPostEffect'),
    ('Vulkan keeps the counter-clockwise front face with the rows mirrored', 'harness/vulkan/vk_support.cpp',
     'spec.rows_up ? vk::FrontFace::eClockwise : vk::FrontFace::eCounterClockwise',
     'vk::FrontFace::eCounterClockwise', 'BackendContract.*BottomRowOrigin'),
    ('a D3D11 target culls the faces its flip turned over', 'harness/render/unity_render_state.cpp',
     '  if (state.cull != CullMode::Off) state.cull', '  if (false) state.cull', 'UnityPlatform|ADirect3DRenderTarget'),
    ('reversed depth is linearised as forward depth', 'harness/render/renderer_inputs.cpp',
     'const float zx = direct3d ? far / near - 1.0f : 1.0f - far / near, zy = direct3d ? 1.0f : far / near;',
     'const float zx = 1.0f - far / near, zy = far / near;', 'UnityPlatform|Direct3DConventions'),
    # Surface shaders, lights and shadows.
    ("a surface shader's legacy lighting loses its SH ambient", 'shaderlab/surface_shader.cpp',
     'c.rgb += o.Albedo * IN.sh;', 'c.rgb += 0;', 'SurfaceShader'),
    ('a surface shader reads uv_MainTex as the texture MainTex', 'shaderlab/surface_shader.cpp',
     'name[prefix.size()] ==', "'_' !=", 'SurfaceShader|SurfaceProgram'),
    ('a written o.Normal is taken for a world-space one', 'harness/render/surface_program.cpp',
     'shape.writes_normal = function_writes(*function, output, "Normal");',
     'shape.writes_normal = function_writes(*function, output, "Normals");',
     'SurfaceProgram'),
    ('the main light is the first directional one, not the brightest', 'harness/render/forward_lights.cpp',
     '(!out.main || scene.lights[i].brightness() > scene.lights[*out.main].brightness())', '!out.main',
     'ForwardLights'),
    ("a point light's falloff leaves out Unity's constant", 'harness/render/forward_lights.cpp',
     'return fade / (1.0f + 25.0f * t);', 'return fade / (1.0f + t);', 'ForwardLights'),
    ('a ForwardAdd pass is drawn without its light', 'harness/render/planner.cpp',
     'for (size_t light : lights.pixel) passes.push_back({pass, light, false});', '',
     'Planner.AForwardAdd|realworld.unity_toon_point_light'),
    ('a shadow map is drawn though nothing receives it', 'harness/render/planner.cpp',
     'if (!receivers || !casters)', 'if (!casters)', 'Planner.AShadowMap'),
    ("the shadow map's depth is compared the wrong way", 'harness/render/scene_renderer.cpp',
     'AddressMode::ClampToEdge, CompareOp::LessEqual});', 'AddressMode::ClampToEdge, CompareOp::Greater});',
     'realworld.unity_toon_shadow|realworld.unity_standard_pbr_shadow'),
    ("a comparison filtered in the shader weighs its texels in the wrong order", 'glsl/intrinsic_mapping.cpp',
     'mix(compared.w, compared.z, f.x)', 'mix(compared.z, compared.w, f.x)',
     'FilteredComparison|realworld.unity_soft_shadows'),
    ("a soft shadow's map is read without filtering", 'harness/render/scene_renderer.cpp',
     'Light::Shadows::Soft ? Filter::Linear : Filter::Nearest', 'Light::Shadows::Soft ? Filter::Nearest : Filter::Nearest',
     'realworld.unity_soft_shadows'),
    # The lowerings (glsl/lower/): a decision gone wrong must show in what is drawn, not only in
    # the lowering's own test.
    ('half emulation leaves arithmetic unrounded', 'glsl/lower/half_emulation.cpp',
     'case ExprKind::Binary: return static_cast<const hlsl::BinaryExpr&>(e).op != hlsl::BinaryOp::Comma;',
     'case ExprKind::Binary: return false;', 'HalfEmulation'),
    ('the tracing variant tests no intrinsic result', 'glsl/lower/trace_sites.cpp',
     'if (call->call_kind == CallKind::Intrinsic || call->call_kind == CallKind::Method)', 'if (false)',
     'TraceSites|NonfiniteTrace|TraceVariant'),
    ("a read of a struct parameter's resource names the whole parameter", 'glsl/lower/flatten_resources.cpp',
     'return flattened_name(static_cast<const ParamDecl&>(*origin.root), origin.fields, names);',
     'return flattened_name(static_cast<const ParamDecl&>(*origin.root), {}, names);', 'FlattenResources|Resource'),
    # The perceptual metrics (harness/image/metric_layers.h).
    ("a scene's metric is measured but does not decide", 'harness/image/image_compare.cpp',
     '  else if (metric_verdict)\n', '  else if (false && metric_verdict)\n', 'CompareImages|Gating.AScenesMetric'),
    ("FLIP's features do not raise the colour difference", 'harness/image/flip.cpp',
     'values[p] = std::pow(colour, 1.0f - feature_difference);',
     'values[p] = std::pow(colour, 1.0f - 0.0f * feature_difference);', 'Flip|DiffMetric'),
    ("CIEDE2000 forgets the blue region's rotation", 'harness/image/delta_e.cpp',
     'return std::sqrt(l * l + c * c + h * h + rt * c * h);',
     'return std::sqrt(l * l + c * c + h * h + 0.0 * rt * c * h);', 'DeltaE'),
    ("half emulation leaves an increment unrounded", 'glsl/lower/half_emulation.cpp',
     '  return increments && e.operand && rounds(e.operand->type);', '  return false && increments;',
     'HalfEmulation'),
    # `xshade watch` (harness/live): a warm worker, and which scenes a save reaches.
    ("a warm worker keeps a module whose include changed", 'harness/render/variant_compiler.cpp',
     '  if (known != modules_.end() &&\n', '  if (false && known != modules_.end() &&\n', 'VariantCompiler'),
    ("a file reaches no scene that read it", 'harness/live/scene_reads.cpp',
     '[&](const fs::path& file) { return known->second.count(file) > 0; }',
     '[&](const fs::path& file) { return known->second.count(file) > 1; }', 'SceneReadIndex'),
    ("the plan's reads are lost when a source does not compile", 'harness/render/planner.cpp',
     '      files_read_->insert(*path);\n      if (source)\n',
     '      files_read_->insert(*path);\n      if (source && source->module->ok())\n', 'Planner'),
]


def run(cmd, cwd):
    started = time.time()
    p = subprocess.run(cmd, cwd=cwd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    return p.returncode, p.stdout, time.time() - started


def main():
    ap = argparse.ArgumentParser(description=__doc__.split('\n\n')[0])
    ap.add_argument('--build', default=os.path.join(ROOT, 'build'))
    ap.add_argument('--only', default='')
    ap.add_argument('--full', action='store_true')
    args = ap.parse_args()

    chosen = [m for m in MUTATIONS if args.only in m[0]]
    rows = []
    for index, (name, path, before, after, tests) in enumerate(chosen, 1):
        file = os.path.join(ROOT, path)
        original = open(file, encoding='utf-8').read()
        if original.count(before) != 1:
            rows.append((name, path, 'not applied: the text is not in the file once', ''))
            print('[%d/%d] %s: not applied' % (index, len(chosen), name), flush=True)
            continue
        try:
            open(file, 'w', encoding='utf-8').write(original.replace(before, after))
            code, out, _ = run(['cmake', '--build', args.build], ROOT)
            if code != 0:
                verdict, by = 'NOT RUN', 'the mutated source does not build; make the mutation compile'
            else:
                ctest = ['ctest', '--test-dir', args.build, '-j%d' % (os.cpu_count() or 2)]
                if not args.full:
                    ctest += ['-R', tests]
                code, out, secs = run(ctest, ROOT)
                failed = [l.split(' - ')[1].split(' (')[0] for l in out.splitlines() if ' - ' in l and '(Failed)' in l]
                if 'No tests were found' in out:
                    verdict, by = 'NOT CAUGHT', 'no test matches ' + tests
                elif code != 0:
                    verdict, by = 'caught', ', '.join(failed[:3]) + (' and %d more' % (len(failed) - 3) if len(failed) > 3 else '')
                else:
                    verdict, by = 'NOT CAUGHT', 'every test passed'
        finally:
            open(file, 'w', encoding='utf-8').write(original)
        rows.append((name, path, verdict, by))
        print('[%d/%d] %s: %s (%s)' % (index, len(chosen), name, verdict, by), flush=True)
    run(['cmake', '--build', args.build], ROOT)  # the build as the source is again

    print('\n| wrong change | file | caught | by |\n|---|---|---|---|')
    for name, path, verdict, by in rows:
        print('| %s | %s | %s | %s |' % (name, path, verdict, by))
    missed = [r for r in rows if r[2] != 'caught']
    print('\n%d of %d wrong changes caught' % (len(rows) - len(missed), len(rows)))
    return 1 if missed else 0


if __name__ == '__main__':
    sys.exit(main())
