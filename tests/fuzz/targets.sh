# The fuzz targets, by the reader each one fuzzes (the program is NAME_fuzzer, tests/fuzz/CMakeLists.txt):
# sourced by tests/fuzz/run, which fuzzes them, and tests/sanitizers/build, which builds them.
fuzz_targets=(front_end scene_file project_file golden_manifest image_file shaderlab)
