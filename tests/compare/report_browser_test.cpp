// report.html in a real browser: Debian's headless Chromium opens the report of a comparison that
// holds every kind of frame, runs its script and dumps the DOM, which must list the expected frames
// worst first with their verdicts, show the viewer with its images loaded, and carry no error
// marker; a page whose data is broken must carry it (so the check can fail). A 1200-frame report
// must load too. Skipped only where no Chromium is installed (.ci/packages installs it).
#include <gtest/gtest.h>
#include <stdlib.h>
#include <unistd.h>

#include <regex>

#include "tests/support/run_spume.h"
#include "tests/compare/compare_test_support.h"
#include "render/image/png_io.h"

namespace spume {
namespace {

namespace fs = std::filesystem;
using testing::CommandResult;
using testing::flat_image;
using testing::run_command;
using testing::run_spume;
using testing::fresh_dir;

std::string browser() {
  for (const char* path : {"/usr/bin/chromium", "/usr/bin/chromium-browser"})
    if (access(path, X_OK) == 0) return path;
  return "";
}

// The DOM after the page's scripts ran and its load event fired.
std::string dump_dom(const fs::path& page, const std::string& fragment = "") {
  char profile[] = "/tmp/spume_chromium_XXXXXX";  // a fresh profile: no state from other runs
  if (!mkdtemp(profile)) return "";
  const fs::path err = fs::path(profile).string() + ".log";
  const std::string command =
      "timeout 120 " + browser() +
      " --headless --no-sandbox --disable-gpu --disable-quic --no-first-run --disable-background-networking"
      " --disable-component-update --disable-sync --user-data-dir=" + std::string(profile) +
      " --dump-dom 'file://" + fs::absolute(page).string() + fragment + "' 2>" + err.string();
  const CommandResult r = run_command(command);
  EXPECT_EQ(r.status, 0) << command << "\n" << testing::read_file(err);
  fs::remove_all(profile);
  fs::remove(err);
  return r.output;
}

std::string attribute(const std::string& tag, const std::string& name) {
  std::smatch m;
  if (std::regex_search(tag, m, std::regex("\\s" + name + "=\"([^\"]*)\""))) return m[1];
  return "<absent>";
}

std::string element_tag(const std::string& dom, const std::string& id) {
  std::smatch m;
  if (std::regex_search(dom, m, std::regex("<[a-z]+ [^>]*id=\"" + id + "\"[^>]*>"))) return m[0];
  return "";
}

std::string body_tag(const std::string& dom) {
  std::smatch m;
  return std::regex_search(dom, m, std::regex("<body[^>]*>")) ? m.str() : "";
}

std::string row_tag(const std::string& dom, const std::string& frame) {
  std::smatch m;
  return std::regex_search(dom, m, std::regex("<tr [^>]*data-frame=\"" + frame + "\"[^>]*>")) ? m.str() : "";
}

struct Row {
  std::string frame, verdict;
};

std::vector<Row> table_rows(const std::string& dom) {
  std::vector<Row> rows;
  const std::regex tr("<tr [^>]*data-index=[^>]*>");
  for (auto it = std::sregex_iterator(dom.begin(), dom.end(), tr); it != std::sregex_iterator(); ++it)
    rows.push_back({attribute(it->str(), "data-frame"), attribute(it->str(), "data-verdict")});
  return rows;
}

std::string frame_name(int f) {
  char name[32];
  std::snprintf(name, sizeof name, "%04d.png", f);
  return name;
}

// Six frames: identical, over the thresholds, missing in new, other size, within the thresholds,
// unreadable.
fs::path make_report(const std::string& name) {  // each test its own folder: ctest runs them in parallel
  const fs::path dir = fresh_dir(name);
  for (int f = 0; f < 6; ++f) write_png(dir / "ref" / frame_name(f), testing::random_image(64, 36, uint32_t(f)));
  write_png(dir / "new" / frame_name(0), testing::random_image(64, 36, 0));
  ImageRGB8 changed = testing::random_image(64, 36, 1);
  for (int y = 10; y < 16; ++y)
    for (int x = 20; x < 26; ++x) changed.at(x, y)[1] = uint8_t(changed.at(x, y)[1] ^ 0x40);
  write_png(dir / "new" / frame_name(1), changed);
  write_png(dir / "new" / frame_name(3), testing::random_image(32, 18, 3));
  ImageRGB8 nearly = testing::random_image(64, 36, 4);
  nearly.at(3, 3)[0] = uint8_t(nearly.at(3, 3)[0] ^ 1);
  write_png(dir / "new" / frame_name(4), nearly);
  testing::write_file(dir / "new" / frame_name(5), "truncated");
  const CommandResult r = run_spume("compare --quiet '" + (dir / "ref").string() + "' '" + (dir / "new").string() +
                                     "' --out '" + (dir / "out").string() + "'");
  EXPECT_EQ(r.status, 1) << r.output;
  return dir / "out" / "report.html";
}

TEST(ReportBrowser, ShowsFramesWorstFirstWithVerdictsAndLoadsTheViewer) {
  if (browser().empty()) GTEST_SKIP() << "no Chromium installed (apt-get install chromium)";
  const fs::path page = make_report("browser_dom");
  const std::string html = testing::read_file(page);
  // Self-contained: nothing is fetched from a network.
  EXPECT_EQ(html.find("http://"), std::string::npos);
  EXPECT_EQ(html.find("https://"), std::string::npos);
  EXPECT_EQ(html.find("<link"), std::string::npos);
  EXPECT_EQ(html.find("<script src"), std::string::npos);

  const std::string dom = dump_dom(page);
  const std::string body = body_tag(dom);
  EXPECT_EQ(attribute(body, "data-status"), "ready") << body;
  EXPECT_EQ(attribute(body, "data-verdict"), "fail");
  EXPECT_NE(attribute(element_tag(dom, "script-error"), "hidden"), "<absent>");
  const std::vector<Row> rows = table_rows(dom);
  const std::vector<std::pair<std::string, std::string>> expected = {
      {"0005.png", "unreadable"}, {"0002.png", "missing"}, {"0003.png", "size-mismatch"},
      {"0001.png", "fail"},       {"0004.png", "pass"},    {"0000.png", "identical"}};
  ASSERT_EQ(rows.size(), expected.size()) << dom;
  for (size_t i = 0; i < rows.size(); ++i) {
    EXPECT_EQ(rows[i].frame, expected[i].first) << "row " << i;
    EXPECT_EQ(rows[i].verdict, expected[i].second) << "row " << i;
  }
  // The viewer opens on the worst frame; only its reference decoded, and that image loaded.
  const std::string viewer = element_tag(dom, "viewer");
  EXPECT_EQ(attribute(viewer, "hidden"), "<absent>") << viewer;
  EXPECT_EQ(attribute(viewer, "data-frame"), "0005.png") << viewer;
  EXPECT_EQ(attribute(viewer, "data-images"), "loaded") << viewer;
  EXPECT_EQ(attribute(element_tag(dom, "v-ref"), "data-state"), "loaded");
  EXPECT_EQ(attribute(element_tag(dom, "v-new"), "data-state"), "none");
  EXPECT_NE(dom.find("<circle class=\"marker fail\" data-index=\"1\""), std::string::npos);
  EXPECT_EQ(attribute(element_tag(dom, "plot-cursor"), "visibility"), "visible");

  // Addressed by its anchor, the failing frame shows reference, new and its heat map, all loaded.
  const std::string failing = dump_dom(page, "#f-0001");
  EXPECT_EQ(attribute(body_tag(failing), "data-status"), "ready");
  const std::string v = element_tag(failing, "viewer");
  EXPECT_EQ(attribute(v, "data-frame"), "0001.png") << v;
  EXPECT_EQ(attribute(v, "data-images"), "loaded") << v;
  for (const char* id : {"v-ref", "v-new", "v-extra"})
    EXPECT_EQ(attribute(element_tag(failing, id), "data-state"), "loaded") << id;
  EXPECT_NE(element_tag(failing, "v-extra").find("diff/0001_heat.png"), std::string::npos);
  EXPECT_EQ(attribute(row_tag(failing, "0001.png"), "class"), "fail current");
}

// Drives the page as a person would (clicks, the slider, keys, the order and filter controls) from a
// script appended to a copy of it, which records every expectation that did not hold in
// <body data-test>.
const char* const kInteractionScript = R"JS(<script>
(function () {
  var failed = [];
  function check(name, ok) { if (!ok) failed.push(name); }
  function $(id) { return document.getElementById(id); }
  function mode(m) { document.querySelector('[data-mode="' + m + '"]').click(); }
  document.querySelector('tr[data-frame="0001.png"]').click();
  check('a row click opens its frame', $('viewer').getAttribute('data-frame') === '0001.png');
  mode('heat');
  check('heat map', $('v-extra').style.visibility === 'visible' && /diff\/0001_heat\.png$/.test($('v-extra').getAttribute('src')));
  mode('diff');
  check('difference', /diff\/0001_diff\.png$/.test($('v-extra').getAttribute('src')));
  mode('flip');
  check('flip shows the reference first', $('v-tag').textContent === 'reference' && $('v-new').style.visibility === 'hidden');
  $('v-frame').dispatchEvent(new PointerEvent('pointerdown', { bubbles: true }));
  check('a click flips to new', $('v-tag').textContent === 'new' && $('v-new').style.visibility === 'visible' &&
        $('v-ref').style.visibility === 'hidden');
  mode('slider');
  $('v-slider').value = 250;
  $('v-slider').dispatchEvent(new Event('input'));
  check('the slider clips new at 25%', /25%\)$/.test($('v-new').style.clipPath) && $('v-divider').style.left === '25%');
  document.dispatchEvent(new KeyboardEvent('keydown', { key: 'j' }));
  check('j opens the next row', $('viewer').getAttribute('data-frame') === '0004.png');
  document.querySelector('tr[data-frame="0002.png"]').click();
  check('a frame missing in new shows its reference', document.querySelector('[data-mode="slider"]').disabled &&
        $('v-tag').textContent === 'reference');
  document.querySelector('tr[data-frame="0003.png"]').click();
  check('images of two sizes are not overlaid', document.querySelector('[data-mode="slider"]').disabled &&
        document.querySelector('[data-mode="flip"]').disabled && !document.querySelector('[data-mode="new"]').disabled);
  mode('new');
  check('new at its own size', $('v-frame').style.aspectRatio.replace(/ /g, '') === '32/18');
  $('order').value = 'sequence';
  $('order').dispatchEvent(new Event('change'));
  check('sequence order', document.querySelector('#frame-table tbody tr').getAttribute('data-frame') === '0000.png');
  $('only-failing').checked = true;
  $('only-failing').dispatchEvent(new Event('change'));
  var shown = Array.prototype.filter.call(document.querySelectorAll('#frame-table tbody tr'), function (r) { return !r.hidden; });
  check('failing frames only', shown.length === 4);
  document.querySelector('#error-plot circle[data-index="1"]').dispatchEvent(new MouseEvent('click', { bubbles: true }));
  check('a plot point opens its frame', $('viewer').getAttribute('data-frame') === '0001.png');
  document.body.setAttribute('data-test', failed.length ? 'failed: ' + failed.join('; ') : 'passed');
})();
</script>
)JS";

