#include "bench/output/html_report.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <iterator>
#include <string>
#include <string_view>
#include <vector>

#include "bench/output/base64.hpp"
#include "bench/output/html_report_markdown.hpp"
#include "core/errors.hpp"
#include "io/read_file.hpp"
#include "tests/support/temp_dir.hpp"
#include "viz/image.hpp"

namespace retrace::bench {
namespace {

using HtmlReportFolder = retrace::testing::TempDirTest;

// Writes a file below the test's folder, creating its folders.
void Put(const retrace::testing::TempDir& tmp, const std::filesystem::path& name,
         std::string_view bytes) {
  std::filesystem::create_directories((tmp.path() / name).parent_path());
  tmp.Write(name, bytes);
}

std::size_t Count(const std::string& text, const std::string& what) {
  std::size_t n = 0;
  for (std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

TEST(HtmlEscape, EscapesTheFiveSpecialCharactersAndNothingElse) {
  EXPECT_EQ(HtmlEscape("<a href=\"x\">Tom & Jerry's</a>"),
            "&lt;a href=&quot;x&quot;&gt;Tom &amp; Jerry&#39;s&lt;/a&gt;");
  EXPECT_EQ(HtmlEscape("plain text, 0.5 m — ü"), "plain text, 0.5 m — ü");
  EXPECT_EQ(HtmlEscape("&amp;"), "&amp;amp;");  // escaped again: text is never trusted as HTML
  EXPECT_EQ(HtmlEscape(""), "");
}

TEST(Base64, MatchesTheRfc4648TestVectors) {
  EXPECT_EQ(Base64Encode(""), "");
  EXPECT_EQ(Base64Encode("f"), "Zg==");
  EXPECT_EQ(Base64Encode("fo"), "Zm8=");
  EXPECT_EQ(Base64Encode("foo"), "Zm9v");
  EXPECT_EQ(Base64Encode("foob"), "Zm9vYg==");
  EXPECT_EQ(Base64Encode("fooba"), "Zm9vYmE=");
  EXPECT_EQ(Base64Encode("foobar"), "Zm9vYmFy");
}

TEST(Base64, EncodesEveryByteValue) {
  EXPECT_EQ(Base64Encode(std::string("\xff\xfe\xfd", 3)), "//79");  // vectors: Python base64
  EXPECT_EQ(Base64Encode(std::string("\x00\x00", 2)), "AAA=");
  EXPECT_EQ(Base64Encode("\x89PNG\r\n\x1a\n"), "iVBORw0KGgo=");
  std::string all;
  for (int b = 0; b < 256; ++b) all += static_cast<char>(b);
  const std::string encoded = Base64Encode(all);
  EXPECT_EQ(encoded.size(), 344u);  // 4 * ceil(256 / 3)
  EXPECT_EQ(encoded.substr(0, 12), "AAECAwQFBgcI");
  EXPECT_EQ(encoded.substr(encoded.size() - 8), "/P3+/w==");
}

TEST(MarkdownToHtml, RendersTablesWithAlignmentAndEscapesCells) {
  const std::string html = MarkdownToHtml(
      "# Title\n\nSome `code` and **bold**.\n\n| metric | value |\n|---|---:|\n"
      "| <script>alert(1)</script> | 0.5 [0.4, 0.6] * |\n\n- one\n- two\n");
  EXPECT_NE(html.find("<h3>Title</h3>"), std::string::npos);
  EXPECT_NE(html.find("<code>code</code>"), std::string::npos);
  EXPECT_NE(html.find("<strong>bold</strong>"), std::string::npos);
  EXPECT_NE(html.find("<th>metric</th>"), std::string::npos);
  EXPECT_NE(html.find("<td style=\"text-align:right\">0.5 [0.4, 0.6] *</td>"), std::string::npos);
  EXPECT_NE(html.find("&lt;script&gt;alert(1)&lt;/script&gt;"), std::string::npos);
  EXPECT_EQ(html.find("<script>"), std::string::npos);
  EXPECT_NE(html.find("<li>two</li>"), std::string::npos);
}

// A run-like folder: one mode's metrics, manifest and figure, and a compare's comparison.json.
TEST_F(HtmlReportFolder, HoldsEverySectionAndEmbedsTheFigure) {
  const std::filesystem::path dir = tmp_.path() / "results";
  std::filesystem::create_directories(dir / "partial" / "figures");
  viz::Image image(4, 3);
  image.rgb[0] = 255;
  viz::WritePng(image, dir / "partial" / "figures" / "maps.png");
  const std::string png = io::ReadFileBytes(dir / "partial" / "figures" / "maps.png");
  Put(tmp_, "results/partial/metrics.json", R"({"mode": "partial", "aggregate": {
      "runs": 2, "successes": 2, "outcomes": {"success": 2, "lost": 0},
      "tracking_error_m": {"pooled": {"rms": 0.0123, "max": null}}}, "runs": []})");
  Put(tmp_, "results/partial/manifest.yaml",
      "command: retrace run <b>x</b>.yaml\nseed: 7\ngit_revision: abc123\n"
      "build_type: Release\nwall_time_s: 12.5\nwarnings: []\nconfig:\n  name: tiny\n");
  Put(tmp_, "results/comparison.json", R"({"confidence": 0.95, "reference": "consistent",
      "command": "retrace compare tiny.yaml", "git_revision": "abc123",
      "metrics": [{"key": "success_rate", "label": "success rate", "unit": "fraction"}],
      "modes": {"consistent": {"success_rate": {"mean": 1.0, "ci95": [1.0, 1.0]}},
                "partial": {"success_rate": {"mean": 0.75, "ci95": [0.5, 1.0],
                    "vs_reference": {"mean": -0.25, "ci95": [-0.5, 0.0], "significant": true}}}}})");

