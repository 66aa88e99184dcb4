// The Vulkan lane: Vulkan 1.3 on Mesa's lavapipe, headless, every driver object owned by vk::raii.
//
// Each public operation records one command buffer, submits it and waits on a fence, so nothing is
// in flight between calls. Image layouts are tracked per image (all subresources share one
// layout) and changed with synchronization2 barriers; drawing uses dynamic rendering.
//
// Why this file is long: it is the one class of the Backend seam for Vulkan, and render() is one
// pass of what a draw needs there (descriptor sets, push constants, a pipeline per draw state); its
// stateless pieces live in vk_support.
#include "harness/vulkan/vulkan_backend.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cstring>
#include <functional>
#include <map>
#include <optional>
#include <set>
#include <stdexcept>
#include <tuple>
#include <utility>

#include <fmt/format.h>
#include <vulkan/vulkan_raii.hpp>

#include "harness/backend/guarded.h"
#include "harness/backend/handle_table.h"
#include "harness/backend/pass_resolution.h"
#include "harness/vulkan/lavapipe_loading.h"
#include "harness/vulkan/vk_support.h"

namespace xshade::harness {
namespace {

using vk_support::Buffer;
using vk_support::Image;
using vk_support::Recording;

constexpr vk::Format kColorFormat = vk::Format::eR32G32B32A32Sfloat;
constexpr vk::Format kDepthFormat = vk::Format::eD32Sfloat;
constexpr vk::Format kDepthStencilFormat = vk::Format::eD32SfloatS8Uint;  // TargetDesc::stencil

// ---- Resources ---------------------------------------------------------------------------------

struct Target {
  Image color;
  std::optional<Image> depth;
  std::optional<Image> second_color;  // TargetDesc::second_color
};

struct Mesh {
  Buffer vertices;
  Buffer indices;
  uint32_t index_count = 0;
};

struct Program {
  std::string name;
  ProgramLayout layout;
  bool fullscreen = false;
  std::string vertex_entry;
  std::string fragment_entry;
  std::set<uint32_t> vertex_inputs;
  // The inputs above location 3 (no mesh has them) and what they read: fed backend.h's constant
  // from the backend's constant buffer at binding 1.
  std::map<uint32_t, TexelKind> unsupplied_inputs;
  vk::raii::ShaderModule vertex{nullptr};
  vk::raii::ShaderModule fragment{nullptr};
  vk::raii::DescriptorSetLayout set_layout{nullptr};
  vk::raii::PipelineLayout pipeline_layout{nullptr};
  // The layout's push-constant block (UniformBlockSlot::push_constant), if it has one.
  std::optional<size_t> push_constant_slot;
  // ProgramDesc::specialization as the pipelines' specialization data: a word per entry.
  std::vector<vk::SpecializationMapEntry> specialization_entries;
  std::vector<uint32_t> specialization_data;
  // One per target kind and draw state: by the target's depth format (eUndefined: none), whether it
  // has a second colour, the state, and rows_up.
  std::map<std::tuple<vk::Format, bool, DrawState, bool>, vk::raii::Pipeline> pipelines;
};

// A failed vk::raii call says so; any other exception speaks for itself.
std::string describe_exception(const std::exception& e) {
  if (dynamic_cast<const vk::SystemError*>(&e) != nullptr) return std::string("Vulkan call failed: ") + e.what();
  return e.what();
}

template <class T, class F>
Result<T> guarded(const std::string& what, F&& body) {
  return harness::guarded<T>(what, std::forward<F>(body), &describe_exception);
}

// ---- The backend -------------------------------------------------------------------------------

class VulkanBackend final : public Backend {
 public:
  ~VulkanBackend() override {
    try {
      if (*device_) device_.waitIdle();
    } catch (...) {
      // Nothing useful can be done while tearing down.
    }
  }

  Result<void> init(const VulkanOptions& options);

  const DriverInfo& driver_info() const override { return info_; }
  Result<TargetHandle> create_target(const TargetDesc& desc) override;
  Result<MeshHandle> upload_mesh(const MeshData& mesh) override;
  Result<TextureHandle> upload_texture(const TextureData& texture) override;
  Result<ProgramHandle> create_program(const ProgramDesc& desc) override;
  Result<void> destroy(TargetHandle target) override { return destroy_in(objects_.targets, target); }
  Result<void> destroy(MeshHandle mesh) override { return destroy_in(objects_.meshes, mesh); }
  Result<void> destroy(TextureHandle texture) override { return destroy_in(objects_.textures, texture); }
  Result<void> destroy(ProgramHandle program) override { return destroy_in(objects_.programs, program); }
  Result<void> render(const RenderPass& pass) override;
  Result<FloatImage> read_color(TargetHandle target) override { return read_image(target, false); }
  Result<FloatImage> read_second_color(TargetHandle target) override { return read_image(target, true); }
  std::vector<std::string> take_driver_messages() override {
    std::lock_guard lock(log_->mutex);
    return std::exchange(log_->messages, {});
  }

 private:
  vk_support::DeviceRef device_ref() const { return {physical_, device_, memory_properties_}; }
  Buffer create_buffer(vk::DeviceSize size, vk::BufferUsageFlags usage) const {
    return vk_support::create_host_buffer(device_ref(), size, usage);
  }
  // `compare`: a comparison sampler (of a slot the shader compares), with desc.compare.
  const vk::raii::Sampler& sampler(const SamplerDesc& desc, bool compare);
  // Every sample of each texel of `image` (multisampled, just created) from level 0 of `data`.
  void fill_multisampled(Image& image, const TextureData& data);
  // The vertex buffer of every input no mesh supplies (stride 0): 16 zero bytes, then four
  // float ones for a colour input (backend.h).
  const Buffer& unsupplied_input_buffer();
  // Records with `record`, submits, waits. Layouts roll back if anything throws.
  void submit(const std::function<void(Recording&)>& record);
  Result<vk::Pipeline> pipeline(Program& program, const Target& target, const DrawState& state, bool rows_up);
  Result<FloatImage> read_image(TargetHandle handle, bool second);

  // Every submit waits for its fence, so no work is in flight between calls and nothing a
  // command buffer used can be pending: the object goes at once.
  template <class Table, class HandleType>
  Result<void> destroy_in(Table& table, HandleType handle) {
    return guarded<void>("destroy", [&]() -> Result<void> { return table.erase(handle, "destroy"); });
  }

  // Declared first so that it outlives the messenger that writes into it.
  std::unique_ptr<vk_support::MessageLog> log_ = std::make_unique<vk_support::MessageLog>();
  std::unique_ptr<vk::raii::Context> context_;
  vk::raii::Instance instance_{nullptr};
  vk::raii::DebugUtilsMessengerEXT messenger_{nullptr};
  vk::raii::PhysicalDevice physical_{nullptr};
  vk::raii::Device device_{nullptr};
  vk::raii::Queue queue_{nullptr};
  vk::raii::CommandPool command_pool_{nullptr};
  uint32_t queue_family_ = 0;
  vk::PhysicalDeviceMemoryProperties memory_properties_;
  vk::DeviceSize uniform_alignment_ = 256;
  vk::DeviceSize storage_alignment_ = 256;
  uint32_t max_image_size_ = 4096;
  uint32_t max_uniform_range_ = 16384;
  uint32_t max_push_constants_ = 128;
  DriverInfo info_;

