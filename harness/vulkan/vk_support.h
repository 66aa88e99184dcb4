// Private helpers of the lavapipe backend: resources owned by vk::raii, layout tracking with
// synchronization2 barriers, the debug-utils message log, and the bits of SPIR-V reflection the
// backend needs for clear errors. Not part of the harness interface.
#pragma once

#include <cstddef>
#include <cstdint>
#include <map>
#include <mutex>
#include <optional>
#include <set>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include <vulkan/vulkan_raii.hpp>

#include "harness/backend/backend.h"

namespace xshade::harness::vk_support {

inline constexpr const char* kValidationLayer = "VK_LAYER_KHRONOS_validation";

// ---- SPIR-V ------------------------------------------------------------------------------------

struct EntryPointInfo {
  bool found = false;
  std::set<uint32_t> input_locations;  // Location decorations of the entry point's Input variables
  // Per input location, what its components are: 32-bit float, int or uint (a scalar or a
  // vector). Empty for anything else (a 64-bit or 16-bit type, a matrix, a struct).
  std::map<uint32_t, std::optional<TexelKind>> input_types;
  // (set, binding) of every resource variable the entry point's call tree reads (one the module
  // only declares, or reads in a function the entry point never calls, needs no descriptor).
  std::set<std::pair<uint32_t, uint32_t>> descriptor_bindings;
  // The descriptor type each of those needs, where its variable's type says (an array of
  // descriptors by its element): a layout of another type at the binding would reach the driver
  // mismatched, which lavapipe does not survive.
  std::map<std::pair<uint32_t, uint32_t>, vk::DescriptorType> descriptor_types;
};

enum class ExecutionModel : uint32_t { Vertex = 0, Fragment = 4 };

// Finds the entry point `name` of `model`, the locations and component types of its inputs, and the module's
// descriptor bindings. The module must already
// have passed spirv-val.
EntryPointInfo reflect_entry_point(const std::vector<uint32_t>& words, ExecutionModel model, const std::string& name);

// ---- Resources ---------------------------------------------------------------------------------

// Memory is declared first so that it is freed after the object bound to it.
struct Buffer {
  vk::raii::DeviceMemory memory{nullptr};
  vk::raii::Buffer buffer{nullptr};
  vk::DeviceSize size = 0;
};

struct Image {
  vk::raii::DeviceMemory memory{nullptr};
  vk::raii::Image image{nullptr};
  // All levels and layers of the shape's view type, of the one aspect (the depth of a depth and
  // stencil image: a sampled view has one aspect).
  vk::raii::ImageView view{nullptr};
  // A depth and stencil image's view of both aspects, the one it is attached by; else null.
  vk::raii::ImageView attachment_view{nullptr};
  vk::Format format = vk::Format::eUndefined;
  vk::ImageAspectFlags aspect;  // every aspect the image has
  uint32_t width = 0;
  uint32_t height = 0;
  uint32_t levels = 1;
  uint32_t layers = 1;  // array layers (a 3D image has 1)
  TextureShape shape;   // as a shader sees it, for the draw-time check against the slot
  TextureFormat texture_format = TextureFormat::Rgba32Float;
  vk::ImageLayout layout = vk::ImageLayout::eUndefined;  // of every subresource
  bool linear_filter = false;                            // the format supports linear filtering
  std::string label;                                     // for messages: "texture 3", "colour of target 1"
};

struct ImageSpec {
  vk::Format format = vk::Format::eUndefined;
  vk::ImageAspectFlags aspect;
  uint32_t width = 0;
  uint32_t height = 0;
  uint32_t levels = 1;
  vk::ImageUsageFlags usage;
  std::string label;
  TextureFormat texture_format = TextureFormat::Rgba32Float;
  TextureDimension dimension = TextureDimension::Tex2D;
  uint32_t layers = 1;  // array layers, or the depth of a 3D image
  uint32_t samples = 1;
};

// The image type, view type, extent, layer count and flags of a spec's dimension.
struct ImageGeometry {
  vk::ImageType type;
  vk::ImageViewType view_type;
  vk::Extent3D extent;
  uint32_t array_layers;
  vk::ImageCreateFlags flags;
};
ImageGeometry image_geometry(const ImageSpec& spec);

// A device and what allocations need to know about it.
struct DeviceRef {
  const vk::raii::PhysicalDevice& physical;
  const vk::raii::Device& device;
  const vk::PhysicalDeviceMemoryProperties& memory;
};

// The first memory type allowed by `type_bits` with `required | preferred`, else with `required`;
// throws when there is none.
uint32_t memory_type(const vk::PhysicalDeviceMemoryProperties& memory, uint32_t type_bits,
                     vk::MemoryPropertyFlags required, vk::MemoryPropertyFlags preferred);
// A host-visible, coherent buffer (device-local too where the device offers it).
Buffer create_host_buffer(const DeviceRef& device, vk::DeviceSize size, vk::BufferUsageFlags usage);
void write_buffer(Buffer& buffer, const void* data, size_t size, size_t offset = 0);
// Empty when the device can make the image `spec` describes, else why not.
std::optional<std::string> unsupported_image(const DeviceRef& device, const ImageSpec& spec);
// An optimally tiled image of the spec's dimension with its memory and a view, in layout Undefined.
Image create_image(const DeviceRef& device, ImageSpec spec);

// ---- Layouts and submission --------------------------------------------------------------------

// One command buffer being recorded. Layout changes are applied to the images at once and rolled
// back if the recording is never submitted successfully.
class Recording {
 public:
  explicit Recording(vk::raii::CommandBuffer command_buffer) : cmd(std::move(command_buffer)) {}

