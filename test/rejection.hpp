// Helpers for tests of error messages: the ModelError message a URDF is rejected with, and a
// check that a message contains a part (the culprit's name, the offending value).
#pragma once

#include <gtest/gtest.h>

#include <exception>
#include <string>

#include "spatial_dynamics/urdf/model_builder.hpp"

namespace sd_test {

/// The ModelError message of building `xml`; fails the test when it is accepted or throws anything else.
inline std::string rejection(const std::string& xml, const spatial_dynamics::ModelBuildOptions& options = {}) {
  try {
    spatial_dynamics::build_model_from_urdf_string(xml, options);
  } catch (const spatial_dynamics::ModelError& e) {
    return e.what();
  } catch (const std::exception& e) {
    ADD_FAILURE() << "expected ModelError, got another exception: " << e.what();
    return "";
  }
  ADD_FAILURE() << "expected ModelError, the model was accepted:\n" << xml;
  return "";
}

}  // namespace sd_test

#define EXPECT_CONTAINS(text, part) \
  EXPECT_NE(std::string(text).find(part), std::string::npos) << "'" << (text) << "' lacks '" << (part) << "'"
