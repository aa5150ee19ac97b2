// loom-shaderc: the build-time shader compiler.
//
//   loom-shaderc <input.vert|.frag|.comp> -o <out.cpp> --symbol <c_identifier>
//                [-I <include dir>]... [--depfile <out.d>]
//   loom-shaderc --text <input> -o <out.cpp> --symbol <c_identifier>
//
// Shader mode compiles the GLSL with loom::shader_compiler::ShaderCompiler (build time and run time agree),
// checks that the GL GLSL SPIRV-Cross makes from it is valid, and writes
//   extern const std::uint32_t <symbol>_words[]; extern const std::size_t <symbol>_word_count;
// Text mode writes
//   extern const char <symbol>_text[]; extern const std::size_t <symbol>_size;
// Errors go to stderr as "file:line: message" and make the tool exit 1, failing the build.

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <optional>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "loom/shader_compiler/shader_compiler.hpp"

namespace {

namespace fs = std::filesystem;

struct Arguments {
    fs::path input;
    fs::path output;
    std::string symbol;
    std::vector<fs::path> include_dirs;
    std::optional<fs::path> depfile;
    bool text = false;
};

void print_usage() {
    std::cerr << "usage: loom-shaderc <shader> -o <out.cpp> --symbol <name> [-I <dir>]... [--depfile <file>]\n"
                 "       loom-shaderc --text <file> -o <out.cpp> --symbol <name>\n";
}

std::optional<Arguments> parse_arguments(int argc, char** argv) {
    Arguments args;
    std::vector<std::string> list(argv + 1, argv + argc);
    for (std::size_t i = 0; i < list.size(); ++i) {
        const std::string& arg = list[i];
        auto next = [&]() -> std::optional<std::string> {
            if (i + 1 >= list.size()) {
                std::cerr << "loom-shaderc: " << arg << " needs a value\n";
                return std::nullopt;
            }
            return list[++i];
        };
        if (arg == "-o") {
            auto value = next();
            if (!value) return std::nullopt;
            args.output = *value;
        } else if (arg == "--symbol") {
            auto value = next();
            if (!value) return std::nullopt;
            args.symbol = *value;
        } else if (arg == "-I") {
            auto value = next();
            if (!value) return std::nullopt;
            args.include_dirs.emplace_back(*value);
        } else if (arg == "--depfile") {
            auto value = next();
            if (!value) return std::nullopt;
            args.depfile = *value;
        } else if (arg == "--text") {
            args.text = true;
        } else if (!arg.empty() && arg[0] == '-') {
            std::cerr << "loom-shaderc: unknown option " << arg << "\n";
            return std::nullopt;
        } else if (args.input.empty()) {
            args.input = arg;
        } else {
            std::cerr << "loom-shaderc: more than one input (" << args.input << ", " << arg << ")\n";
            return std::nullopt;
        }
    }
    if (args.input.empty() || args.output.empty() || args.symbol.empty()) return std::nullopt;
    return args;
}

std::optional<std::string> read_file(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) return std::nullopt;
    std::ostringstream text;
    text << in.rdbuf();
    return std::move(text).str();
}

std::optional<loom::rhi::ShaderStage> stage_from_extension(const fs::path& path) {
    const std::string ext = path.extension().string();
    if (ext == ".vert") return loom::rhi::ShaderStage::Vertex;
    if (ext == ".frag") return loom::rhi::ShaderStage::Fragment;
    if (ext == ".comp") return loom::rhi::ShaderStage::Compute;
    return std::nullopt;
}

/// Always rewrites (a stale timestamp would make the build rerun this command every time).
bool write_file(const fs::path& path, const std::string& content) {
    std::error_code ec;
    if (path.has_parent_path()) fs::create_directories(path.parent_path(), ec);
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out << content;
    return static_cast<bool>(out);
}

/// A Makefile-style dependency line for Ninja / Make (spaces escaped).
std::string depfile_path(const fs::path& path) {
    std::string out;
    for (char c : path.generic_string()) {
        if (c == ' ' || c == '#') out += '\\';
        if (c == '$') out += '$';
        out += c;
    }
    return out;
}