TEST(ReportBrowser, ViewerAndTableRespondToClicksKeysAndControls) {
  if (browser().empty()) GTEST_SKIP() << "no Chromium installed (apt-get install chromium)";
  const fs::path page = make_report("browser_driven");
  std::string html = testing::read_file(page);
  const size_t end = html.rfind("</body>");
  ASSERT_NE(end, std::string::npos);
  html.insert(end, kInteractionScript);
  const fs::path driven = page.parent_path() / "driven.html";  // beside it: the same relative links
  testing::write_file(driven, html);
  const std::string dom = dump_dom(driven);
  EXPECT_EQ(attribute(body_tag(dom), "data-status"), "ready");
  EXPECT_EQ(attribute(body_tag(dom), "data-test"), "passed");
}

TEST(ReportBrowser, BrokenPageDataSetsTheErrorMarker) {
  if (browser().empty()) GTEST_SKIP() << "no Chromium installed (apt-get install chromium)";
  const fs::path page = make_report("browser_broken");
  std::string html = testing::read_file(page);
  const std::string open = "<script type=\"application/json\" id=\"compare-data\">";
  const size_t at = html.find(open);
  ASSERT_NE(at, std::string::npos);
  html.insert(at + open.size(), "{broken");
  const fs::path broken = page.parent_path() / "broken.html";
  testing::write_file(broken, html);
  const std::string dom = dump_dom(broken);
  EXPECT_EQ(attribute(body_tag(dom), "data-status"), "error");
  const std::string box = element_tag(dom, "script-error");
  EXPECT_EQ(attribute(box, "hidden"), "<absent>") << box;
  EXPECT_NE(dom.find("The report script failed"), std::string::npos);
}

