#include "harness/osmesa_backend.h"
// Placeholder until the backend lands.
namespace xshade::harness {
Result<std::unique_ptr<Backend>> create_osmesa_backend(const OsmesaOptions&) { return fail("not built"); }
}