  const HtmlReport report = WriteHtmlReport(dir);
  EXPECT_EQ(report.kind, "run");
  EXPECT_EQ(report.images, 1);
  const std::string html = tmp_.Read("results/report.html");
  EXPECT_EQ(html, report.html);
  for (const char* section : {"summary", "comparison", "figures", "provenance", "files"})
    EXPECT_NE(html.find("<section id=\"" + std::string(section) + "\">"), std::string::npos)
        << section;
  // The summary: success as s/r, the metric, undefined values as n/a.
  EXPECT_NE(html.find("<td>2/2</td>"), std::string::npos);
  EXPECT_NE(html.find("0.0123"), std::string::npos);
  EXPECT_NE(html.find("tracking error RMS (m)"), std::string::npos);
  // The comparison's intervals.
  EXPECT_NE(html.find("0.75 [0.5, 1]"), std::string::npos);
  EXPECT_NE(html.find("-0.25 [-0.5, 0] *"), std::string::npos);
  // The manifest, escaped; its config folded away.
  EXPECT_NE(html.find("retrace run &lt;b&gt;x&lt;/b&gt;.yaml"), std::string::npos);
  EXPECT_EQ(html.find("<b>x</b>"), std::string::npos);
  EXPECT_NE(html.find("abc123"), std::string::npos);
  EXPECT_NE(html.find("<summary>config</summary>"), std::string::npos);
  // The figure, embedded whole, captioned; nothing outside the page.
  EXPECT_NE(html.find("src=\"data:image/png;base64," + Base64Encode(png) + "\""),
            std::string::npos);
  EXPECT_NE(html.find("partial/figures/maps.png</code>: the taught route"), std::string::npos);
  EXPECT_EQ(Count(html, "<img "), 1u);
  EXPECT_EQ(html.find("src=\"http"), std::string::npos);
  EXPECT_EQ(html.find("href=\"http"), std::string::npos);
  EXPECT_EQ(html.find("file:"), std::string::npos);
  EXPECT_NE(html.find("document.body.dataset.images"), std::string::npos);

