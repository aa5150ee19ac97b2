#pragma once
// Helpers for the shader compiler tests.

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "loom/shader_compiler/shader_compiler.hpp"
#include "loom_test/test_support.hpp"

namespace loom::test {

inline shader_compiler::ShaderSource source(std::string name, rhi::ShaderStage stage, std::string code,
                                std::vector<std::pair<std::string, std::string>> defines = {}) {
    return shader_compiler::ShaderSource{std::move(name), stage, std::move(code), std::move(defines)};
}

/// Compiles and fails the test (returning an empty module) when compilation fails.
inline rhi::ShaderModule compile_ok(shader_compiler::ShaderCompiler& compiler, const shader_compiler::ShaderSource& src) {
    auto module = compiler.compile(src);
    EXPECT_TRUE(module.ok()) << (module.ok() ? "" : module.error().to_string());
    return module.ok() ? std::move(module).value() : rhi::ShaderModule{};
}

/// Compiles expecting failure; returns the error message ("" and a test failure on success).
inline std::string compile_error(shader_compiler::ShaderCompiler& compiler, const shader_compiler::ShaderSource& src) {
    auto module = compiler.compile(src);
    EXPECT_FALSE(module.ok()) << "expected " << src.name << " not to compile";
    if (module.ok()) return "";
    EXPECT_EQ(module.error().code, ErrorCode::ShaderCompile) << module.error().to_string();
    return module.error().message;
}

/// The whole content of a text file ("" when it cannot be read).
inline std::string read_text(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    std::ostringstream text;
    text << in.rdbuf();
    return text.str();
}

}  // namespace loom::test
