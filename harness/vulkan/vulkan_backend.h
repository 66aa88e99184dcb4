// Vulkan 1.3 through Mesa's lavapipe (the CPU device), headless: no window system, no swapchain.
#pragma once

#include <memory>

#include "harness/backend/backend.h"

namespace xshade::harness {

struct VulkanOptions {
  // Enable VK_LAYER_KHRONOS_validation when it is installed; its messages are collected and
  // returned by Backend::take_driver_messages().
  bool validation = false;
};

// True when the Khronos validation layer can be enabled on this machine.
bool vulkan_validation_available();

// Fails with a message naming the Debian package (mesa-vulkan-drivers, or libvulkan1 for the
// loader) when no Vulkan CPU device can be found.
Result<std::unique_ptr<Backend>> create_vulkan_backend(const VulkanOptions& options = {});

}  // namespace xshade::harness
