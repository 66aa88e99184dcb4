// How the Vulkan lane's driver is loaded: once a process, the loader seeing lavapipe alone
// (unless the user chose drivers: the lane ignores every GPU anyway, and loading each installed
// driver, two of them with their own LLVM, cost some 25 ms an instance), and the loader and
// lavapipe staying loaded after a backend lets them go: a worker makes a backend for every scene
// it renders, and the loader unloaded both at each instance's end, to load and relocate them
// again for the next.
#pragma once

namespace xshade::harness {

// Called before each backend's loader starts; does its work the first time. The manifest is named
// (VK_DRIVER_FILES) rather than selected by a pattern, which makes the loader warn, through the
// validation layer's messenger, about each driver it leaves out.
void keep_lavapipe_loaded();

}  // namespace xshade::harness