  std::map<std::tuple<Filter, AddressMode, std::optional<CompareOp>>, vk::raii::Sampler> samplers_;
  Buffer unsupplied_vertices_;
  BackendObjects<Target, Mesh, Image, Program> objects_;
};

Result<void> VulkanBackend::init(const VulkanOptions& options) {
  keep_lavapipe_loaded();
  try {
    context_ = std::make_unique<vk::raii::Context>();
  } catch (const std::exception& e) {
    return fail(ErrorKind::Backend,
                fmt::format("cannot load the Vulkan loader libvulkan.so.1 ({}); install the Debian package libvulkan1",
                            e.what()));
  }
  return guarded<void>("creating the Vulkan lavapipe backend", [&]() -> Result<void> {
    const uint32_t loader_version = context_->enumerateInstanceVersion();
    if (loader_version < VK_API_VERSION_1_3)
      return fail(ErrorKind::Backend, fmt::format("the Vulkan loader supports Vulkan {} but 1.3 is required; install "
                                                  "a newer Debian package libvulkan1",
                                                  vk_support::version_string(loader_version)));

    const bool validation = options.validation && vulkan_validation_available();
    std::vector<const char*> layers;
    std::vector<const char*> extensions;
    if (validation) {
      layers.push_back(vk_support::kValidationLayer);
      extensions.push_back(VK_EXT_DEBUG_UTILS_EXTENSION_NAME);
    }
    vk::ApplicationInfo app("xshade", 1, "xshade", 1, VK_API_VERSION_1_3);
    vk::InstanceCreateInfo instance_info({}, &app, layers, extensions);
    const vk::DebugUtilsMessengerCreateInfoEXT debug_info = vk_support::messenger_info(log_.get());
    if (validation) instance_info.pNext = &debug_info;  // also report instance creation
    try {
      instance_ = vk::raii::Instance(*context_, instance_info);
    } catch (const vk::SystemError& e) {
      return fail(ErrorKind::Backend, fmt::format("cannot create a Vulkan instance ({}): no usable Vulkan driver; "
                                                  "install the Debian package mesa-vulkan-drivers (lavapipe) and "
                                                  "check VK_DRIVER_FILES / VK_ICD_FILENAMES",
                                                  e.what()));
    }
    if (validation) messenger_ = vk::raii::DebugUtilsMessengerEXT(instance_, debug_info);

    // The CPU device, i.e. lavapipe; GPUs are ignored so that results never depend on hardware.
    std::vector<vk::raii::PhysicalDevice> devices;
    try {
      devices = instance_.enumeratePhysicalDevices();
    } catch (const vk::SystemError& e) {
      return fail(ErrorKind::Backend, fmt::format("no Vulkan CPU device (lavapipe) found: cannot enumerate Vulkan "
                                                  "devices ({}); install the Debian package mesa-vulkan-drivers and "
                                                  "check VK_DRIVER_FILES / VK_ICD_FILENAMES",
                                                  e.what()));
    }
    std::string seen;
    for (auto& candidate : devices) {
      const vk::PhysicalDeviceProperties properties = candidate.getProperties();
      seen += fmt::format("{}'{}'", seen.empty() ? "" : ", ", properties.deviceName.data());
      if (properties.deviceType == vk::PhysicalDeviceType::eCpu && !*physical_) physical_ = std::move(candidate);
    }
    if (!*physical_)
      return fail(ErrorKind::Backend, fmt::format("no Vulkan CPU device (lavapipe) found (devices: {}); install the "
                                                  "Debian package mesa-vulkan-drivers and check VK_DRIVER_FILES / "
                                                  "VK_ICD_FILENAMES",
                                                  seen.empty() ? "none" : seen));

    const auto properties =
        physical_.getProperties2<vk::PhysicalDeviceProperties2, vk::PhysicalDeviceDriverProperties>();
    const vk::PhysicalDeviceProperties& props = properties.get<vk::PhysicalDeviceProperties2>().properties;
    const auto& driver = properties.get<vk::PhysicalDeviceDriverProperties>();
    if (props.apiVersion < VK_API_VERSION_1_3)
      return fail(ErrorKind::Backend,
                  fmt::format("the Vulkan CPU device '{}' supports Vulkan {} but 1.3 is required; "
                              "install a newer Debian package mesa-vulkan-drivers",
                              props.deviceName.data(), vk_support::version_string(props.apiVersion)));
    info_.api = "Vulkan 1.3 (lavapipe)";
    info_.renderer = props.deviceName.data();
    info_.api_version = vk_support::version_string(props.apiVersion);
    info_.driver_version = driver.driverInfo.data();
    if (size_t paren = info_.driver_version.find(" ("); paren != std::string::npos)
      info_.driver_version.resize(paren);  // "Mesa 22.3.6 (LLVM 15.0.6)" -> "Mesa 22.3.6"
    info_.llvm_version = llvm_version_of(info_.renderer);
    uniform_alignment_ = std::max<vk::DeviceSize>(props.limits.minUniformBufferOffsetAlignment, 16);
    storage_alignment_ = std::max<vk::DeviceSize>(props.limits.minStorageBufferOffsetAlignment, 16);
    max_image_size_ = props.limits.maxImageDimension2D;
    max_uniform_range_ = props.limits.maxUniformBufferRange;
    max_push_constants_ = props.limits.maxPushConstantsSize;
    memory_properties_ = physical_.getMemoryProperties();

    const auto format_features = [&](vk::Format format) {
      return physical_.getFormatProperties(format).optimalTilingFeatures;
    };
    using F = vk::FormatFeatureFlagBits;
    if ((format_features(kColorFormat) & (F::eColorAttachment | F::eSampledImage | F::eTransferSrc)) !=
            (F::eColorAttachment | F::eSampledImage | F::eTransferSrc) ||
        (format_features(kDepthFormat) & (F::eDepthStencilAttachment | F::eSampledImage)) !=
            (F::eDepthStencilAttachment | F::eSampledImage) ||
        (format_features(kDepthStencilFormat) & (F::eDepthStencilAttachment | F::eSampledImage)) !=
            (F::eDepthStencilAttachment | F::eSampledImage))
      return fail(ErrorKind::Backend,
                  fmt::format("'{}' cannot render to and sample R32G32B32A32_SFLOAT, D32_SFLOAT and "
                              "D32_SFLOAT_S8_UINT",
                              info_.renderer));

    const auto families = physical_.getQueueFamilyProperties();
    auto graphics = std::find_if(families.begin(), families.end(), [](const auto& family) {
      return bool(family.queueFlags & vk::QueueFlagBits::eGraphics);
    });
    if (graphics == families.end())
      return fail(ErrorKind::Backend, fmt::format("'{}' has no graphics queue", info_.renderer));
    queue_family_ = static_cast<uint32_t>(graphics - families.begin());

    // Enable what the device supports, so that any valid shader runs, except robustness (which
    // would hide out-of-bounds bugs behind defined results).
    auto features = physical_.getFeatures2<vk::PhysicalDeviceFeatures2, vk::PhysicalDeviceVulkan11Features,
                                           vk::PhysicalDeviceVulkan12Features, vk::PhysicalDeviceVulkan13Features>();
    features.get<vk::PhysicalDeviceFeatures2>().features.robustBufferAccess = VK_FALSE;
    auto& features13 = features.get<vk::PhysicalDeviceVulkan13Features>();
    features13.robustImageAccess = VK_FALSE;
    if (!features13.dynamicRendering || !features13.synchronization2)
      return fail(ErrorKind::Backend, fmt::format("'{}' lacks dynamic rendering or synchronization2", info_.renderer));
    const float priority = 1.0f;
    vk::DeviceQueueCreateInfo queue_info({}, queue_family_, 1, &priority);
    vk::DeviceCreateInfo device_info({}, queue_info, {}, {}, nullptr);
    device_info.pNext = &features.get<vk::PhysicalDeviceFeatures2>();
    device_ = vk::raii::Device(physical_, device_info);
    queue_ = vk::raii::Queue(device_, queue_family_, 0);
    command_pool_ = vk::raii::CommandPool(
        device_, vk::CommandPoolCreateInfo(vk::CommandPoolCreateFlagBits::eTransient, queue_family_));
    return {};
  });
}

const vk::raii::Sampler& VulkanBackend::sampler(const SamplerDesc& desc, bool compare) {
  const auto key =
      std::make_tuple(desc.filter, desc.address, compare ? std::optional<CompareOp>(desc.compare) : std::nullopt);
  auto found = samplers_.find(key);
  if (found != samplers_.end()) return found->second;
  return samplers_.emplace(key, vk::raii::Sampler(device_, vk_support::sampler_info(desc, compare))).first->second;
}

void VulkanBackend::submit(const std::function<void(Recording&)>& record) {
  vk::raii::CommandBuffers buffers(device_,
                                   vk::CommandBufferAllocateInfo(*command_pool_, vk::CommandBufferLevel::ePrimary, 1));
  Recording recording(std::move(buffers.front()));
  try {
    recording.cmd.begin(vk::CommandBufferBeginInfo(vk::CommandBufferUsageFlagBits::eOneTimeSubmit));
    record(recording);
    recording.cmd.end();
    vk::raii::Fence fence(device_, vk::FenceCreateInfo());
    vk::CommandBufferSubmitInfo command_info(*recording.cmd);
    queue_.submit2(vk::SubmitInfo2({}, {}, command_info, {}), *fence);
    const vk::Result waited = device_.waitForFences({*fence}, VK_TRUE, UINT64_MAX);
    if (waited != vk::Result::eSuccess)
      throw std::runtime_error("waiting for the GPU work failed: " + vk::to_string(waited));
  } catch (...) {
    recording.rollback();
    throw;
  }
}

Result<TargetHandle> VulkanBackend::create_target(const TargetDesc& desc) {
  return guarded<TargetHandle>("create_target", [&]() -> Result<TargetHandle> {
    if (desc.width == 0 || desc.height == 0)
      return fail(ErrorKind::Internal, fmt::format("create_target: size {}x{} is empty", desc.width, desc.height));
    if (std::max(desc.width, desc.height) > max_image_size_)
      return fail(ErrorKind::Backend, fmt::format("create_target: size {}x{} exceeds the device limit of {}",
                                                  desc.width, desc.height, max_image_size_));
    const uint32_t id = objects_.targets.next_handle().id;
    using U = vk::ImageUsageFlagBits;
    auto target = std::make_unique<Target>();
    // Transfer-dst only for the initial clear below.
    const auto color_image = [&](const char* what) {
      return vk_support::create_image(device_ref(),
                                      {kColorFormat, vk::ImageAspectFlagBits::eColor, desc.width, desc.height, 1,
                                       U::eColorAttachment | U::eSampled | U::eTransferSrc | U::eTransferDst,
                                       fmt::format("the {} of target {}", what, id), TextureFormat::Rgba32Float});
    };
    target->color = color_image("colour");
    if (desc.second_color) target->second_color = color_image("second colour");
    if (desc.stencil && !desc.depth)
      return fail(ErrorKind::Internal, "create_target: a stencil buffer needs a depth buffer");
    const vk::ImageAspectFlags depth_aspect = desc.stencil
                                                  ? vk::ImageAspectFlagBits::eDepth | vk::ImageAspectFlagBits::eStencil
                                                  : vk::ImageAspectFlags(vk::ImageAspectFlagBits::eDepth);
    if (desc.depth)
      target->depth = vk_support::create_image(
          device_ref(), {desc.stencil ? kDepthStencilFormat : kDepthFormat, depth_aspect, desc.width, desc.height, 1,
                         U::eDepthStencilAttachment | U::eSampled | U::eTransferSrc | U::eTransferDst,
                         fmt::format("the depth of target {}", id), TextureFormat::Depth32Float});
    // Start from defined contents (zero colour, far depth) so that reads before a render are
    // stable.
    submit([&](Recording& rec) {
      for (Image* color : {&target->color, target->second_color ? &*target->second_color : nullptr}) {
        if (!color) continue;
        rec.transition(*color, vk::ImageLayout::eTransferDstOptimal);
        rec.cmd.clearColorImage(*color->image, vk::ImageLayout::eTransferDstOptimal,
                                vk::ClearColorValue(std::array<float, 4>{0.0f, 0.0f, 0.0f, 0.0f}),
                                vk::ImageSubresourceRange(vk::ImageAspectFlagBits::eColor, 0, 1, 0, 1));
      }
      if (target->depth) {
        rec.transition(*target->depth, vk::ImageLayout::eTransferDstOptimal);
        rec.cmd.clearDepthStencilImage(*target->depth->image, vk::ImageLayout::eTransferDstOptimal,
                                       vk::ClearDepthStencilValue(1.0f, 0),
                                       vk::ImageSubresourceRange(depth_aspect, 0, 1, 0, 1));
      }
    });
    return objects_.targets.insert(std::move(target));
  });
}

Result<MeshHandle> VulkanBackend::upload_mesh(const MeshData& data) {
  return guarded<MeshHandle>("upload_mesh", [&]() -> Result<MeshHandle> {
    if (auto valid = validate_mesh(data); !valid) return fail(valid.error());
    auto mesh = std::make_unique<Mesh>();
    const size_t vertex_bytes = data.vertices.size() * sizeof(Vertex);
    const size_t index_bytes = data.indices.size() * sizeof(uint32_t);
    mesh->vertices = create_buffer(vertex_bytes, vk::BufferUsageFlagBits::eVertexBuffer);
    vk_support::write_buffer(mesh->vertices, data.vertices.data(), vertex_bytes);
    mesh->indices = create_buffer(index_bytes, vk::BufferUsageFlagBits::eIndexBuffer);
    vk_support::write_buffer(mesh->indices, data.indices.data(), index_bytes);
    mesh->index_count = static_cast<uint32_t>(data.indices.size());
    return objects_.meshes.insert(std::move(mesh));
  });
}

Result<TextureHandle> VulkanBackend::upload_texture(const TextureData& data) {
  return guarded<TextureHandle>("upload_texture", [&]() -> Result<TextureHandle> {
    if (auto valid = validate_texture(data, max_image_size_); !valid) return fail(valid.error());
    const TextureShape shape = data.shape();
    const bool depth = data.format == TextureFormat::Depth32Float;
    const vk::ImageAspectFlags aspect = depth ? vk::ImageAspectFlagBits::eDepth : vk::ImageAspectFlagBits::eColor;
    const uint32_t id = objects_.textures.next_handle().id;
    using U = vk::ImageUsageFlagBits;
    vk_support::ImageSpec spec{vk_support::vk_format(data.format),
                               aspect,
                               data.width,
                               data.height,
                               static_cast<uint32_t>(data.levels.size()),
                               shape.multisampled ? U::eSampled | U::eColorAttachment : U::eSampled | U::eTransferDst,
                               fmt::format("texture {}", id),
                               data.format,
                               data.dimension,
                               data.layers,
                               data.samples};
    if (auto why = vk_support::unsupported_image(device_ref(), spec))
      return fail(ErrorKind::Backend,
                  fmt::format("upload_texture: {} of {}: {}", shape_name(shape), format_name(data.format), *why));
    auto image = std::make_unique<Image>(vk_support::create_image(device_ref(), spec));
    if (shape.multisampled) {
      fill_multisampled(*image, data);
      return objects_.textures.insert(std::move(image));
    }
    std::vector<size_t> offsets;
    size_t total = 0;
    for (const std::vector<std::byte>& level : data.levels) {
      offsets.push_back(total);
      total += (level.size() + 15) & ~size_t(15);
    }
    Buffer staging = create_buffer(total, vk::BufferUsageFlagBits::eTransferSrc);
    for (size_t level = 0; level < data.levels.size(); ++level)
      vk_support::write_buffer(staging, data.levels[level].data(), data.levels[level].size(), offsets[level]);
    const bool volume = data.dimension == TextureDimension::Tex3D;
    submit([&](Recording& rec) {
      rec.transition(*image, vk::ImageLayout::eTransferDstOptimal);
      // Each level's layers (cube faces, 1D rows) follow one another in the buffer, as they are
      // numbered in the image; row 0 of each is v = 0.
      std::vector<vk::BufferImageCopy> regions;
      for (uint32_t level = 0; level < image->levels; ++level)
        regions.emplace_back(
            offsets[level], 0, 0, vk::ImageSubresourceLayers(aspect, level, 0, image->layers), vk::Offset3D(0, 0, 0),
            vk::Extent3D(std::max<uint32_t>(1, data.width >> level), std::max<uint32_t>(1, data.height >> level),
                         volume ? std::max<uint32_t>(1, data.layers >> level) : 1));
      rec.cmd.copyBufferToImage(*staging.buffer, *image->image, vk::ImageLayout::eTransferDstOptimal, regions);
      rec.transition(*image, vk::ImageLayout::eShaderReadOnlyOptimal);
    });
    return objects_.textures.insert(std::move(image));
  });
}

void VulkanBackend::fill_multisampled(Image& image, const TextureData& data) {
  // A multisampled image takes no copies from a buffer: the data goes into a single-sampled 2D
  // array first, and a draw per layer writes it into every sample.
  using U = vk::ImageUsageFlagBits;
  Image source = vk_support::create_image(
      device_ref(),
      {image.format, vk::ImageAspectFlagBits::eColor, data.width, data.height, 1, U::eSampled | U::eTransferDst,
       "the single-sampled copy of " + image.label, data.format, TextureDimension::Tex2DArray, data.layers, 1});
  Buffer staging = create_buffer(data.levels[0].size(), vk::BufferUsageFlagBits::eTransferSrc);
  vk_support::write_buffer(staging, data.levels[0].data(), data.levels[0].size());

  const TexelKind kind = texel_kind(data.format);
  const auto module = [&](std::span<const uint32_t> words) {
    return vk::raii::ShaderModule(device_, vk::ShaderModuleCreateInfo({}, words.size_bytes(), words.data()));
  };
  const vk::raii::ShaderModule vertex = module(vk_support::fill_vertex_shader());
  const vk::raii::ShaderModule fragment = module(vk_support::fill_fragment_shader(kind));
  const vk::DescriptorSetLayoutBinding binding(0, vk::DescriptorType::eCombinedImageSampler, 1,
                                               vk::ShaderStageFlagBits::eFragment);
  const vk::raii::DescriptorSetLayout set_layout(device_, vk::DescriptorSetLayoutCreateInfo({}, binding));
  const vk::PushConstantRange push(vk::ShaderStageFlagBits::eFragment, 0, sizeof(int32_t));
  const vk::DescriptorSetLayout set_layout_handle = *set_layout;
  const vk::raii::PipelineLayout pipeline_layout(device_, vk::PipelineLayoutCreateInfo({}, set_layout_handle, push));
  const vk::Rect2D area({0, 0}, {data.width, data.height});
  const vk::raii::Pipeline pipeline =
      vk_support::create_fill_pipeline(device_, *vertex, *fragment, *pipeline_layout, image.format, data.samples, area);

  const vk::DescriptorPoolSize pool_size(vk::DescriptorType::eCombinedImageSampler, 1);
  const vk::raii::DescriptorPool pool(
      device_, vk::DescriptorPoolCreateInfo(vk::DescriptorPoolCreateFlagBits::eFreeDescriptorSet, 1, pool_size));
  vk::raii::DescriptorSets sets(device_, vk::DescriptorSetAllocateInfo(*pool, set_layout_handle));
  const vk::DescriptorImageInfo source_info(*sampler({Filter::Nearest, AddressMode::ClampToEdge}, false), *source.view,
                                            vk::ImageLayout::eShaderReadOnlyOptimal);
  device_.updateDescriptorSets(
      vk::WriteDescriptorSet(*sets.front(), 0, 0, vk::DescriptorType::eCombinedImageSampler, source_info), nullptr);
  std::vector<vk::raii::ImageView> layer_views;
  for (uint32_t layer = 0; layer < data.layers; ++layer)
    layer_views.emplace_back(device_, vk::ImageViewCreateInfo({}, *image.image, vk::ImageViewType::e2D, image.format,
                                                              {}, {vk::ImageAspectFlagBits::eColor, 0, 1, layer, 1}));
  submit([&](Recording& rec) {
    rec.transition(source, vk::ImageLayout::eTransferDstOptimal);
    const vk::BufferImageCopy region(0, 0, 0,
                                     vk::ImageSubresourceLayers(vk::ImageAspectFlagBits::eColor, 0, 0, data.layers),
                                     vk::Offset3D(0, 0, 0), vk::Extent3D(data.width, data.height, 1));
    rec.cmd.copyBufferToImage(*staging.buffer, *source.image, vk::ImageLayout::eTransferDstOptimal, region);
    rec.transition(source, vk::ImageLayout::eShaderReadOnlyOptimal);
    rec.transition(image, vk::ImageLayout::eColorAttachmentOptimal);
    rec.cmd.bindPipeline(vk::PipelineBindPoint::eGraphics, *pipeline);
    rec.cmd.bindDescriptorSets(vk::PipelineBindPoint::eGraphics, *pipeline_layout, 0, *sets.front(), nullptr);
    for (uint32_t layer = 0; layer < data.layers; ++layer) {
      const vk::RenderingAttachmentInfo color(*layer_views[layer], vk::ImageLayout::eColorAttachmentOptimal, {},
                                              nullptr, {}, vk::AttachmentLoadOp::eDontCare,
                                              vk::AttachmentStoreOp::eStore);
      rec.cmd.beginRendering(vk::RenderingInfo({}, area, 1, 0, color));
      const int32_t layer_index = static_cast<int32_t>(layer);
      rec.cmd.pushConstants<int32_t>(*pipeline_layout, vk::ShaderStageFlagBits::eFragment, 0, layer_index);
      rec.cmd.draw(3, 1, 0, 0);
      rec.cmd.endRendering();
    }
    rec.transition(image, vk::ImageLayout::eShaderReadOnlyOptimal);
  });
}

const Buffer& VulkanBackend::unsupplied_input_buffer() {
  if (!*unsupplied_vertices_.buffer) {
    // Four zeros (of any type), then four float ones for a colour input (backend.h).
    const std::array<float, 8> values{0.0f, 0.0f, 0.0f, 0.0f, 1.0f, 1.0f, 1.0f, 1.0f};
    unsupplied_vertices_ = create_buffer(sizeof values, vk::BufferUsageFlagBits::eVertexBuffer);
    vk_support::write_buffer(unsupplied_vertices_, values.data(), sizeof values);
  }
  return unsupplied_vertices_;
}

Result<ProgramHandle> VulkanBackend::create_program(const ProgramDesc& desc) {
  const std::string what = fmt::format("create_program '{}'", desc.name);
  return guarded<ProgramHandle>(what, [&]() -> Result<ProgramHandle> {
    auto program = std::make_unique<Program>();
    program->name = desc.name;
    program->layout = desc.layout;
    program->fullscreen = desc.fullscreen;
    for (const auto& [id, word] : desc.specialization) {
      program->specialization_entries.emplace_back(id, uint32_t(program->specialization_data.size() * sizeof(uint32_t)),
                                                   sizeof(uint32_t));
      program->specialization_data.push_back(word);
    }
    program->vertex_entry = desc.vertex.entry_point;
    program->fragment_entry = desc.fragment.entry_point;

    struct StageIn {
      const ShaderStageSource& source;
      const char* stage;
      vk_support::ExecutionModel model;
      vk::raii::ShaderModule& module;
    };
    using vk_support::ExecutionModel;
    // What each stage's SPIR-V needs at each binding of set 0, and which shader says so.
    std::map<uint32_t, std::pair<vk::DescriptorType, std::string>> needed_types;
    for (const StageIn& in : {StageIn{desc.vertex, "vertex", ExecutionModel::Vertex, program->vertex},
                              StageIn{desc.fragment, "fragment", ExecutionModel::Fragment, program->fragment}}) {
      const std::string shader = fmt::format("{}: {} shader '{}'", what, in.stage, in.source.name);
      if (in.source.spirv.empty()) return fail(ErrorKind::Internal, shader + " has no SPIR-V");
      if (const std::vector<std::string> refusals = vk_support::spirv_validation_messages(in.source.spirv);
          !refusals.empty()) {
        Error error{fmt::format("{} is not valid SPIR-V", shader), {in.source.name, 0, 0}, {}};
        for (const std::string& refusal : refusals)
          error.diagnostics.push_back({Severity::Error, {in.source.name, 0, 0}, refusal});
        return fail(std::move(error));
      }
      const vk_support::EntryPointInfo entry =
          vk_support::reflect_entry_point(in.source.spirv, in.model, in.source.entry_point);
      if (!entry.found)
        return fail(ErrorKind::Internal,
                    fmt::format("{} has no {} entry point named '{}'", shader, in.stage, in.source.entry_point));
      if (in.model == ExecutionModel::Vertex) {
        program->vertex_inputs = entry.input_locations;
        for (const auto& [location, kind] : entry.input_types) {
          if (location <= 3) continue;
          if (!kind)
            return fail(ErrorKind::UserInput,
                        fmt::format("{} reads vertex input location {}, which no mesh supplies and whose type is "
                                    "not a 32-bit float, int or uint scalar or vector",
                                    shader, location));
          program->unsupplied_inputs.emplace(location, *kind);
        }
      }
      // A resource the layout does not list would reach the driver without a descriptor.
      for (const auto& [set, binding] : entry.descriptor_bindings)
        if (set != 0 || !vk_support::layout_has_binding(desc.layout, binding))
          return fail(ErrorKind::Internal,
                      fmt::format("{} reads the resource at set {} binding {}, which the program's "
                                  "layout does not list",
                                  shader, set, binding));
      for (const auto& [place, type] : entry.descriptor_types)
        if (place.first == 0) needed_types.emplace(place.second, std::pair{type, shader});
      in.module = vk::raii::ShaderModule(
          device_, vk::ShaderModuleCreateInfo({}, in.source.spirv.size() * sizeof(uint32_t), in.source.spirv.data()));
    }
    if (desc.fullscreen && !program->vertex_inputs.empty())
      return fail(ErrorKind::Internal, fmt::format("{}: a full-screen program's vertex shader must read no vertex "
                                                   "input, but it reads location {}",
                                                   what, *program->vertex_inputs.begin()));

    std::vector<vk::DescriptorSetLayoutBinding> bindings;
    std::map<uint32_t, std::string> used;  // binding -> what uses it
    std::set<uint32_t> shared_samplers;    // sampler bindings already listed
    std::set<std::string> names;
    const auto stages = vk::ShaderStageFlagBits::eVertex | vk::ShaderStageFlagBits::eFragment;
    auto add = [&](uint32_t binding, vk::DescriptorType type, const std::string& user) -> Result<void> {
      if (auto [it, fresh] = used.emplace(binding, user); !fresh)
        return fail(ErrorKind::Internal,
                    fmt::format("{}: binding {} is used by both {} and {}", what, binding, it->second, user));
      bindings.emplace_back(binding, type, 1, stages);
      return {};
    };
    for (size_t s = 0; s < desc.layout.uniform_blocks.size(); ++s) {
      const UniformBlockSlot& slot = desc.layout.uniform_blocks[s];
      if (!names.insert(slot.name).second)
        return fail(ErrorKind::Internal, fmt::format("{}: the layout names '{}' twice", what, slot.name));
      if (slot.push_constant) {
        if (program->push_constant_slot)
          return fail(ErrorKind::Internal,
                      fmt::format("{}: '{}' and '{}' are both push constants; a program has one block of them", what,
                                  desc.layout.uniform_blocks[*program->push_constant_slot].name, slot.name));
        if (slot.size == 0 || slot.size > max_push_constants_)
          return fail(ErrorKind::Backend,
                      fmt::format("{}: push-constant block '{}' has size {}; the device allows 1..{} bytes", what,
                                  slot.name, slot.size, max_push_constants_));
        program->push_constant_slot = s;
        continue;
      }
      if (slot.size == 0 || slot.size > max_uniform_range_)
        return fail(ErrorKind::Backend, fmt::format("{}: uniform block '{}' has size {}; the device allows 1..{} bytes",
                                                    what, slot.name, slot.size, max_uniform_range_));
      if (auto ok = add(slot.binding, vk::DescriptorType::eUniformBuffer, fmt::format("uniform block '{}'", slot.name));
          !ok)
        return fail(ok.error());
    }
    for (const TextureSlot& slot : desc.layout.textures) {
      if (!names.insert(slot.name).second)
        return fail(ErrorKind::Internal, fmt::format("{}: the layout names '{}' twice", what, slot.name));
      const std::string user = fmt::format("texture '{}'", slot.name);
      Result<void> ok = slot.sampler_binding || slot.image_only
                            ? add(slot.binding, vk::DescriptorType::eSampledImage, user)
                            : add(slot.binding, vk::DescriptorType::eCombinedImageSampler, user);
      // Textures sampled through one SamplerState share its binding (render checks that their
      // samplers agree).
      if (ok && slot.sampler_binding && !shared_samplers.count(*slot.sampler_binding)) {
        ok = add(*slot.sampler_binding, vk::DescriptorType::eSampler, "the sampler of " + user);
        shared_samplers.insert(*slot.sampler_binding);
      }
      if (!ok) return fail(ok.error());
    }
    for (const StorageBufferSlot& slot : desc.layout.storage_buffers) {
      if (!names.insert(slot.name).second)
        return fail(ErrorKind::Internal, fmt::format("{}: the layout names '{}' twice", what, slot.name));
      if (auto ok =
              add(slot.binding, vk::DescriptorType::eStorageBuffer, fmt::format("storage buffer '{}'", slot.name));
          !ok)
        return fail(ok.error());
    }
    // A combined image sampler also serves a separate image and sampler at its binding (Vulkan's
    // rule, what [[vk::binding]] of a texture and its sampler at one number asks).
    const auto serves = [](vk::DescriptorType layout, vk::DescriptorType needed) {
      return layout == needed ||
             (layout == vk::DescriptorType::eCombinedImageSampler &&
              (needed == vk::DescriptorType::eSampledImage || needed == vk::DescriptorType::eSampler));
    };
    for (const vk::DescriptorSetLayoutBinding& binding : bindings)
      if (auto needed = needed_types.find(binding.binding);
          needed != needed_types.end() && !serves(binding.descriptorType, needed->second.first))
        return fail(ErrorKind::Internal,
                    fmt::format("{} reads binding {} as a {} descriptor, but the program's layout gives it a {}",
                                needed->second.second, binding.binding, vk::to_string(needed->second.first),
                                vk::to_string(binding.descriptorType)));
    program->set_layout = vk::raii::DescriptorSetLayout(device_, vk::DescriptorSetLayoutCreateInfo({}, bindings));
    const vk::DescriptorSetLayout set_layout = *program->set_layout;
    std::vector<vk::PushConstantRange> push_ranges;
    if (program->push_constant_slot)
      push_ranges.emplace_back(stages, 0, desc.layout.uniform_blocks[*program->push_constant_slot].size);
    program->pipeline_layout =
        vk::raii::PipelineLayout(device_, vk::PipelineLayoutCreateInfo({}, set_layout, push_ranges));
    return objects_.programs.insert(std::move(program));
  });
}

Result<vk::Pipeline> VulkanBackend::pipeline(Program& program, const Target& target, const DrawState& state,
                                             bool rows_up) {
  const vk::Format depth_format = target.depth ? target.depth->format : vk::Format::eUndefined;
  const bool second_color = target.second_color.has_value();
  const auto key = std::tuple{depth_format, second_color, state, rows_up};
  if (auto known = program.pipelines.find(key); known != program.pipelines.end()) return *known->second;
  return guarded<vk::Pipeline>(
      fmt::format("creating the pipeline of program '{}'", program.name), [&]() -> Result<vk::Pipeline> {
        auto made = program.pipelines.emplace(
            key, vk_support::create_draw_pipeline(
                     device_, {*program.vertex, *program.fragment, program.vertex_entry.c_str(),
                               program.fragment_entry.c_str(), program.vertex_inputs, program.unsupplied_inputs,
                               *program.pipeline_layout, kColorFormat, depth_format, second_color ? 2u : 1u, state,
                               rows_up, program.specialization_entries, program.specialization_data}));
        return *made.first->second;
      });
}

Result<void> VulkanBackend::render(const RenderPass& pass) {
  const std::string what = fmt::format("render into target {}", pass.target.id);
  return guarded<void>(what, [&]() -> Result<void> {
    // Resolve every binding before recording anything; what only Vulkan refuses is checked per
    // texture beside the shared checks.
    const auto facts = [](const Image& image) { return std::pair{image.shape, image.texture_format}; };
    const auto vulkan_checks = [](const ProgramLayout& layout, size_t index, const TextureBinding& binding,
                                  const BoundTexture<Image>& bound, const std::vector<BoundTexture<Image>>& earlier,
                                  const std::string& where) -> Result<void> {
      if (bound.sampler.filter == Filter::Linear && !bound.texture->linear_filter)
        return fail(ErrorKind::Backend, fmt::format("{}: texture '{}': {} cannot be filtered linearly on this device; "
                                                    "use a nearest sampler",
                                                    where, binding.name, bound.texture->label));
      const auto& slots = layout.textures;
      const auto& sampler_binding = slots[index].sampler_binding;
      if (!sampler_binding) return {};
      // One SamplerState, one sampler: every texture read through it must be bound with the same.
      for (size_t other = 0; other < index; ++other) {
        if (slots[other].sampler_binding != sampler_binding) continue;
        const SamplerDesc& first = earlier[other].sampler;
        const bool compared = slots[index].comparison;
        if (first.filter == bound.sampler.filter && first.address == bound.sampler.address &&
            slots[other].comparison == compared && (!compared || first.compare == bound.sampler.compare))
          continue;
        return fail(ErrorKind::UserInput,
                    fmt::format("{}: textures '{}' and '{}' are sampled through one sampler (binding {}) but are "
                                "bound with different samplers",
                                where, slots[other].name, slots[index].name, *sampler_binding));
      }
      return {};
    };
    auto resolved = resolve_pass(objects_, pass, what, facts, vulkan_checks);
    if (!resolved) return fail(resolved.error());
    Target* target = resolved->target;

    // What the pass needs from the driver: a pipeline per draw, descriptors by type, uniform bytes.
    struct Resolved {
      Program* program;
      Mesh* mesh;
      const std::vector<const UniformBinding*>& uniforms;
      const std::vector<BoundTexture<Image>>& textures;
      const std::vector<const StorageBufferBinding*>& storage_buffers;
      vk::Pipeline pipeline;
      bool rows_up;  // clip -y at row 0; a full-screen program's uv (0, 0) is row 0 either way
    };
    std::vector<Resolved> draws;
    std::vector<Image*> sampled_targets;
    vk::DeviceSize uniform_bytes = 0, storage_bytes = 0;
    size_t uniform_count = 0, combined_count = 0, separate_count = 0, image_only_count = 0, storage_count = 0;
    const auto storage_step = [&](size_t bytes) {
      return (bytes + storage_alignment_ - 1) / storage_alignment_ * storage_alignment_;
    };
    for (size_t d = 0; d < resolved->draws.size(); ++d) {
      const auto& draw = resolved->draws[d];
      const bool rows_up = pass.row_origin == RowOrigin::Bottom && !draw.program->fullscreen;
      auto made = pipeline(*draw.program, *target, pass.draws[d].state, rows_up);
      if (!made) return fail(made.error());
      draws.push_back(
          Resolved{draw.program, draw.mesh, draw.uniforms, draw.textures, draw.storage_buffers, *made, rows_up});
      for (const StorageBufferBinding* buffer : draw.storage_buffers)
        storage_bytes += storage_step(buffer->bytes.size());
      storage_count += draw.storage_buffers.size();
      const ProgramLayout& layout = draw.program->layout;
      for (const UniformBlockSlot& block : layout.uniform_blocks) {
        if (block.push_constant) continue;
        uniform_bytes += (block.size + uniform_alignment_ - 1) / uniform_alignment_ * uniform_alignment_;
        uniform_count += 1;
      }
      for (size_t s = 0; s < layout.textures.size(); ++s) {
        if (draw.textures[s].of_target) sampled_targets.push_back(draw.textures[s].texture);
        const TextureSlot& slot = layout.textures[s];
        if (slot.image_only) {
          image_only_count += 1;
        } else {
          (slot.sampler_binding ? separate_count : combined_count) += 1;
        }
      }
    }

    // Uniform data for every draw in one host-visible buffer; one descriptor set per draw.
    Buffer uniforms;
    if (uniform_bytes > 0) {
      uniforms = create_buffer(uniform_bytes, vk::BufferUsageFlagBits::eUniformBuffer);
      void* mapped = uniforms.memory.mapMemory(0, uniform_bytes);
      vk::DeviceSize offset = 0;
      for (const Resolved& draw : draws) {
        for (size_t s = 0; s < draw.uniforms.size(); ++s) {
          if (draw.program->push_constant_slot == s) continue;
          const UniformBinding* binding = draw.uniforms[s];
          std::memcpy(static_cast<std::byte*>(mapped) + offset, binding->bytes.data(), binding->bytes.size());
          offset += (binding->bytes.size() + uniform_alignment_ - 1) / uniform_alignment_ * uniform_alignment_;
        }
      }
      uniforms.memory.unmapMemory();
    }
    // Storage-buffer data likewise, each draw's buffers at aligned offsets.
    Buffer storage;
    if (storage_bytes > 0) {
      storage = create_buffer(storage_bytes, vk::BufferUsageFlagBits::eStorageBuffer);
      void* mapped = storage.memory.mapMemory(0, storage_bytes);
      vk::DeviceSize offset = 0;
      for (const Resolved& draw : draws)
        for (const StorageBufferBinding* buffer : draw.storage_buffers) {
          std::memcpy(static_cast<std::byte*>(mapped) + offset, buffer->bytes.data(), buffer->bytes.size());
          offset += storage_step(buffer->bytes.size());
        }
      storage.memory.unmapMemory();
    }
    std::vector<vk::DescriptorPoolSize> pool_sizes;
    auto add_size = [&](vk::DescriptorType type, size_t count) {
      if (count) pool_sizes.emplace_back(type, static_cast<uint32_t>(count));
    };
    add_size(vk::DescriptorType::eUniformBuffer, uniform_count);
    add_size(vk::DescriptorType::eCombinedImageSampler, combined_count);
    add_size(vk::DescriptorType::eSampledImage, separate_count + image_only_count);
    add_size(vk::DescriptorType::eSampler, separate_count);
    add_size(vk::DescriptorType::eStorageBuffer, storage_count);
    vk::raii::DescriptorPool pool{nullptr};
    std::vector<vk::raii::DescriptorSet> sets;  // declared after the pool: freed before it
    std::vector<vk::DescriptorSet> draw_sets(draws.size());
    if (!pool_sizes.empty()) {
      pool = vk::raii::DescriptorPool(device_,
                                      vk::DescriptorPoolCreateInfo(vk::DescriptorPoolCreateFlagBits::eFreeDescriptorSet,
                                                                   static_cast<uint32_t>(draws.size()), pool_sizes));
      vk::DeviceSize offset = 0, storage_offset = 0;
      for (size_t i = 0; i < draws.size(); ++i) {
        const Resolved& draw = draws[i];
        const ProgramLayout& layout = draw.program->layout;
        if (layout.uniform_blocks.size() == (draw.program->push_constant_slot ? 1u : 0u) && layout.textures.empty() &&
            layout.storage_buffers.empty())
          continue;
        const vk::DescriptorSetLayout set_layout = *draw.program->set_layout;
        vk::raii::DescriptorSets allocated(device_, vk::DescriptorSetAllocateInfo(*pool, set_layout));
        sets.push_back(std::move(allocated.front()));
        draw_sets[i] = *sets.back();
        // Reserved up front: the writes point into these vectors.
        std::vector<vk::DescriptorBufferInfo> buffer_infos;
        std::vector<vk::DescriptorImageInfo> image_infos;
        buffer_infos.reserve(layout.uniform_blocks.size() + layout.storage_buffers.size());
        image_infos.reserve(layout.textures.size() * 2);
        std::vector<vk::WriteDescriptorSet> writes;
        for (const UniformBlockSlot& slot : layout.uniform_blocks) {
          if (slot.push_constant) continue;
          buffer_infos.emplace_back(*uniforms.buffer, offset, slot.size);
          writes.emplace_back(draw_sets[i], slot.binding, 0, vk::DescriptorType::eUniformBuffer, nullptr,
                              buffer_infos.back());
          offset += (slot.size + uniform_alignment_ - 1) / uniform_alignment_ * uniform_alignment_;
        }
        for (size_t s = 0; s < layout.storage_buffers.size(); ++s) {
          const vk::DeviceSize size = draw.storage_buffers[s]->bytes.size();
          buffer_infos.emplace_back(*storage.buffer, storage_offset, size);
          writes.emplace_back(draw_sets[i], layout.storage_buffers[s].binding, 0, vk::DescriptorType::eStorageBuffer,
                              nullptr, buffer_infos.back());
          storage_offset += storage_step(size);
        }
        for (size_t s = 0; s < layout.textures.size(); ++s) {
          const TextureSlot& slot = layout.textures[s];
          const BoundTexture<Image>& bound = draw.textures[s];
          const vk::Sampler smp = *sampler(bound.sampler, slot.comparison);
          if (slot.image_only) {
            image_infos.emplace_back(nullptr, *bound.texture->view, vk::ImageLayout::eShaderReadOnlyOptimal);
            writes.emplace_back(draw_sets[i], slot.binding, 0, vk::DescriptorType::eSampledImage, image_infos.back());
          } else if (slot.sampler_binding) {
            image_infos.emplace_back(nullptr, *bound.texture->view, vk::ImageLayout::eShaderReadOnlyOptimal);
            writes.emplace_back(draw_sets[i], slot.binding, 0, vk::DescriptorType::eSampledImage, image_infos.back());
            const bool first_reader =
                std::none_of(layout.textures.begin(), layout.textures.begin() + long(s),
                             [&](const TextureSlot& other) { return other.sampler_binding == slot.sampler_binding; });
            if (first_reader) {
              image_infos.emplace_back(smp, nullptr, vk::ImageLayout::eUndefined);
              writes.emplace_back(draw_sets[i], *slot.sampler_binding, 0, vk::DescriptorType::eSampler,
                                  image_infos.back());
            }
          } else {
            image_infos.emplace_back(smp, *bound.texture->view, vk::ImageLayout::eShaderReadOnlyOptimal);
            writes.emplace_back(draw_sets[i], slot.binding, 0, vk::DescriptorType::eCombinedImageSampler,
                                image_infos.back());
          }
        }
        device_.updateDescriptorSets(writes, nullptr);
      }
    }

    vk::Buffer unsupplied_buffer;
    if (std::any_of(draws.begin(), draws.end(),
                    [](const Resolved& d) { return !d.program->unsupplied_inputs.empty(); }))
      unsupplied_buffer = *unsupplied_input_buffer().buffer;
    submit([&](Recording& rec) {
      for (Image* image : sampled_targets) rec.transition(*image, vk::ImageLayout::eShaderReadOnlyOptimal);
      rec.transition(target->color, vk::ImageLayout::eColorAttachmentOptimal);
      if (target->second_color) rec.transition(*target->second_color, vk::ImageLayout::eColorAttachmentOptimal);
      if (target->depth) rec.transition(*target->depth, vk::ImageLayout::eDepthStencilAttachmentOptimal);
      const vk::Rect2D area({0, 0}, {target->color.width, target->color.height});
      const auto attachment = [](const Image& image, const glm::vec4& clear) {
        return vk::RenderingAttachmentInfo(
            *image.view, vk::ImageLayout::eColorAttachmentOptimal, {}, nullptr, {}, vk::AttachmentLoadOp::eClear,
            vk::AttachmentStoreOp::eStore,
            vk::ClearColorValue(std::array<float, 4>{clear.r, clear.g, clear.b, clear.a}));
      };
      std::vector<vk::RenderingAttachmentInfo> colors{attachment(target->color, pass.clear_color)};
      if (target->second_color) colors.push_back(attachment(*target->second_color, glm::vec4(0.0f)));
      vk::RenderingAttachmentInfo depth;
      const bool stencil = target->depth && *target->depth->attachment_view;
      if (target->depth)
        depth = vk::RenderingAttachmentInfo(stencil ? *target->depth->attachment_view : *target->depth->view,
                                            vk::ImageLayout::eDepthStencilAttachmentOptimal, {}, nullptr, {},
                                            vk::AttachmentLoadOp::eClear, vk::AttachmentStoreOp::eStore,
                                            vk::ClearDepthStencilValue(pass.clear_depth, pass.clear_stencil));
      rec.cmd.beginRendering(
          vk::RenderingInfo({}, area, 1, 0, colors, target->depth ? &depth : nullptr, stencil ? &depth : nullptr));
      // Negative height: clip +y is up and row 0 is the top, as in Direct3D; positive: rows_up.
      const float width = static_cast<float>(target->color.width);
      const float height = static_cast<float>(target->color.height);
      rec.cmd.setScissor(0, area);
      for (size_t i = 0; i < draws.size(); ++i) {
        const Resolved& draw = draws[i];
        rec.cmd.setViewport(0, draw.rows_up ? vk::Viewport(0.0f, 0.0f, width, height, 0.0f, 1.0f)
                                            : vk::Viewport(0.0f, height, width, -height, 0.0f, 1.0f));
        rec.cmd.bindPipeline(vk::PipelineBindPoint::eGraphics, draw.pipeline);
        if (draw_sets[i])
          rec.cmd.bindDescriptorSets(vk::PipelineBindPoint::eGraphics, *draw.program->pipeline_layout, 0, draw_sets[i],
                                     nullptr);
        if (const std::optional<size_t> push = draw.program->push_constant_slot) {
          const std::vector<std::byte>& bytes = draw.uniforms[*push]->bytes;
          rec.cmd.pushConstants<std::byte>(*draw.program->pipeline_layout,
                                           vk::ShaderStageFlagBits::eVertex | vk::ShaderStageFlagBits::eFragment, 0,
                                           bytes);
        }
        if (draw.program->fullscreen) {
          rec.cmd.draw(3, 1, 0, 0);
        } else {
          if (std::any_of(draw.program->vertex_inputs.begin(), draw.program->vertex_inputs.end(),
                          [](uint32_t location) { return location <= 3; }))
            rec.cmd.bindVertexBuffers(0, *draw.mesh->vertices.buffer, vk::DeviceSize(0));
          if (!draw.program->unsupplied_inputs.empty())
            rec.cmd.bindVertexBuffers(1, unsupplied_buffer, vk::DeviceSize(0));
          rec.cmd.bindIndexBuffer(*draw.mesh->indices.buffer, 0, vk::IndexType::eUint32);
          rec.cmd.drawIndexed(draw.mesh->index_count, 1, 0, 0, 0);
        }
      }
      rec.cmd.endRendering();
    });
    return {};
  });
}

Result<FloatImage> VulkanBackend::read_image(TargetHandle handle, bool second) {
  const std::string what = fmt::format("{} of target {}", second ? "read_second_color" : "read_color", handle.id);
  return guarded<FloatImage>(what, [&]() -> Result<FloatImage> {
    auto found = objects_.targets.find(handle, what);
    if (!found) return fail(found.error());
    Target* target = *found;
    if (second && !target->second_color)
      return fail(ErrorKind::Internal, what + ": the target has no second colour attachment");
    Image& color = second ? *target->second_color : target->color;
    FloatImage result(color.width, color.height);
    const vk::DeviceSize bytes = result.rgba.size() * sizeof(float);
    Buffer readback = create_buffer(bytes, vk::BufferUsageFlagBits::eTransferDst);
    submit([&](Recording& rec) {
      rec.transition(color, vk::ImageLayout::eTransferSrcOptimal);
      const vk::BufferImageCopy region(0, 0, 0, vk::ImageSubresourceLayers(vk::ImageAspectFlagBits::eColor, 0, 0, 1),
                                       vk::Offset3D(0, 0, 0), vk::Extent3D(color.width, color.height, 1));
      rec.cmd.copyImageToBuffer(*color.image, vk::ImageLayout::eTransferSrcOptimal, *readback.buffer, region);
      const vk::MemoryBarrier2 to_host(vk::PipelineStageFlagBits2::eAllTransfer, vk::AccessFlagBits2::eTransferWrite,
                                       vk::PipelineStageFlagBits2::eHost, vk::AccessFlagBits2::eHostRead);
      rec.cmd.pipelineBarrier2(vk::DependencyInfo({}, to_host, {}, {}));
    });
    const void* mapped = readback.memory.mapMemory(0, bytes);
    std::memcpy(result.rgba.data(), mapped, bytes);
    readback.memory.unmapMemory();
    return result;
  });
}

}  // namespace

Result<std::unique_ptr<Backend>> create_vulkan_backend(const VulkanOptions& options) {
  try {
    auto backend = std::make_unique<VulkanBackend>();
    if (auto ok = backend->init(options); !ok) return fail(ok.error());
    return std::unique_ptr<Backend>(std::move(backend));
  } catch (const std::exception& e) {
    return fail(ErrorKind::Backend, fmt::format("creating the Vulkan lavapipe backend: {}", e.what()));
  } catch (...) {
    return fail(ErrorKind::Backend, "creating the Vulkan lavapipe backend: unknown exception");
  }
}

}  // namespace xshade::harness
