#include "loom_test/browser.hpp"

#include <cstdlib>
#include <fstream>
#include <sstream>

#include <sys/wait.h>

namespace loom::test {

std::string read_file(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    std::ostringstream text;
    text << in.rdbuf();
    return text.str();
}

std::string quoted(const std::filesystem::path& path) { return "\"" + path.string() + "\""; }

std::optional<std::string> find_chromium() {
    if (const char* given = std::getenv("LOOM_CHROMIUM"); given && *given) return std::string(given);
    const char* path = std::getenv("PATH");
    if (!path) return std::nullopt;
    std::stringstream dirs(path);
    std::string dir;
    while (std::getline(dirs, dir, ':')) {
        for (const char* name : {"chromium", "chromium-browser"}) {
            const std::filesystem::path candidate = std::filesystem::path(dir) / name;
            std::error_code ec;
            if (std::filesystem::is_regular_file(candidate, ec)) return candidate.string();
        }
    }
    return std::nullopt;
}

PageDump dump_dom(const std::string& chromium, const std::filesystem::path& page, std::string_view fragment,
                  const std::filesystem::path& dir) {
    // A fresh profile per run, and no network, updates, sync or first-run pages: the run
    // depends on nothing but the page.
    const std::string url = "file://" + std::filesystem::absolute(page).string() + std::string(fragment);
    const std::string arguments =
        "--headless --no-sandbox --disable-gpu --disable-quic --no-first-run --disable-background-networking "
        "--disable-component-update --disable-sync --user-data-dir=" + quoted(dir / "chromium-profile") +
        " --window-size=1600,4000 --dump-dom \"" + url + "\"";
    // timeout(1) stops a browser that hangs instead of holding the test until ctest's limit.
    const std::string command = "timeout 120 \"" + chromium + "\" " + arguments + " >" + quoted(dir / "dom.html") + " 2>" +
                                quoted(dir / "chromium.log");
    const int raw = std::system(command.c_str());
    PageDump result;
    result.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
    result.dom = read_file(dir / "dom.html");
    result.log = read_file(dir / "chromium.log");
    return result;
}

std::string_view from_element(std::string_view dom, std::string_view id) {
    const std::size_t at = dom.find("id=\"" + std::string(id) + "\"");
    if (at == std::string_view::npos) return {};
    return dom.substr(at);
}

namespace {

std::string decode(std::string_view text) {
    std::string out;
    for (std::size_t i = 0; i < text.size(); ++i) {
        bool replaced = false;
        for (auto [entity, c] : {std::pair{"&amp;", '&'}, {"&lt;", '<'}, {"&gt;", '>'}, {"&quot;", '"'}}) {
            if (text.substr(i).starts_with(entity)) {
                out += c;
                i += std::string_view(entity).size() - 1;
                replaced = true;
                break;
            }
        }
        if (!replaced) out += text[i];
    }
    return out;
}

}  // namespace

std::vector<std::string> attribute_values(std::string_view text, std::string_view attribute) {
    std::vector<std::string> values;
    const std::string key = " " + std::string(attribute) + "=\"";
    for (std::size_t at = text.find(key); at != std::string_view::npos; at = text.find(key, at)) {
        at += key.size();
        const std::size_t end = text.find('"', at);
        if (end == std::string_view::npos) break;
        values.push_back(decode(text.substr(at, end - at)));
        at = end;
    }
    return values;
}

std::optional<std::string> attribute_of(std::string_view dom, std::string_view tag, std::string_view attribute) {
    // "<body " with its attributes: the page's comments mention "<body>" itself.
    const std::size_t start = dom.find("<" + std::string(tag) + " ");
    if (start == std::string_view::npos) return std::nullopt;
    const std::size_t end = dom.find('>', start);
    const auto values = attribute_values(dom.substr(start, end - start), attribute);
    if (values.empty()) return std::nullopt;
    return values.front();
}

}  // namespace loom::test