  // Written atomically: no temporary left; made again, the same bytes.
  std::vector<std::string> names;
  for (const auto& entry : std::filesystem::directory_iterator(dir))
    names.push_back(entry.path().filename().string());
  std::sort(names.begin(), names.end());
  EXPECT_EQ(names, (std::vector<std::string>{"comparison.json", "partial", "report.html"}));
  EXPECT_EQ(WriteHtmlReport(dir).html, html);
}

TEST_F(HtmlReportFolder, ShowsASuitesRegressionsInRed) {
  Put(tmp_, "bench/report.json", R"({"suite": "ci", "verdict": "FAIL",
      "counts": {"checked": 2, "failures": 1, "improved": 0, "reported": 0},
      "rows": [
        {"metric": "office.partial.success_rate", "baseline": 1.0, "now": 0.5, "delta": -0.5,
         "seed_sd": 0.1, "tolerance": "abs 0.13", "pattern": "*.*.success_rate",
         "verdict": "FAIL", "reason": "worse by more than 0.13"},
        {"metric": "office.partial.repeatability_m", "baseline": 0.02, "now": 0.021,
         "delta": 0.001, "seed_sd": 0.001, "tolerance": "abs 0.01", "pattern": "*.*.*",
         "verdict": "pass", "reason": ""}]})");
  const HtmlReport report = BuildHtmlReport(tmp_.path() / "bench");
  EXPECT_EQ(report.kind, "bench");
  const std::string& html = report.html;
  EXPECT_NE(html.find("<section id=\"suite\">"), std::string::npos);
  EXPECT_NE(html.find("<span class=\"fail-text\">FAIL</span>"), std::string::npos);
  // In the regressions table and in the table of every metric, both red.
  EXPECT_EQ(Count(html, "<tr class=\"fail\"><td>office.partial.success_rate</td>"), 2u);
  EXPECT_NE(html.find("<td class=\"num\">-0.5</td><td>abs 0.13</td><td>worse by more than "
                      "0.13</td>"),
            std::string::npos);
  EXPECT_EQ(Count(html, "<tr class=\"fail\">"), 2u);
  EXPECT_NE(html.find("<tr><td>office.partial.repeatability_m</td>"), std::string::npos);
}

TEST_F(HtmlReportFolder, CapsASweepsResultsTable) {
  std::string csv = "case,combo,repeat,seed,nav.localizer.particles,success_rate\n";
  for (int i = 0; i < 250; ++i) csv += std::to_string(i) + ",0,0,1,100,1\n";
  Put(tmp_, "sweep/results.csv", csv);
  Put(tmp_, "sweep/sweep.json", R"({"name": "particles", "cases": 250, "complete": true,
      "command": "retrace sweep particles.yaml", "git_revision": "abc", "wall_time_s": 3.5})");
  const HtmlReport report = BuildHtmlReport(tmp_.path() / "sweep");
  EXPECT_EQ(report.kind, "sweep");
  EXPECT_NE(report.html.find("The first 200 of 250 rows"), std::string::npos);
  EXPECT_NE(report.html.find("<td class=\"num\">199</td>"), std::string::npos);
  EXPECT_EQ(report.html.find("<td class=\"num\">200</td>"), std::string::npos);
  EXPECT_NE(report.html.find("retrace sweep particles.yaml"), std::string::npos);
}

TEST_F(HtmlReportFolder, ListsWhatAnUnknownFolderHolds) {
  Put(tmp_, "any/notes <1>.txt", "hello");
  Put(tmp_, "any/sub/data.bin", "xyz");
  const HtmlReport report = BuildHtmlReport(tmp_.path() / "any");
  EXPECT_EQ(report.kind, "folder");
  EXPECT_EQ(report.images, 0);
  EXPECT_NE(report.html.find("notes &lt;1&gt;.txt  (5 bytes)"), std::string::npos);
  EXPECT_NE(report.html.find("sub/data.bin"), std::string::npos);
  EXPECT_NE(report.html.find("No PNG figures"), std::string::npos);
}

TEST_F(HtmlReportFolder, RefusesBadInputAndWritesNothing) {
  EXPECT_THROW(WriteHtmlReport(tmp_.path() / "missing"), core::IoError);
  EXPECT_FALSE(std::filesystem::exists(tmp_.path() / "missing"));
  Put(tmp_, "file.txt", "x");
  EXPECT_THROW(WriteHtmlReport(tmp_.path() / "file.txt"), core::IoError);

  Put(tmp_, "run/partial/manifest.yaml", "command: [unclosed\n");
  try {
    WriteHtmlReport(tmp_.path() / "run");
    ADD_FAILURE() << "no error for a malformed manifest";
  } catch (const core::IoError& e) {
    EXPECT_NE(std::string(e.what()).find("manifest.yaml: cannot read the manifest"),
              std::string::npos)
        << e.what();
  }
  EXPECT_FALSE(std::filesystem::exists(tmp_.path() / "run" / "report.html"));
  EXPECT_EQ(std::distance(std::filesystem::directory_iterator(tmp_.path() / "run"),
                          std::filesystem::directory_iterator{}),
            1);  // partial/ only: no temporary file
}

}  // namespace
}  // namespace retrace::bench