TEST(ReportBrowser, ThousandsOfFramesLoadWithLazyThumbnails) {
  if (browser().empty()) GTEST_SKIP() << "no Chromium installed (apt-get install chromium)";
  const fs::path dir = fresh_dir("browser_many");
  const int n = 1200;
  for (int f = 0; f < n; ++f) {
    const ImageRGB8 img = flat_image(16, 9, uint8_t(f % 200));
    write_png(dir / "ref" / frame_name(f), img);
    write_png(dir / "new" / frame_name(f), f % 100 == 7 ? flat_image(16, 9, uint8_t(f % 200 + 20)) : img);
  }
  const CommandResult r = run_spume("compare --quiet '" + (dir / "ref").string() + "' '" + (dir / "new").string() +
                                     "' --out '" + (dir / "out").string() + "'");
  ASSERT_EQ(r.status, 1) << r.output;
  const std::string dom = dump_dom(dir / "out" / "report.html");
  EXPECT_EQ(attribute(body_tag(dom), "data-status"), "ready");
  const std::vector<Row> rows = table_rows(dom);
  ASSERT_EQ(rows.size(), size_t(n));
  for (size_t i = 0; i < 12; ++i) EXPECT_EQ(rows[i].verdict, "fail") << i;  // frames 7, 107, ..., 1107
  EXPECT_EQ(rows[12].verdict, "identical");
  // Every thumbnail waits until it is scrolled near: 2 a frame, 3 for a failing one.
  const std::string html = testing::read_file(dir / "out" / "report.html");
  size_t lazy = 0;
  for (size_t p = 0; (p = html.find("<img loading=\"lazy\"", p)) != std::string::npos; ++p) ++lazy;
  EXPECT_EQ(lazy, size_t(2 * n + 12));
}

}  // namespace
}  // namespace spume
