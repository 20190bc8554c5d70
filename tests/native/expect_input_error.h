// wqmesh: a test helper shared by the input tests: running code that must
// refuse its input with an InputError of a given kind.
// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once

#include <gtest/gtest.h>

#include <string>

#include "wqmesh/error.h"

namespace wqmesh::testing {

/// Runs `f` and expects it to throw InputError of `kind`; returns the error's
/// message ("" and a failure when nothing, or another kind, is thrown).
template <class F>
std::string expect_input_error(F f, InputErrorKind kind) {
  try {
    f();
    ADD_FAILURE() << "no error; expected " << error_kind_name(kind);
  } catch (const InputError& e) {
    EXPECT_STREQ(error_kind_name(e.kind()), error_kind_name(kind)) << e.what();
    return e.what();
  }
  return {};
}

}  // namespace wqmesh::testing
