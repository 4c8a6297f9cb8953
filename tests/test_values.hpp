// SPDX-License-Identifier: Apache-2.0
// Values the tests share: one definition, so that test files may be compiled together (unity builds).
#pragma once

#include <limits>

namespace {
constexpr float nan_f = std::numeric_limits<float>::quiet_NaN();
}  // namespace
