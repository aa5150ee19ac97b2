// loom-compare's HTML report opened in headless Chromium, without a GPU: the cases and their
// pictures are made here. The page's scripts must run without an error, and the picture viewer
// must open on a click and from the address, flip between the backends, show the difference,
// zoom in whole steps and go to the next case, as a user's keys drive it.
#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "loom/image_io/image_io.hpp"
#include "loom_test/browser.hpp"
#include "loom_test/test_support.hpp"
#include "report.hpp"

namespace loom::test {
namespace {

using namespace loom::compare;
using nlohmann::json;

// 8x6 pictures of one colour each, so that a shown picture is told by its file.
void write_picture(const std::filesystem::path& path, uint8_t r, uint8_t g, uint8_t b) {
    rhi::Image image(8, 6, rhi::Format::RGBA8Unorm);
    for (uint32_t y = 0; y < image.height; ++y) {
        for (uint32_t x = 0; x < image.width; ++x) {
            const auto texel = image.texel(x, y);
            texel[0] = std::byte{r};
            texel[1] = std::byte{g};
            texel[2] = std::byte{b};
            texel[3] = std::byte{255};
        }
    }
    std::filesystem::create_directories(path.parent_path());
    ASSERT_TRUE(image_io::write_png(image, path).ok()) << path;
}

CaseResult picture_case(const std::filesystem::path& dir, const std::string& name, const std::string& pipeline) {
    CaseResult c;
    c.scene = "models/" + name + ".gltf";
    c.pipeline = pipeline;
    c.id = "models_" + name + ".gltf." + pipeline;
    for (rhi::Backend backend : {rhi::Backend::OpenGL, rhi::Backend::Vulkan}) {
        BackendRun run{backend};
        run.image_file = "cases/" + c.id + "/" + std::string(rhi::backend_name(backend)) + ".png";
        c.runs.push_back(run);
    }
    c.image = ImageMetrics{12.0, 3, 48, 41.5, "cases/" + c.id + "/diff.png"};
    write_picture(dir / c.runs[0].image_file, 200, 40, 40);
    write_picture(dir / c.runs[1].image_file, 40, 200, 40);
    write_picture(dir / c.image->diff_file, 90, 90, 90);
    return c;
}

// The report with `driver` (a script run at the page's load event, once the pictures loaded)
// before </body>: it acts as the user and writes what the viewer showed after each step on
// <body data-steps>.
std::filesystem::path write_report(const std::filesystem::path& dir, const std::string& driver) {
    std::vector<CaseResult> cases = {picture_case(dir, "Box", "deferred"), picture_case(dir, "Duck", "forward")};
    cases[1].failures = {"pictures differ: 3 pixels"};  // listed first
    Options options;
    const RunInfo run{&options, {rhi::Backend::OpenGL, rhi::Backend::Vulkan}, summarize(cases, 1.0)};
    std::string html = report_html(cases, run);
    const std::string recorder = R"(<script>
window.addEventListener("load", () => {
  const viewer = document.getElementById("viewer");
  const steps = [];
  const note = (step) => steps.push({
    step: step,
    hidden: viewer.hidden,
    case: viewer.dataset.case || null,
    image: viewer.dataset.image || null,
    zoom: viewer.dataset.zoom || null,
    width: document.getElementById("viewer-canvas").style.width,
    shown: Array.from(document.querySelectorAll("#viewer-canvas img")).filter((img) => !img.hidden).map((img) => img.getAttribute("src")),
    address: location.hash,
  });
  const press = (key) => { document.dispatchEvent(new KeyboardEvent("keydown", { key: key })); note(key); };
  note("loaded");
)" + driver + R"(
  document.body.dataset.steps = JSON.stringify(steps);
});
</script>
)";
    html.insert(html.rfind("</body>"), recorder);
    const std::filesystem::path page = dir / "report.html";
    std::ofstream(page, std::ios::binary) << html;
    return page;
}

std::filesystem::path fresh_dir(const std::string& name) {
    const std::filesystem::path dir = output_dir() / "compare_report" / name;
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(dir);
    return std::filesystem::absolute(dir);
}

json open_and_read_steps(const std::string& chromium, const std::filesystem::path& page, std::string_view fragment) {
    const PageDump dump = dump_dom(chromium, page, fragment, page.parent_path());
    EXPECT_EQ(dump.status, 0) << dump.log;
    EXPECT_EQ(attribute_of(dump.dom, "body", "data-status"), "ok");
    EXPECT_EQ(attribute_of(dump.dom, "body", "data-errors"), "0");
    const auto steps = attribute_of(dump.dom, "body", "data-steps");
    if (!steps) {
        ADD_FAILURE() << "the driver did not run";
        return json::array();
    }
    return json::parse(*steps);
}

TEST(CompareReportPage, AClickOnAPictureOpensTheViewerOnItsCase) {
    LOOM_REQUIRE_CHROMIUM(chromium);
    const auto dir = fresh_dir("click");
    const auto page = write_report(dir, R"(
  document.querySelector('.pictures[data-case="models_Box.gltf.deferred"] figure[data-image="vulkan"] a').click();
  note("click");
  press("Escape");
)");
    const json steps = open_and_read_steps(chromium, page, "");
    ASSERT_EQ(steps.size(), 3u) << steps.dump(1);
    EXPECT_EQ(steps[0]["hidden"], true) << "closed until asked";
    EXPECT_EQ(steps[1]["hidden"], false);
    EXPECT_EQ(steps[1]["case"], "models_Box.gltf.deferred");
    EXPECT_EQ(steps[1]["image"], "vulkan");
    EXPECT_EQ(steps[1]["shown"], json::array({"cases/models_Box.gltf.deferred/vulkan.png"}));
    EXPECT_EQ(steps[1]["zoom"], "fit");
    EXPECT_EQ(steps[1]["address"], "#view=models_Box.gltf.deferred&image=vulkan&zoom=fit");
    EXPECT_EQ(steps[2]["hidden"], true);
    EXPECT_EQ(steps[2]["address"], "#models_Box.gltf.deferred") << "closing goes back to the case";
}

TEST(CompareReportPage, TheViewerOpensFromTheAddressFlipsShowsTheDifferenceAndZoomsInWholeSteps) {
    LOOM_REQUIRE_CHROMIUM(chromium);
    const auto dir = fresh_dir("keys");
    const auto page = write_report(dir, R"(
  for (const key of ["f", "f", "3", "+", "-", "0", "ArrowRight"]) press(key);
)");
    const json steps = open_and_read_steps(chromium, page, "#view=models_Duck.gltf.forward&image=gl&zoom=4");
    ASSERT_EQ(steps.size(), 8u) << steps.dump(1);
    const std::string duck = "cases/models_Duck.gltf.forward/";
    // Opened from the address: the GL picture at 4x, each of its 8x6 pixels a 4x4 square.
    EXPECT_EQ(steps[0]["hidden"], false);
    EXPECT_EQ(steps[0]["case"], "models_Duck.gltf.forward");
    EXPECT_EQ(steps[0]["shown"], json::array({duck + "gl.png"}));
    EXPECT_EQ(steps[0]["zoom"], "4");
    EXPECT_EQ(steps[0]["width"], "32px");
    // F flips to the other backend and back, at the same place and zoom.
    EXPECT_EQ(steps[1]["shown"], json::array({duck + "vulkan.png"}));
    EXPECT_EQ(steps[1]["width"], "32px");
    EXPECT_EQ(steps[2]["shown"], json::array({duck + "gl.png"}));
    // 3: the third picture, the difference.
    EXPECT_EQ(steps[3]["image"], "difference");
    EXPECT_EQ(steps[3]["shown"], json::array({duck + "diff.png"}));
    // + and -: the next whole step up (6x) and back.
    EXPECT_EQ(steps[4]["zoom"], "6");
    EXPECT_EQ(steps[4]["width"], "48px");
    EXPECT_EQ(steps[5]["width"], "32px");
    // 0: fit, the largest step at which the picture shows whole: 64x in a 1600-pixel-wide window.
    EXPECT_EQ(steps[6]["zoom"], "fit");
    EXPECT_EQ(steps[6]["width"], "512px");
    EXPECT_EQ(steps[6]["address"], "#view=models_Duck.gltf.forward&image=difference&zoom=fit");
    // →: the next case, the same picture and zoom.
    EXPECT_EQ(steps[7]["case"], "models_Box.gltf.deferred");
    EXPECT_EQ(steps[7]["shown"], json::array({"cases/models_Box.gltf.deferred/diff.png"}));
    EXPECT_EQ(steps[7]["zoom"], "fit");
}

}  // namespace
}  // namespace loom::test
