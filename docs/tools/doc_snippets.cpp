// loom-doc-snippets: keeps the code in the guides identical to code that is compiled.
//
//   loom-doc-snippets --root <repository> [--update] docs/a.md docs/b.md ...
//
// Every ```cpp and ```cmake block of a guide, and every ```json block that has a marker, must
// follow (on the line before it) one of:
//
//   <!-- snippet: docs/snippets/getting_started.cpp#first-pass -->
//       the block is the region `first-pass` of that file: the lines between
//       `// [docs:first-pass]` and `// [/docs:first-pass]` (`#` instead of `//` in CMake files),
//       without their common indentation and without other region markers. The snippet files
//       are compiled (and partly run) by docs/CMakeLists.txt, so a snippet that drifts from the
//       API breaks the build.
//   <!-- excerpt: framegraph/include/loom/framegraph/planner.hpp -->
//       the block quotes that file: its lines, stripped of surrounding blanks, appear in the
//       file in the same order, one after the other.
//
// --check (the default) reports every block that differs or has no marker ("file:line: ...")
// and exits with 1; --update rewrites snippet blocks from their regions (excerpts stay).
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

namespace {

namespace fs = std::filesystem;

std::optional<std::vector<std::string>> read_lines(const fs::path& path) {
    std::ifstream in(path);
    if (!in) return std::nullopt;
    std::vector<std::string> lines;
    std::string line;
    while (std::getline(in, line)) lines.push_back(line);
    return lines;
}

std::string trim(const std::string& s) {
    const auto begin = s.find_first_not_of(" \t\r");
    if (begin == std::string::npos) return "";
    const auto end = s.find_last_not_of(" \t\r");
    return s.substr(begin, end - begin + 1);
}

bool starts_with(const std::string& s, const std::string& prefix) { return s.rfind(prefix, 0) == 0; }

/// A region marker line: `// [docs:name]`, `// [/docs:name]` (or with `#`).
bool is_marker(const std::string& line) {
    const std::string t = trim(line);
    return (starts_with(t, "// [docs:") || starts_with(t, "// [/docs:") || starts_with(t, "# [docs:") ||
            starts_with(t, "# [/docs:")) &&
           t.back() == ']';
}

/// The lines of region `name` of `file`, dedented, markers removed; an error message otherwise.
std::optional<std::vector<std::string>> region(const std::vector<std::string>& file, const std::string& name,
                                               std::string& error) {
    std::optional<std::size_t> begin, end;
    for (std::size_t i = 0; i < file.size(); ++i) {
        const std::string t = trim(file[i]);
        if (t == "// [docs:" + name + "]" || t == "# [docs:" + name + "]") begin = i + 1;
        if (t == "// [/docs:" + name + "]" || t == "# [/docs:" + name + "]") end = i;
    }
    if (!begin || !end || *end < *begin) {
        error = "no region '" + name + "' (between [docs:" + name + "] and [/docs:" + name + "] comments)";
        return std::nullopt;
    }
    std::vector<std::string> lines;
    for (std::size_t i = *begin; i < *end; ++i) {
        if (!is_marker(file[i])) lines.push_back(file[i]);
    }
    std::size_t indent = std::string::npos;
    for (const std::string& l : lines) {
        if (trim(l).empty()) continue;
        indent = std::min(indent, l.find_first_not_of(' '));
    }
    for (std::string& l : lines) {
        l = trim(l).empty() ? "" : l.substr(indent == std::string::npos ? 0 : indent);
        while (!l.empty() && (l.back() == ' ' || l.back() == '\r')) l.pop_back();
    }
    return lines;
}

/// True when the non-blank lines of `block` appear, trimmed, one after the other in `file`.
bool quoted_in(const std::vector<std::string>& block, const std::vector<std::string>& file) {
    std::vector<std::string> wanted;
    for (const std::string& l : block) {
        if (!trim(l).empty()) wanted.push_back(trim(l));
    }
    if (wanted.empty()) return false;
    std::vector<std::string> have;
    for (const std::string& l : file) {
        if (!trim(l).empty()) have.push_back(trim(l));
    }
    for (std::size_t start = 0; start + wanted.size() <= have.size(); ++start) {
        bool all = true;
        for (std::size_t i = 0; i < wanted.size() && all; ++i) all = have[start + i] == wanted[i];
        if (all) return true;
    }
    return false;
}

struct Options {
    fs::path root = ".";
    bool update = false;
    std::vector<fs::path> guides;
};

/// Checks (or updates) one guide; returns the number of problems.
int process(const Options& options, const fs::path& guide) {
    auto lines = read_lines(guide);
    if (!lines) {
        std::fprintf(stderr, "%s: cannot read\n", guide.string().c_str());
        return 1;
    }
    int problems = 0;
    bool changed = false;
    std::vector<std::string> out;
    auto report = [&](std::size_t line, const std::string& message) {
        std::fprintf(stderr, "%s:%zu: %s\n", guide.string().c_str(), line + 1, message.c_str());
        ++problems;
    };
    for (std::size_t i = 0; i < lines->size(); ++i) {
        const std::string& line = (*lines)[i];
        out.push_back(line);
        const std::string t = trim(line);
        if (!starts_with(t, "```") || t.size() == 3) continue;
        const std::string language = t.substr(3);
        // The rest of the block, up to its closing fence.
        std::size_t close = i + 1;
        while (close < lines->size() && trim((*lines)[close]) != "```") ++close;
        if (close == lines->size()) {
            report(i, "code block not closed");
            break;
        }
        std::vector<std::string> block(lines->begin() + static_cast<std::ptrdiff_t>(i) + 1,
                                       lines->begin() + static_cast<std::ptrdiff_t>(close));
        std::size_t marker_line = i;
        while (marker_line > 0 && trim((*lines)[marker_line - 1]).empty()) --marker_line;
        const std::string marker = marker_line > 0 ? trim((*lines)[marker_line - 1]) : "";
        // A ```json block is checked when it names its file (a sample graph the tests plan);
        // without a marker it is an illustration, like a shell transcript.
        const bool marked = starts_with(marker, "<!-- snippet: ") || starts_with(marker, "<!-- excerpt: ");
        const bool checked = language == "cpp" || language == "cmake" || (language == "json" && marked);
        std::vector<std::string> replacement = block;
        if (checked) {
            if (starts_with(marker, "<!-- snippet: ") && marker.size() > 18 && marker.substr(marker.size() - 4) == " -->") {
                const std::string target = marker.substr(14, marker.size() - 18);
                const auto hash = target.find('#');
                const fs::path file = options.root / target.substr(0, hash);
                auto source = read_lines(file);
                std::string error;
                if (hash == std::string::npos) {
                    report(i, "snippet marker '" + target + "' names no region (file#region)");
                } else if (!source) {
                    report(i, "snippet file " + file.string() + " cannot be read");
                } else if (auto r = region(*source, target.substr(hash + 1), error)) {
                    if (*r != block) {
                        if (options.update) {
                            replacement = *r;
                            changed = true;
                        } else {
                            report(i, "```" + language + " block differs from " + target +
                                          " (run loom-doc-snippets --update, or change the snippet file)");
                        }
                    }
                } else {
                    report(i, target + ": " + error);
                }
            } else if (starts_with(marker, "<!-- excerpt: ") && marker.size() > 18 && marker.substr(marker.size() - 4) == " -->") {
                const fs::path file = options.root / marker.substr(14, marker.size() - 18);
                auto source = read_lines(file);
                if (!source) {
                    report(i, "excerpt file " + file.string() + " cannot be read");
                } else if (!quoted_in(block, *source)) {
                    report(i, "```" + language + " block is not a quote of " + file.string());
                }
            } else {
                report(i, "```" + language + " block without a '<!-- snippet: file#region -->' or "
                          "'<!-- excerpt: file -->' line before it");
            }
        }
        out.insert(out.end(), replacement.begin(), replacement.end());
        out.push_back((*lines)[close]);
        i = close;
    }
    if (changed) {
        std::ofstream file(guide);
        for (const std::string& l : out) file << l << "\n";
        std::printf("%s: updated\n", guide.string().c_str());
    }
    return problems;
}

}  // namespace

int main(int argc, char** argv) {
    Options options;
    for (int i = 1; i < argc; ++i) {
        const std::string arg = argv[i];
        if (arg == "--root" && i + 1 < argc) {
            options.root = argv[++i];
        } else if (arg == "--update") {
            options.update = true;
        } else if (arg == "--check") {
            options.update = false;
        } else if (starts_with(arg, "--")) {
            std::fprintf(stderr, "loom-doc-snippets: unknown option %s\n", arg.c_str());
            return 2;
        } else {
            options.guides.emplace_back(arg);
        }
    }
    if (options.guides.empty()) {
        std::fprintf(stderr, "usage: loom-doc-snippets --root <repository> [--update] <guide.md>...\n");
        return 2;
    }
    int problems = 0;
    for (const fs::path& guide : options.guides) problems += process(options, guide);
    if (problems > 0) {
        std::fprintf(stderr, "loom-doc-snippets: %d problem(s)\n", problems);
        return 1;
    }
    std::printf("loom-doc-snippets: %zu guide(s) match their snippets\n", options.guides.size());
    return 0;
}
