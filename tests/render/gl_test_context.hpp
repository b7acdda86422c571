// The one CPU (llvmpipe) EGL context the render tests share: created on
// first use, kept for the process; a test without one fails, not crashes.
#pragma once
#include <gtest/gtest.h>

#include <memory>
#include <string>

#include "render/gl_context.hpp"

namespace rscene::render {

inline GlContext* context() {
  static std::unique_ptr<GlContext> ctx = [] {
    std::string err;
    auto c = GlContext::create(Backend::Cpu, &err);
    if (!c) ADD_FAILURE() << "no CPU EGL context: " << err;
    return c;
  }();
  return ctx.get();
}

}  // namespace rscene::render
