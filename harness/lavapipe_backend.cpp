#include "harness/lavapipe_backend.h"
// Placeholder until the backend lands.
namespace xshade::harness {
bool vulkan_validation_available() { return false; }
Result<std::unique_ptr<Backend>> create_lavapipe_backend(const LavapipeOptions&) { return fail("not built"); }
}
