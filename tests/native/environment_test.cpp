// SPDX-License-Identifier: GPL-3.0-or-later
// wqmesh: the test environment itself. The tests of the shared models skip
// when ../shared/models is absent, so that a checkout without it still runs
// the rest; under CI (the environment variable CI set to anything but "" or
// "false") the folder must be there, since a skip would hide 17 tests.
// The sanitizer build is configured with an empty folder on purpose
// (tests/native/CMakeLists.txt): there, nothing is required.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <string>

namespace {

bool under_ci() {
  const char* ci = std::getenv("CI");
  return ci != nullptr && std::string(ci) != "" && std::string(ci) != "false" && std::string(ci) != "0";
}

TEST(Environment, SharedModelsArePresentUnderCI) {
  const std::string dir = WQMESH_SHARED_MODELS;
  if (dir.empty()) GTEST_SKIP() << "this build reads no shared models (WQMESH_TEST_SHARED_MODELS is empty)";
  std::error_code ec;
  const bool present = std::filesystem::is_directory(dir, ec) && !std::filesystem::is_empty(dir, ec);
  if (!under_ci() && !present) GTEST_SKIP() << dir << " is absent: the tests of the shared models skip";
  EXPECT_TRUE(present) << "CI is set but the shared models folder " << dir
                       << " is missing or empty: the tests that read it would all skip";
}

}  // namespace
