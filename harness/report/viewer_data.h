// What a scene page's image-diff viewer (viewer/viewer.js) reads: the scene as JSON, and the
// float values of its images as a script of their own. Pages are opened from file://, where a
// script cannot fetch a file or read back the pixels of an <img>, so the float images travel as
// deflated float32 in a classic script, pixels/PAGE.js, that the page loads beside itself.
#pragma once

#include <filesystem>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "harness/gate/run_results.h"

namespace xshade::harness {

struct ViewerPage {
  // The scene JSON for <script id="xshade-viewer-data" type="application/json">, with every '<'
  // written \u003c so that no text in it can end the element.
  std::string data_json;
  // The float images the viewer reads, by their path in the report (KEY), each a script of one
  // line, window.XSHADE_PIXELS[KEY] = {...}, that the report writes once as pixels/KEY.js however
  // many pages show the image. `script` is empty for an image an earlier page already carries.
  struct PixelScript {
    std::string image;
    std::string script;
  };
  std::vector<PixelScript> pixels;
};

// pixels/KEY.js, the file that carries the float values of the report's image at `image`.
std::string pixel_script_path(const std::string& image);

// Lanes whose rendered images are bit-identical, with the same golden and verdict, form one
// group, shown once ("gl = vk = vk-hlsl"). The float images are read from `report_dir` (each
// lane's image_exr, and its golden_exr, or its golden PNG decoded when the golden has no float
// image); an image that does not read, or of more than 2048 x 2048 pixels, is shown from its PNG
// alone.
// Cross-lane pairs are listed only where the images differ.
// `in_memory` holds images the caller already has, by their path in the report (a run has each
// lane's render): those are not read again. `scripted` holds the images whose script an earlier
// page of the same report made: they are not encoded again (merged reports can name one image
// from thousands of scenes); the images this page scripts are added to it.
ViewerPage viewer_page(const SceneResult& scene, const std::filesystem::path& report_dir,
                       const std::map<std::string, const FloatImage*>& in_memory = {},
                       std::set<std::string>* scripted = nullptr);

}  // namespace xshade::harness
