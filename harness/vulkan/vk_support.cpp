#include "harness/vulkan/vk_support.h"

#include <bit>
#include <cstring>
#include <map>
#include <stdexcept>

#include <fmt/format.h>

#include <spirv-tools/libspirv.hpp>

#include "base/spirv_words.h"
#include "harness/vulkan/vulkan_backend.h"

// The multisample fill's SPIR-V (CMakeLists.txt makes these from shaders/).
#include "multisample_fill_float.h"
#include "multisample_fill_int.h"
#include "multisample_fill_uint.h"
#include "multisample_fill_vertex.h"

namespace xshade::harness::vk_support {

EntryPointInfo reflect_entry_point(const std::vector<uint32_t>& words, ExecutionModel model, const std::string& name) {
  constexpr uint32_t kOpName = 5, kOpMemberName = 6, kOpEntryPoint = 15, kOpFunction = 54, kOpFunctionEnd = 56,
                     kOpFunctionCall = 57, kOpVariable = 59, kOpDecorate = 71, kOpMemberDecorate = 72;
  constexpr uint32_t kOpTypeInt = 21, kOpTypeFloat = 22, kOpTypeVector = 23, kOpTypePointer = 32;
  constexpr uint32_t kOpTypeImage = 25, kOpTypeSampler = 26, kOpTypeSampledImage = 27, kOpTypeArray = 28,
                     kOpTypeRuntimeArray = 29;
  constexpr uint32_t kDecorationBlock = 2, kDecorationBufferBlock = 3;
  constexpr uint32_t kDimBuffer = 5, kDimSubpassData = 6;
  constexpr uint32_t kStorageClassStorageBuffer = 12;
  constexpr uint32_t kDecorationLocation = 30, kDecorationBinding = 33, kDecorationDescriptorSet = 34;
  constexpr uint32_t kStorageClassUniformConstant = 0, kStorageClassInput = 1, kStorageClassUniform = 2;
  EntryPointInfo info;
  std::vector<uint32_t> interface_ids;
  std::map<uint32_t, uint32_t> locations;  // id -> Location
  std::map<uint32_t, uint32_t> inputs;     // ids of Input-storage variables -> their pointer type
  std::map<uint32_t, TexelKind> scalars;   // 32-bit scalar type ids
  std::map<uint32_t, uint32_t> vectors;    // vector type id -> component type id
  std::map<uint32_t, uint32_t> pointers;   // pointer type id -> pointee type id
  std::map<uint32_t, uint32_t> bindings;   // id -> Binding
  std::map<uint32_t, uint32_t> sets;       // id -> DescriptorSet
  std::set<uint32_t> resources;            // ids of UniformConstant, Uniform and StorageBuffer variables
  std::map<uint32_t, vk::DescriptorType> descriptor_kinds;  // type id -> the descriptor a variable of it needs
  std::map<uint32_t, uint32_t> elements;                    // array type id -> element type id
  std::map<uint32_t, uint32_t> resource_types;              // resource variable id -> pointee type id
  std::map<uint32_t, uint32_t> storage_classes;             // resource variable id -> its storage class
  std::set<uint32_t> blocks, buffer_blocks;                 // struct type ids decorated Block, BufferBlock
  // The ids each function's instructions read, and the functions it calls: a resource counts
  // where the entry point's call tree reads it (Vulkan's static use), not in a function nothing
  // calls (glslang's HLSL front end emits those too).
  std::map<uint32_t, std::set<uint32_t>> function_operands;
  std::map<uint32_t, std::set<uint32_t>> function_calls;
  uint32_t entry_function = 0;
  uint32_t current_function = 0;
  spirv::for_each_instruction(words, [&](uint32_t opcode, uint32_t count, const uint32_t* op) {
    if (opcode == kOpEntryPoint && count >= 4 && op[1] == static_cast<uint32_t>(model)) {
      // OpEntryPoint model id "name" interface-ids...
      const std::string entry_name = spirv::literal_string(&op[3], count - 3);
      if (entry_name == name) {
        info.found = true;
        entry_function = op[2];
        for (size_t i = 3 + spirv::literal_string_words(entry_name.size()); i < count; ++i)
          interface_ids.push_back(op[i]);
      }
    } else if (opcode == kOpDecorate && count >= 4 && op[2] == kDecorationLocation) {
      locations[op[1]] = op[3];
    } else if (opcode == kOpDecorate && count >= 4 && op[2] == kDecorationBinding) {
      bindings[op[1]] = op[3];
    } else if (opcode == kOpDecorate && count >= 4 && op[2] == kDecorationDescriptorSet) {
      sets[op[1]] = op[3];
    } else if (opcode == kOpDecorate && count >= 3 && (op[2] == kDecorationBlock || op[2] == kDecorationBufferBlock)) {
      (op[2] == kDecorationBlock ? blocks : buffer_blocks).insert(op[1]);
    } else if (opcode == kOpTypeImage && count >= 8) {
      // OpTypeImage result sampled-type Dim Depth Arrayed MS Sampled format
      const uint32_t dim = op[3], sampled = op[7];
      descriptor_kinds[op[1]] = dim == kDimSubpassData ? vk::DescriptorType::eInputAttachment
                                : dim == kDimBuffer    ? (sampled == 2 ? vk::DescriptorType::eStorageTexelBuffer
                                                                       : vk::DescriptorType::eUniformTexelBuffer)
                                : sampled == 2         ? vk::DescriptorType::eStorageImage
                                                       : vk::DescriptorType::eSampledImage;
    } else if (opcode == kOpTypeSampler && count >= 2) {
      descriptor_kinds[op[1]] = vk::DescriptorType::eSampler;
    } else if (opcode == kOpTypeSampledImage && count >= 3) {
      descriptor_kinds[op[1]] = vk::DescriptorType::eCombinedImageSampler;
    } else if ((opcode == kOpTypeArray || opcode == kOpTypeRuntimeArray) && count >= 3) {
      elements[op[1]] = op[2];
    } else if (opcode == kOpTypeInt && count >= 4 && op[2] == 32) {
      scalars[op[1]] = op[3] ? TexelKind::Int : TexelKind::Uint;
    } else if (opcode == kOpTypeFloat && count >= 3 && op[2] == 32) {
      scalars[op[1]] = TexelKind::Float;
    } else if (opcode == kOpTypeVector && count >= 4) {
      vectors[op[1]] = op[2];
    } else if (opcode == kOpTypePointer && count >= 4) {
      pointers[op[1]] = op[3];
    } else if (opcode == kOpVariable && count >= 4 && op[3] == kStorageClassInput) {
      inputs[op[2]] = op[1];
    } else if (opcode == kOpVariable && count >= 4 &&
               (op[3] == kStorageClassUniformConstant || op[3] == kStorageClassUniform ||
                op[3] == kStorageClassStorageBuffer)) {
      resources.insert(op[2]);
      storage_classes[op[2]] = op[3];
      if (auto pointee = pointers.find(op[1]); pointee != pointers.end()) resource_types[op[2]] = pointee->second;
    } else if (opcode == kOpFunction && count >= 3) {
      current_function = op[2];
    } else if (opcode == kOpFunctionEnd) {
      current_function = 0;
    } else if (opcode != kOpName && opcode != kOpMemberName && opcode != kOpDecorate && opcode != kOpMemberDecorate &&
               opcode != kOpVariable && opcode != kOpEntryPoint) {
      // Code only: outside functions, literals (constants, array sizes) would pass for ids. In
      // code, a literal that equals a resource's id (a swizzle index, an image-operand mask)
      // counts too: that errs on the side of the check.
      if (current_function) {
        if (opcode == kOpFunctionCall && count >= 4) function_calls[current_function].insert(op[3]);
        for (uint32_t i = 1; i < count; ++i) function_operands[current_function].insert(op[i]);
      }
    }
  });
  for (uint32_t id : interface_ids) {
    auto location = locations.find(id);
    auto input = inputs.find(id);
    if (input == inputs.end() || location == locations.end()) continue;
    info.input_locations.insert(location->second);
    std::optional<TexelKind> kind;
    if (auto pointee = pointers.find(input->second); pointee != pointers.end()) {
      uint32_t type = pointee->second;
      if (auto vector = vectors.find(type); vector != vectors.end()) type = vector->second;
      if (auto scalar = scalars.find(type); scalar != scalars.end()) kind = scalar->second;
    }
    info.input_types[location->second] = kind;
  }
  // Only the resources the entry point's call tree reads: glslang's HLSL front end keeps a global
  // texture a stage never reads (a vertex stage declares the fragment stage's textures), and the
  // functions of other entry points, which need no descriptor.
  std::set<uint32_t> operands;
  std::set<uint32_t> reached;
  std::vector<uint32_t> pending{entry_function};
  while (!pending.empty()) {
    const uint32_t function = pending.back();
    pending.pop_back();
    if (!reached.insert(function).second) continue;
    operands.insert(function_operands[function].begin(), function_operands[function].end());
    for (uint32_t callee : function_calls[function]) pending.push_back(callee);
  }
  for (const auto& [id, binding] : bindings) {
    if (!resources.count(id) || !operands.count(id)) continue;
    const std::pair<uint32_t, uint32_t> place{sets.count(id) ? sets[id] : 0, binding};
    info.descriptor_bindings.insert(place);
    if (!resource_types.count(id)) continue;
    uint32_t type = resource_types[id];
    while (elements.count(type)) type = elements[type];
    if (auto kind = descriptor_kinds.find(type); kind != descriptor_kinds.end()) {
      info.descriptor_types[place] = kind->second;
    } else if (buffer_blocks.count(type) || (blocks.count(type) && storage_classes[id] == kStorageClassStorageBuffer)) {
      info.descriptor_types[place] = vk::DescriptorType::eStorageBuffer;
    } else if (blocks.count(type) && storage_classes[id] == kStorageClassUniform) {
      info.descriptor_types[place] = vk::DescriptorType::eUniformBuffer;
    }
  }
  return info;
}

uint32_t memory_type(const vk::PhysicalDeviceMemoryProperties& memory, uint32_t type_bits,
                     vk::MemoryPropertyFlags required, vk::MemoryPropertyFlags preferred) {
  for (vk::MemoryPropertyFlags wanted : {required | preferred, required}) {
    for (uint32_t i = 0; i < memory.memoryTypeCount; ++i) {
      if ((type_bits & (1u << i)) && (memory.memoryTypes[i].propertyFlags & wanted) == wanted) return i;
    }
  }
  throw std::runtime_error(fmt::format("no memory type with properties {}", vk::to_string(required)));
}

namespace {

vk::raii::DeviceMemory allocate(const DeviceRef& device, const vk::MemoryRequirements& needs,
                                vk::MemoryPropertyFlags required, vk::MemoryPropertyFlags preferred) {
  return vk::raii::DeviceMemory(
      device.device,
      vk::MemoryAllocateInfo(needs.size, memory_type(device.memory, needs.memoryTypeBits, required, preferred)));
}

}  // namespace

Buffer create_host_buffer(const DeviceRef& device, vk::DeviceSize size, vk::BufferUsageFlags usage) {
  Buffer result;
  result.size = size;
  result.buffer = vk::raii::Buffer(device.device, vk::BufferCreateInfo({}, size, usage));
  result.memory = allocate(device, result.buffer.getMemoryRequirements(),
                           vk::MemoryPropertyFlagBits::eHostVisible | vk::MemoryPropertyFlagBits::eHostCoherent,
                           vk::MemoryPropertyFlagBits::eDeviceLocal);
  result.buffer.bindMemory(*result.memory, 0);
  return result;
}

void write_buffer(Buffer& buffer, const void* data, size_t size, size_t offset) {
  if (size == 0) return;
  void* mapped = buffer.memory.mapMemory(offset, size);
  std::memcpy(mapped, data, size);
  buffer.memory.unmapMemory();
}

ImageGeometry image_geometry(const ImageSpec& spec) {
  using D = TextureDimension;
  switch (spec.dimension) {
    case D::Tex1D: return {vk::ImageType::e1D, vk::ImageViewType::e1D, {spec.width, 1, 1}, 1, {}};
    case D::Tex1DArray: return {vk::ImageType::e1D, vk::ImageViewType::e1DArray, {spec.width, 1, 1}, spec.layers, {}};
    case D::Tex2D: return {vk::ImageType::e2D, vk::ImageViewType::e2D, {spec.width, spec.height, 1}, 1, {}};
    case D::Tex2DArray:
      return {vk::ImageType::e2D, vk::ImageViewType::e2DArray, {spec.width, spec.height, 1}, spec.layers, {}};
    case D::Tex3D: return {vk::ImageType::e3D, vk::ImageViewType::e3D, {spec.width, spec.height, spec.layers}, 1, {}};
    case D::Cube:
    case D::CubeArray:
      return {vk::ImageType::e2D,
              spec.dimension == D::Cube ? vk::ImageViewType::eCube : vk::ImageViewType::eCubeArray,
              {spec.width, spec.height, 1},
              spec.layers,
              vk::ImageCreateFlagBits::eCubeCompatible};
  }
  return {vk::ImageType::e2D, vk::ImageViewType::e2D, {spec.width, spec.height, 1}, 1, {}};
}

std::optional<std::string> unsupported_image(const DeviceRef& device, const ImageSpec& spec) {
  const ImageGeometry geometry = image_geometry(spec);
  try {
    const vk::ImageFormatProperties properties = device.physical.getImageFormatProperties(
        spec.format, geometry.type, vk::ImageTiling::eOptimal, spec.usage, geometry.flags);
    if (geometry.extent.width > properties.maxExtent.width || geometry.extent.height > properties.maxExtent.height ||
        geometry.extent.depth > properties.maxExtent.depth)
      return fmt::format("its size exceeds the device's {}x{}x{} for this format", properties.maxExtent.width,
                         properties.maxExtent.height, properties.maxExtent.depth);
    if (geometry.array_layers > properties.maxArrayLayers)
      return fmt::format("{} layers exceed the device's {} for this format", geometry.array_layers,
                         properties.maxArrayLayers);
    if (spec.levels > properties.maxMipLevels)
      return fmt::format("{} levels exceed the device's {} for this format", spec.levels, properties.maxMipLevels);
    if (!(uint32_t(properties.sampleCounts) & spec.samples) || !std::has_single_bit(spec.samples))
      return fmt::format("the device has no {}-sample images of this format (it has {})", spec.samples,
                         vk::to_string(properties.sampleCounts));
  } catch (const vk::FormatNotSupportedError&) {
    return fmt::format("the device has no {} images of format {} with usage {}", vk::to_string(geometry.type),
                       vk::to_string(spec.format), vk::to_string(spec.usage));
  }
  return std::nullopt;
}

Image create_image(const DeviceRef& device, ImageSpec spec) {
  const ImageGeometry geometry = image_geometry(spec);
  Image result;
  result.format = spec.format;
  result.aspect = spec.aspect;
  result.width = spec.width;
  result.height = spec.height;
  result.levels = spec.levels;
  result.layers = geometry.array_layers;
  result.shape = {spec.dimension, spec.samples > 1};
  result.texture_format = spec.texture_format;
  result.label = std::move(spec.label);
  result.linear_filter = bool(device.physical.getFormatProperties(spec.format).optimalTilingFeatures &
                              vk::FormatFeatureFlagBits::eSampledImageFilterLinear);
  result.image = vk::raii::Image(
      device.device,
      vk::ImageCreateInfo(geometry.flags, geometry.type, spec.format, geometry.extent, spec.levels,
                          geometry.array_layers, vk::SampleCountFlagBits(spec.samples), vk::ImageTiling::eOptimal,
                          spec.usage, vk::SharingMode::eExclusive, {}, vk::ImageLayout::eUndefined));
  result.memory = allocate(device, result.image.getMemoryRequirements(), {}, vk::MemoryPropertyFlagBits::eDeviceLocal);
  result.image.bindMemory(*result.memory, 0);
  const auto view = [&](vk::ImageAspectFlags aspect) {
    return vk::raii::ImageView(device.device,
                               vk::ImageViewCreateInfo({}, *result.image, geometry.view_type, spec.format, {},
                                                       {aspect, 0, spec.levels, 0, geometry.array_layers}));
  };
  const vk::ImageAspectFlags depth_stencil = vk::ImageAspectFlagBits::eDepth | vk::ImageAspectFlagBits::eStencil;
  if ((spec.aspect & depth_stencil) == depth_stencil) {
    result.view = view(vk::ImageAspectFlagBits::eDepth);
    result.attachment_view = view(spec.aspect);
  } else {
    result.view = view(spec.aspect);
  }
  return result;
}

namespace {

struct StageAccess {
  vk::PipelineStageFlags2 stage;
  vk::AccessFlags2 access;
};

// What touches an image while it is in `layout`: the scopes of a barrier out of or into it.
StageAccess stage_access(vk::ImageLayout layout) {
  using S = vk::PipelineStageFlagBits2;
  using A = vk::AccessFlagBits2;
  switch (layout) {
    case vk::ImageLayout::eUndefined: return {S::eNone, A::eNone};
    case vk::ImageLayout::eTransferDstOptimal: return {S::eAllTransfer, A::eTransferWrite};
    case vk::ImageLayout::eTransferSrcOptimal: return {S::eAllTransfer, A::eTransferRead};
    case vk::ImageLayout::eColorAttachmentOptimal:
      return {S::eColorAttachmentOutput, A::eColorAttachmentRead | A::eColorAttachmentWrite};
    case vk::ImageLayout::eDepthStencilAttachmentOptimal:
      return {S::eEarlyFragmentTests | S::eLateFragmentTests,
              A::eDepthStencilAttachmentRead | A::eDepthStencilAttachmentWrite};
    case vk::ImageLayout::eShaderReadOnlyOptimal:
      // eShaderRead rather than eShaderSampledRead: the best-practices layer of 1.3.239 expects it.
      return {S::eVertexShader | S::eFragmentShader, A::eShaderRead};
    default: return {S::eAllCommands, A::eMemoryRead | A::eMemoryWrite};
  }
}

}  // namespace

void Recording::transition(Image& image, vk::ImageLayout to) {
  if (image.layout == to && to == vk::ImageLayout::eShaderReadOnlyOptimal) return;
  const StageAccess src = stage_access(image.layout);
  const StageAccess dst = stage_access(to);
  const vk::ImageMemoryBarrier2 barrier(src.stage, src.access, dst.stage, dst.access, image.layout, to,
                                        VK_QUEUE_FAMILY_IGNORED, VK_QUEUE_FAMILY_IGNORED, *image.image,
                                        {image.aspect, 0, image.levels, 0, image.layers});
  cmd.pipelineBarrier2(vk::DependencyInfo({}, {}, {}, barrier));
  saved_.emplace_back(&image, image.layout);
  image.layout = to;
}

void Recording::rollback() {
  for (auto it = saved_.rbegin(); it != saved_.rend(); ++it) it->first->layout = it->second;
  saved_.clear();
}

namespace {

VKAPI_ATTR VkBool32 VKAPI_CALL debug_callback(VkDebugUtilsMessageSeverityFlagBitsEXT severity,
                                              VkDebugUtilsMessageTypeFlagsEXT types,
                                              const VkDebugUtilsMessengerCallbackDataEXT* data, void* user) {
  auto* log = static_cast<MessageLog*>(user);
  const char* level = (severity & VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT) ? "error" : "warning";
  const char* kind = (types & VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT)    ? "validation"
                     : (types & VK_DEBUG_UTILS_MESSAGE_TYPE_PERFORMANCE_BIT_EXT) ? "performance"
                                                                                 : "general";
  std::string text =
      fmt::format("vulkan {} {}: {}", kind, level, data && data->pMessage ? data->pMessage : "(no message)");
  std::lock_guard lock(log->mutex);
  log->messages.push_back(std::move(text));
  return VK_FALSE;  // never abort the call that triggered the message
}

}  // namespace

vk::DebugUtilsMessengerCreateInfoEXT messenger_info(MessageLog* log) {
  using Severity = vk::DebugUtilsMessageSeverityFlagBitsEXT;
  using Type = vk::DebugUtilsMessageTypeFlagBitsEXT;
  return vk::DebugUtilsMessengerCreateInfoEXT({}, Severity::eWarning | Severity::eError,
                                              Type::eGeneral | Type::eValidation | Type::ePerformance, &debug_callback,
                                              log);
}

std::string version_string(uint32_t version) {
  return fmt::format("{}.{}.{}", VK_API_VERSION_MAJOR(version), VK_API_VERSION_MINOR(version),
                     VK_API_VERSION_PATCH(version));
}

vk::Format vk_format(TextureFormat format) {
  switch (format) {
    case TextureFormat::Rgba8Unorm: return vk::Format::eR8G8B8A8Unorm;
    case TextureFormat::Rgba8Srgb: return vk::Format::eR8G8B8A8Srgb;
    case TextureFormat::Rgba32Float: return vk::Format::eR32G32B32A32Sfloat;
    case TextureFormat::R32Float: return vk::Format::eR32Sfloat;
    case TextureFormat::Depth32Float: return vk::Format::eD32Sfloat;
    case TextureFormat::Rgba32Uint: return vk::Format::eR32G32B32A32Uint;
    case TextureFormat::Rgba32Sint: return vk::Format::eR32G32B32A32Sint;
  }
  return vk::Format::eUndefined;
}

vk::Format unsupplied_input_format(TexelKind kind) {
  switch (kind) {
    case TexelKind::Float: return vk::Format::eR32G32B32A32Sfloat;
    case TexelKind::Int: return vk::Format::eR32G32B32A32Sint;
    case TexelKind::Uint: return vk::Format::eR32G32B32A32Uint;
  }
  return vk::Format::eR32G32B32A32Sfloat;
}

vk::raii::Pipeline create_draw_pipeline(const vk::raii::Device& device, const DrawPipelineSpec& spec) {
  const bool depth = spec.depth_format != vk::Format::eUndefined;
  const vk::SpecializationInfo specialization(
      uint32_t(spec.specialization_entries.size()), spec.specialization_entries.data(),
      spec.specialization_data.size() * sizeof(uint32_t), spec.specialization_data.data());
  const vk::SpecializationInfo* specialized = spec.specialization_entries.empty() ? nullptr : &specialization;
  const std::array<vk::PipelineShaderStageCreateInfo, 2> stages = {
      vk::PipelineShaderStageCreateInfo({}, vk::ShaderStageFlagBits::eVertex, spec.vertex, spec.vertex_entry,
                                        specialized),
      vk::PipelineShaderStageCreateInfo({}, vk::ShaderStageFlagBits::eFragment, spec.fragment, spec.fragment_entry,
                                        specialized)};
  // Binding 0 is the mesh; binding 1 the constant buffer, read at stride 0 by every input no
  // mesh supplies: four zeros, then four float ones for a float colour input (backend.h).
  std::vector<vk::VertexInputBindingDescription> bindings;
  const std::array<vk::VertexInputAttributeDescription, 4> all_attributes = {
      vk::VertexInputAttributeDescription(0, 0, vk::Format::eR32G32B32Sfloat, offsetof(Vertex, position)),
      vk::VertexInputAttributeDescription(1, 0, vk::Format::eR32G32B32Sfloat, offsetof(Vertex, normal)),
      vk::VertexInputAttributeDescription(2, 0, vk::Format::eR32G32B32A32Sfloat, offsetof(Vertex, tangent)),
      vk::VertexInputAttributeDescription(3, 0, vk::Format::eR32G32Sfloat, offsetof(Vertex, uv))};
  // Only the locations the shader reads: the validation layer warns about unread attributes.
  std::vector<vk::VertexInputAttributeDescription> attributes;
  for (uint32_t location : spec.vertex_inputs)
    if (location < all_attributes.size()) attributes.push_back(all_attributes[location]);
  if (!attributes.empty()) bindings.emplace_back(0, sizeof(Vertex), vk::VertexInputRate::eVertex);
  for (const auto& [location, kind] : spec.unsupplied_inputs)
    attributes.emplace_back(location, 1, unsupplied_input_format(kind),
                            kind == TexelKind::Float && unsupplied_input_reads_white(location) ? 16 : 0);
  if (!spec.unsupplied_inputs.empty()) bindings.emplace_back(1, 0, vk::VertexInputRate::eVertex);
  vk::PipelineVertexInputStateCreateInfo vertex_input;
  if (!attributes.empty()) vertex_input = vk::PipelineVertexInputStateCreateInfo({}, bindings, attributes);
  const vk::PipelineInputAssemblyStateCreateInfo assembly({}, vk::PrimitiveTopology::eTriangleList);
  const vk::PipelineViewportStateCreateInfo viewport({}, 1, nullptr, 1, nullptr);
  const DrawState& state = spec.state;
  // The negative viewport height puts clip +y at the image's row 0, so a triangle's winding in
  // the image is its winding in framebuffer coordinates: counter-clockwise is the front
  // (backend.h's DrawState). A positive height mirrors the rows, and the winding with them.
  vk::PipelineRasterizationStateCreateInfo raster(
      {}, VK_FALSE, VK_FALSE, vk::PolygonMode::eFill,
      state.cull == CullMode::Back    ? vk::CullModeFlagBits::eBack
      : state.cull == CullMode::Front ? vk::CullModeFlagBits::eFront
                                      : vk::CullModeFlagBits::eNone,
      spec.rows_up ? vk::FrontFace::eClockwise : vk::FrontFace::eCounterClockwise);
  raster.lineWidth = 1.0f;
  if (state.depth_bias_slope != 0.0f || state.depth_bias_units != 0.0f) {
    raster.depthBiasEnable = VK_TRUE;
    raster.depthBiasConstantFactor = state.depth_bias_units;
    raster.depthBiasSlopeFactor = state.depth_bias_slope;
  }
  const vk::PipelineMultisampleStateCreateInfo multisample({}, vk::SampleCountFlagBits::e1);
  vk::PipelineDepthStencilStateCreateInfo depth_state({}, depth, depth && state.depth_write,
                                                      vk_compare_op(state.depth_compare));
  const bool stencil = has_stencil(spec.depth_format);
  if (stencil && state.stencil.enabled) {
    const StencilState& s = state.stencil;
    const auto face = [&](const StencilFaceState& ops) {
      return vk::StencilOpState(vk_stencil_op(ops.fail), vk_stencil_op(ops.pass), vk_stencil_op(ops.depth_fail),
                                vk_compare_op(ops.compare), s.read_mask, s.write_mask, s.reference);
    };
    depth_state.stencilTestEnable = VK_TRUE;
    depth_state.front = face(s.front);
    depth_state.back = face(s.back);
  }
  vk::PipelineColorBlendAttachmentState written;
  written.colorWriteMask = vk::ColorComponentFlagBits::eR | vk::ColorComponentFlagBits::eG |
                           vk::ColorComponentFlagBits::eB | vk::ColorComponentFlagBits::eA;
  std::vector<vk::PipelineColorBlendAttachmentState> blend_attachments(spec.color_attachments, written);
  vk::PipelineColorBlendAttachmentState& first = blend_attachments.front();
  first.colorWriteMask = vk::ColorComponentFlags(state.color_write);  // R, G, B, A are bits 0 to 3 in both
  if (state.blend.enabled) {
    const BlendState& b = state.blend;
    first.blendEnable = VK_TRUE;
    first.srcColorBlendFactor = vk_blend_factor(b.color_source);
    first.dstColorBlendFactor = vk_blend_factor(b.color_destination);
    first.colorBlendOp = vk_blend_op(b.color_op);
    first.srcAlphaBlendFactor = vk_blend_factor(b.alpha_source);
    first.dstAlphaBlendFactor = vk_blend_factor(b.alpha_destination);
    first.alphaBlendOp = vk_blend_op(b.alpha_op);
  }
  const vk::PipelineColorBlendStateCreateInfo blend({}, VK_FALSE, vk::LogicOp::eCopy, blend_attachments);
  const std::array<vk::DynamicState, 2> dynamic_states = {vk::DynamicState::eViewport, vk::DynamicState::eScissor};
  const vk::PipelineDynamicStateCreateInfo dynamic({}, dynamic_states);
  const std::vector<vk::Format> color_formats(spec.color_attachments, spec.color_format);
  vk::PipelineRenderingCreateInfo rendering({}, color_formats, spec.depth_format,
                                            stencil ? spec.depth_format : vk::Format::eUndefined);
  vk::GraphicsPipelineCreateInfo info({}, stages, &vertex_input, &assembly, nullptr, &viewport, &raster, &multisample,
                                      &depth_state, &blend, &dynamic, spec.layout);
  info.pNext = &rendering;
  return vk::raii::Pipeline(device, nullptr, info);
}

std::span<const uint32_t> fill_vertex_shader() { return kMultisampleFill_vertex; }

std::span<const uint32_t> fill_fragment_shader(TexelKind kind) {
  switch (kind) {
    case TexelKind::Int: return kMultisampleFill_int;
    case TexelKind::Uint: return kMultisampleFill_uint;
    case TexelKind::Float: break;
  }
  return kMultisampleFill_float;
}

std::vector<std::string> spirv_validation_messages(const std::vector<uint32_t>& words) {
  spvtools::SpirvTools tools(SPV_ENV_VULKAN_1_3);
  std::vector<std::string> messages;
  tools.SetMessageConsumer([&](spv_message_level_t, const char*, const spv_position_t& position, const char* message) {
    messages.push_back("instruction " + std::to_string(position.index) + ": " + message);
  });
  if (!tools.Validate(words) && messages.empty()) messages.push_back("spirv-val refuses it");
  return messages;
}

vk::raii::Pipeline create_fill_pipeline(const vk::raii::Device& device, vk::ShaderModule vertex,
                                        vk::ShaderModule fragment, vk::PipelineLayout layout, vk::Format format,
                                        uint32_t samples, vk::Rect2D area) {
  const std::array<vk::PipelineShaderStageCreateInfo, 2> stages = {
      vk::PipelineShaderStageCreateInfo({}, vk::ShaderStageFlagBits::eVertex, vertex, "main"),
      vk::PipelineShaderStageCreateInfo({}, vk::ShaderStageFlagBits::eFragment, fragment, "main")};
  const vk::PipelineVertexInputStateCreateInfo vertex_input;
  const vk::PipelineInputAssemblyStateCreateInfo assembly({}, vk::PrimitiveTopology::eTriangleList);
  const vk::Viewport viewport(0.0f, 0.0f, float(area.extent.width), float(area.extent.height), 0.0f, 1.0f);
  const vk::PipelineViewportStateCreateInfo viewport_state({}, viewport, area);
  vk::PipelineRasterizationStateCreateInfo raster({}, VK_FALSE, VK_FALSE, vk::PolygonMode::eFill,
                                                  vk::CullModeFlagBits::eNone, vk::FrontFace::eCounterClockwise);
  raster.lineWidth = 1.0f;
  const vk::PipelineMultisampleStateCreateInfo multisample({}, vk::SampleCountFlagBits(samples));
  vk::PipelineColorBlendAttachmentState blend_attachment;
  blend_attachment.colorWriteMask = vk::ColorComponentFlagBits::eR | vk::ColorComponentFlagBits::eG |
                                    vk::ColorComponentFlagBits::eB | vk::ColorComponentFlagBits::eA;
  const vk::PipelineColorBlendStateCreateInfo blend({}, VK_FALSE, vk::LogicOp::eCopy, blend_attachment);
  vk::PipelineRenderingCreateInfo rendering({}, format);
  vk::GraphicsPipelineCreateInfo info({}, stages, &vertex_input, &assembly, nullptr, &viewport_state, &raster,
                                      &multisample, nullptr, &blend, nullptr, layout);
  info.pNext = &rendering;
  return vk::raii::Pipeline(device, nullptr, info);
}

bool layout_has_binding(const ProgramLayout& layout, uint32_t binding) {
  for (const UniformBlockSlot& block : layout.uniform_blocks)
    if (!block.push_constant && block.binding == binding) return true;
  for (const TextureSlot& texture : layout.textures)
    if (texture.binding == binding || texture.sampler_binding == binding) return true;
  for (const StorageBufferSlot& buffer : layout.storage_buffers)
    if (buffer.binding == binding) return true;
  return false;
}

vk::BlendFactor vk_blend_factor(BlendFactor factor) {
  switch (factor) {
    case BlendFactor::Zero: return vk::BlendFactor::eZero;
    case BlendFactor::One: return vk::BlendFactor::eOne;
    case BlendFactor::SrcColor: return vk::BlendFactor::eSrcColor;
    case BlendFactor::OneMinusSrcColor: return vk::BlendFactor::eOneMinusSrcColor;
    case BlendFactor::DstColor: return vk::BlendFactor::eDstColor;
    case BlendFactor::OneMinusDstColor: return vk::BlendFactor::eOneMinusDstColor;
    case BlendFactor::SrcAlpha: return vk::BlendFactor::eSrcAlpha;
    case BlendFactor::OneMinusSrcAlpha: return vk::BlendFactor::eOneMinusSrcAlpha;
    case BlendFactor::DstAlpha: return vk::BlendFactor::eDstAlpha;
    case BlendFactor::OneMinusDstAlpha: return vk::BlendFactor::eOneMinusDstAlpha;
    case BlendFactor::SrcAlphaSaturate: return vk::BlendFactor::eSrcAlphaSaturate;
  }
  return vk::BlendFactor::eOne;
}

vk::BlendOp vk_blend_op(BlendOp op) {
  switch (op) {
    case BlendOp::Add: return vk::BlendOp::eAdd;
    case BlendOp::Subtract: return vk::BlendOp::eSubtract;
    case BlendOp::ReverseSubtract: return vk::BlendOp::eReverseSubtract;
    case BlendOp::Min: return vk::BlendOp::eMin;
    case BlendOp::Max: return vk::BlendOp::eMax;
  }
  return vk::BlendOp::eAdd;
}

vk::StencilOp vk_stencil_op(StencilOp op) {
  switch (op) {
    case StencilOp::Keep: return vk::StencilOp::eKeep;
    case StencilOp::Zero: return vk::StencilOp::eZero;
    case StencilOp::Replace: return vk::StencilOp::eReplace;
    case StencilOp::IncrementClamp: return vk::StencilOp::eIncrementAndClamp;
    case StencilOp::DecrementClamp: return vk::StencilOp::eDecrementAndClamp;
    case StencilOp::Invert: return vk::StencilOp::eInvert;
    case StencilOp::IncrementWrap: return vk::StencilOp::eIncrementAndWrap;
    case StencilOp::DecrementWrap: return vk::StencilOp::eDecrementAndWrap;
  }
  return vk::StencilOp::eKeep;
}

vk::SamplerCreateInfo sampler_info(const SamplerDesc& desc, bool compare) {
  const bool linear = desc.filter == Filter::Linear;
  const vk::Filter filter = linear ? vk::Filter::eLinear : vk::Filter::eNearest;
  const vk::SamplerMipmapMode mip = linear ? vk::SamplerMipmapMode::eLinear : vk::SamplerMipmapMode::eNearest;
  const vk::SamplerAddressMode address =
      desc.address == AddressMode::Repeat ? vk::SamplerAddressMode::eRepeat : vk::SamplerAddressMode::eClampToEdge;
  return vk::SamplerCreateInfo({}, filter, filter, mip, address, address, address, 0.0f, VK_FALSE, 1.0f,
                               compare ? VK_TRUE : VK_FALSE,
                               compare ? vk_compare_op(desc.compare) : vk::CompareOp::eNever, 0.0f, VK_LOD_CLAMP_NONE);
}

bool has_stencil(vk::Format format) {
  return format == vk::Format::eD32SfloatS8Uint || format == vk::Format::eD24UnormS8Uint ||
         format == vk::Format::eD16UnormS8Uint || format == vk::Format::eS8Uint;
}

vk::CompareOp vk_compare_op(CompareOp op) {
  switch (op) {
    case CompareOp::Never: return vk::CompareOp::eNever;
    case CompareOp::Less: return vk::CompareOp::eLess;
    case CompareOp::Equal: return vk::CompareOp::eEqual;
    case CompareOp::LessEqual: return vk::CompareOp::eLessOrEqual;
    case CompareOp::Greater: return vk::CompareOp::eGreater;
    case CompareOp::NotEqual: return vk::CompareOp::eNotEqual;
    case CompareOp::GreaterEqual: return vk::CompareOp::eGreaterOrEqual;
    case CompareOp::Always: return vk::CompareOp::eAlways;
  }
  return vk::CompareOp::eLessOrEqual;
}

}  // namespace xshade::harness::vk_support

namespace xshade::harness {

bool vulkan_validation_available() {
  try {
    vk::raii::Context context;
    for (const vk::LayerProperties& layer : context.enumerateInstanceLayerProperties())
      if (std::string_view(layer.layerName.data()) == vk_support::kValidationLayer) return true;
  } catch (...) {
    // No loader, or enumeration failed: no validation either.
  }
  return false;
}

}  // namespace xshade::harness
