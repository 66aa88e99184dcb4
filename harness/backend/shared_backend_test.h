// For backend tests: one backend per test parameter for the whole suite (a GL context or a Vulkan
// device costs tens of milliseconds), and every test held to leaving no driver message behind.
#pragma once

#include <map>
#include <memory>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "harness/backend/backend.h"

namespace xshade::harness {

// `create(param)` makes the backend a parameter names; a suite derives with its own.
template <class Param, Result<std::unique_ptr<Backend>> (*create)(Param)>
class SharedBackendTest : public ::testing::TestWithParam<Param> {
 protected:
  static void TearDownTestSuite() { backends_.clear(); }

  void SetUp() override {
    std::unique_ptr<Backend>& slot = backends_[this->GetParam()];
    std::string error;
    if (!slot) {
      auto created = create(this->GetParam());
      if (created)
        slot = std::move(*created);
      else
        error = created.error().to_string();
    }
    ASSERT_NE(slot, nullptr) << error;
    backend_ = slot.get();
    backend_->take_driver_messages();
  }
  void TearDown() override {
    if (backend_) {
      EXPECT_EQ(backend_->take_driver_messages(), std::vector<std::string>{});
    }
  }

  Backend& backend() { return *backend_; }

 private:
  static inline std::map<Param, std::unique_ptr<Backend>> backends_;
  Backend* backend_ = nullptr;
};

}  // namespace xshade::harness
