#include "hlsl_like/sema.h"

#include <gtest/gtest.h>

namespace xshade::hlsl {
namespace {

TEST(Sema, Placeholder) { SUCCEED(); }

}  // namespace
}  // namespace xshade::hlsl