std::string c_string_literal(const std::string& text) {
    std::string out = "\"";
    for (unsigned char c : text) {
        if (c == '\n') {
            out += "\\n\"\n    \"";
        } else if (c == '\\' || c == '"') {
            out += '\\';
            out += static_cast<char>(c);
        } else if (c >= 0x20 && c < 0x7f && c != '?') {
            out += static_cast<char>(c);
        } else {
            char octal[8];
            std::snprintf(octal, sizeof octal, "\\%03o", static_cast<unsigned>(c));
            out += octal;
        }
    }
    out += "\"";
    return out;
}

int embed_text(const Arguments& args) {
    auto text = read_file(args.input);
    if (!text) {
        std::cerr << args.input.generic_string() << ": error: cannot read file\n";
        return 1;
    }
    std::string out = "// Generated by loom-shaderc from " + args.input.generic_string() + "; do not edit.\n";
    out += "#include <cstddef>\n\n";
    out += "extern const char " + args.symbol + "_text[] =\n    " + c_string_literal(*text) + ";\n";
    out += "extern const std::size_t " + args.symbol + "_size = " + std::to_string(text->size()) + ";\n";
    if (!write_file(args.output, out)) {
        std::cerr << "loom-shaderc: cannot write " << args.output.generic_string() << "\n";
        return 1;
    }
    return 0;
}

int compile_shader(const Arguments& args) {
    const auto stage = stage_from_extension(args.input);
    if (!stage) {
        std::cerr << args.input.generic_string() << ": error: unknown shader stage (use .vert, .frag or .comp)\n";
        return 1;
    }
    auto code = read_file(args.input);
    if (!code) {
        std::cerr << args.input.generic_string() << ": error: cannot read file\n";
        return 1;
    }

    std::set<std::string> dependencies;
    loom::shader_compiler::ShaderCompilerOptions options;
    options.include_dirs = args.include_dirs;
    options.on_include = [&](const fs::path& resolved) {
        std::error_code ec;
        fs::path absolute = fs::absolute(resolved, ec);
        dependencies.insert((ec ? resolved : absolute).lexically_normal().generic_string());
    };
    loom::shader_compiler::ShaderCompiler compiler(std::move(options));
    loom::shader_compiler::ShaderSource source{args.input.generic_string(), *stage, std::move(*code), {}};
    auto module = compiler.compile(source);
    if (!module) {
        // One diagnostic per line, each "file:line: message", for the build log.
        std::istringstream lines(module.error().message);
        std::string line;
        while (std::getline(lines, line)) std::cerr << line << "\n";
        return 1;
    }
    if (auto gl = loom::shader_compiler::ShaderCompiler::check_gl_source(*module); !gl) {
        std::cerr << gl.error().message << "\n--- generated GL source ---\n" << module->gl_source << "\n";
        return 1;
    }

    std::ostringstream out;
    out << "// Generated by loom-shaderc from " << args.input.generic_string() << "; do not edit.\n"
        << "#include <cstddef>\n#include <cstdint>\n\n"
        << "extern const std::uint32_t " << args.symbol << "_words[] = {";
    const auto& words = module->spirv;
    for (std::size_t i = 0; i < words.size(); ++i) {
        if (i % 8 == 0) out << "\n    ";
        char word[16];
        std::snprintf(word, sizeof word, "0x%08xu,", static_cast<unsigned>(words[i]));
        out << word << (i % 8 == 7 ? "" : " ");
    }
    out << "\n};\n"
        << "extern const std::size_t " << args.symbol << "_word_count = " << words.size() << ";\n";
    if (!write_file(args.output, out.str())) {
        std::cerr << "loom-shaderc: cannot write " << args.output.generic_string() << "\n";
        return 1;
    }

    if (args.depfile) {
        std::string deps = depfile_path(args.output) + ":";
        std::error_code ec;
        deps += " \\\n  " + depfile_path(fs::absolute(args.input, ec).lexically_normal());
        for (const auto& dep : dependencies) deps += " \\\n  " + depfile_path(dep);
        deps += "\n";
        if (!write_file(*args.depfile, deps)) {
            std::cerr << "loom-shaderc: cannot write " << args.depfile->generic_string() << "\n";
            return 1;
        }
    }
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    auto args = parse_arguments(argc, argv);
    if (!args) {
        print_usage();
        return 2;
    }
    return args->text ? embed_text(*args) : compile_shader(*args);
}