  // A barrier from the image's current layout to `to` (a read-only layout it is already in needs
  // none).
  void transition(Image& image, vk::ImageLayout to);
  void rollback();

  vk::raii::CommandBuffer cmd;

 private:
  std::vector<std::pair<Image*, vk::ImageLayout>> saved_;
};

// ---- Debug messages ----------------------------------------------------------------------------

struct MessageLog {
  std::mutex mutex;
  std::vector<std::string> messages;
};

// Warnings and errors of every type go into `log`, which must outlive the messenger.
vk::DebugUtilsMessengerCreateInfoEXT messenger_info(MessageLog* log);

// ---- Conversions -------------------------------------------------------------------------------

std::string version_string(uint32_t version);  // "1.3.230"
vk::Format vk_format(TextureFormat format);
vk::CompareOp vk_compare_op(CompareOp op);
vk::BlendFactor vk_blend_factor(BlendFactor factor);
vk::BlendOp vk_blend_op(BlendOp op);
vk::StencilOp vk_stencil_op(StencilOp op);
// A sampler as `desc` says, comparing with desc.compare where `compare`; every mip level.
vk::SamplerCreateInfo sampler_info(const SamplerDesc& desc, bool compare);
bool has_stencil(vk::Format format);
// Whether a uniform block, texture or separate sampler of `layout` sits at `binding` (of set 0).
bool layout_has_binding(const ProgramLayout& layout, uint32_t binding);

// ---- Pipelines ---------------------------------------------------------------------------------

// What a draw's pipeline is made of. The mesh is vertex binding 0 (only the locations 0..3 the
// shader reads); binding 1 the zero buffer, read at stride 0 by every input no mesh supplies.
struct DrawPipelineSpec {
  vk::ShaderModule vertex;
  vk::ShaderModule fragment;
  const char* vertex_entry;
  const char* fragment_entry;
  const std::set<uint32_t>& vertex_inputs;
  const std::map<uint32_t, TexelKind>& unsupplied_inputs;
  vk::PipelineLayout layout;
  vk::Format color_format;
  vk::Format depth_format;         // eUndefined: no depth attachment, no depth test; with stencil or not
  uint32_t color_attachments = 1;  // each of color_format, written by the locations 0, 1, ...
  // Culling, depth, stencil (where depth_format has it) and blending (of attachment 0; any other
  // is written as it is).
  DrawState state;
  // Drawn with a positive viewport height (clip -y at row 0, RowOrigin::Bottom): the front face
  // is then clockwise in framebuffer coordinates.
  bool rows_up = false;
  // The specialization constants of both stages (none when empty).
  const std::vector<vk::SpecializationMapEntry>& specialization_entries;
  const std::vector<uint32_t>& specialization_data;
};
// Triangles with `spec.state`; viewport and scissor dynamic.
vk::raii::Pipeline create_draw_pipeline(const vk::raii::Device& device, const DrawPipelineSpec& spec);

// The internal draw that fills a multisampled image: each sample of every texel of one layer
// gets the texel of a single-sampled copy. Without sample shading a fragment's one output goes to
// every sample it covers, and the triangle covers the whole layer. The SPIR-V of shaders/, made
// when xshade is built: the vertex shader, and the fragment shader that reads the layer a push
// constant names from a 2D array of texels of `kind`.
std::span<const uint32_t> fill_vertex_shader();
std::span<const uint32_t> fill_fragment_shader(TexelKind kind);

// A SPIR-V module as the Vulkan environment validates it (SPIRV-Tools): the validator's messages,
// or none when it is valid.
std::vector<std::string> spirv_validation_messages(const std::vector<uint32_t>& words);
// The fill's pipeline: `samples` samples of `format` over `area`, the layer as a push constant.
vk::raii::Pipeline create_fill_pipeline(const vk::raii::Device& device, vk::ShaderModule vertex,
                                        vk::ShaderModule fragment, vk::PipelineLayout layout, vk::Format format,
                                        uint32_t samples, vk::Rect2D area);

}  // namespace xshade::harness::vk_support
