// The viewer page without a browser: it is self-contained (no http or https
// resource), its embedded data decodes back to the display meshes, distances,
// colours and tooth numbers it was given, text is escaped, bad inputs name their
// field, and the colour ramp is the report's.
#include "viewer/viewer_page.h"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <regex>

#include "headless_browser.h"
#include "occlude/io/dental.h"
#include "report/report_colours.h"
#include "viewer/html_text.h"
#include "viewer/viewer_assets.h"
#include "viewer/viewer_data_internal.h"
#include "viewer_fixture.h"

namespace occlude::app {
namespace {

using nlohmann::json;

const test::ViewerFixture& Fixture() {
  static const auto f = test::MakeSyntheticViewer(2, 3000);
  return *f;
}

json PageData(const std::string& page) {
  const std::string open = "<script type=\"application/json\" id=\"occlude-viewer-data\">";
  const std::size_t begin = page.find(open);
  EXPECT_NE(begin, std::string::npos);
  const std::size_t end = page.find("</script>", begin);
  return json::parse(page.substr(begin + open.size(), end - begin - open.size()));
}

template <typename T>
std::vector<T> Array(const json& b64) {
  const std::string bytes = test::DecodeBase64(b64.get<std::string>());
  std::vector<T> out(bytes.size() / sizeof(T));
  std::memcpy(out.data(), bytes.data(), out.size() * sizeof(T));  // the test host is little-endian
  return out;
}

TEST(ViewerPageTest, HoldsNoHttpResourceAndInlinesThreeJs) {
  std::string page = ViewerPage(Fixture().inputs);
  EXPECT_NE(page.find("REVISION=\"111\""), std::string::npos) << "three.js r111 is inlined";
  EXPECT_NE(page.find("OrbitControls"), std::string::npos);
  // Nothing that would load a resource: no src/href/url()/import of any remote address.
  const std::regex reference(
      R"((src|href|action)\s*=\s*["']?\s*(https?:)?//|url\(\s*["']?\s*(https?:)?//|@import|importScripts|<link|<iframe)",
      std::regex::icase);
  EXPECT_FALSE(std::regex_search(page, reference));
  // Outside the two Debian libraries (whose only addresses are author credits in comments
  // and the XHTML namespace name), the page names no address at all.
  for (const char* library : {viewer_assets::kThreeJs, viewer_assets::kOrbitControlsJs}) {
    const std::size_t at = page.find(library);
    ASSERT_NE(at, std::string::npos);
    page.erase(at, std::string(library).size());
  }
  EXPECT_EQ(page.find("http://"), std::string::npos);
  EXPECT_EQ(page.find("https://"), std::string::npos);
}

TEST(ViewerPageTest, EmbeddedDataDecodesToTheDisplayMeshesAndDistances) {
  const test::ViewerFixture& f = Fixture();
  const json data = PageData(ViewerSection(f.inputs));
  ASSERT_EQ(data["jaws"].size(), 2u);
  const io::TriangleMesh* meshes[] = {&f.lower.mesh, &f.upper.mesh};
  for (int j = 0; j < 2; ++j) {
    const json& jaw = data["jaws"][j];
    const io::TriangleMesh& mesh = *meshes[j];
    const auto q = Array<std::uint16_t>(jaw["positions"]["data"]);
    ASSERT_EQ(q.size(), 3 * mesh.num_vertices());
    for (std::size_t v = 0; v < mesh.num_vertices(); ++v) {
      for (int k = 0; k < 3; ++k) {
        const double step = jaw["positions"]["step"][k];
        const double x = jaw["positions"]["origin"][k].get<double>() + q[3 * v + k] * step;
        EXPECT_NEAR(x, mesh.vertices[v][k], 0.5 * step + 1e-9);  // rounded to the 16-bit grid
      }
    }
    ASSERT_EQ(jaw["index"]["type"], "uint16");
    const auto index = Array<std::uint16_t>(jaw["index"]["data"]);
    const auto part = Array<std::uint8_t>(jaw["part"]["data"]);
    ASSERT_EQ(index.size(), 3 * mesh.num_triangles());
    for (std::size_t t = 0; t < mesh.num_triangles(); ++t) {
      for (int k = 0; k < 3; ++k) EXPECT_EQ(index[3 * t + k], mesh.triangles[t][k]);
      const json& names = jaw["part"]["names"][part[t]];
      const int universal = mesh.parts[mesh.triangle_part[t]].tooth_number;
      EXPECT_EQ(names["universal"], universal);
      EXPECT_EQ(names["fdi"], universal > 0 ? io::FdiFromUniversal(universal) : 0);
    }
  }
}

TEST(ViewerPageTest, ProposalsCarryPoseNumbersDistancesAndTheirColours) {
  const test::ViewerFixture& f = Fixture();
  const json data = PageData(ViewerSection(f.inputs));
  ASSERT_EQ(data["proposals"].size(), 2u);
  for (std::size_t i = 0; i < 2; ++i) {
    const ViewerProposal& in = f.inputs.proposals[i];
    const json& p = data["proposals"][i];
    EXPECT_EQ(p["label"], in.label);
    EXPECT_EQ(p["numbers"], json::parse(in.numbers_json));
    for (int k = 0; k < 16; ++k) EXPECT_EQ(p["X_LU"][k], in.X_LU.matrix().data()[k]);
    const auto codes = Array<std::int16_t>(p["lower"]["distance_um"]);
    const std::string colours = test::DecodeBase64(p["lower"]["colour"]);
    ASSERT_EQ(codes.size(), in.lower_distance_mm.size());
    for (std::size_t v = 0; v < codes.size(); ++v) {
      const float d = in.lower_distance_mm[v];
      if (d < 32.0f) {
        EXPECT_NEAR(codes[v] / 1000.0, d, 0.0005 + 1e-6) << v;
      }
      const Rgb8 c = ContactColour(d, f.inputs.scale);
      for (int k = 0; k < 3; ++k) EXPECT_EQ(static_cast<std::uint8_t>(colours[3 * v + k]), c[k]);
    }
  }
}

TEST(ViewerPageTest, DistanceCodesSaturateAndMarkFarSurface) {
  using viewer_detail::DistanceCode;
  EXPECT_EQ(DistanceCode(0.1234f), 123);
  EXPECT_EQ(DistanceCode(-0.0456f), -46);
  EXPECT_EQ(DistanceCode(-50.0f), -viewer_detail::kDistanceMaxCode);
  EXPECT_EQ(DistanceCode(32.7f), 32700);
  EXPECT_EQ(DistanceCode(40.0f), viewer_detail::kDistanceFarCode);
  EXPECT_EQ(DistanceCode(kContactFarValue), viewer_detail::kDistanceFarCode);
}

TEST(ViewerPageTest, TextIsEscapedAndCannotCloseTheDataScript) {
  test::ViewerFixture f = *test::MakeSyntheticViewer(1, 500);
  f.inputs.lower_L = &f.lower.mesh;
  f.inputs.upper_U = &f.upper.mesh;
  f.inputs.title = "<b>jaws</b> & \"teeth\"";
  f.inputs.proposals[0].label = "</script><script>alert(1)</script>";
  const std::string page = ViewerPage(f.inputs);
  EXPECT_NE(page.find("&lt;b&gt;jaws&lt;/b&gt; &amp; &quot;teeth&quot;"), std::string::npos);
  EXPECT_EQ(page.find("alert(1)</script>"), std::string::npos);
  EXPECT_EQ(PageData(page)["proposals"][0]["label"], f.inputs.proposals[0].label);
}

TEST(ViewerPageTest, BadInputsNameTheirField) {
  const test::ViewerFixture& f = Fixture();
  const auto expect_error = [](ViewerInputs in, const std::string& field) {
    try {
      ViewerSection(in);
      ADD_FAILURE() << "no error for " << field;
    } catch (const std::invalid_argument& e) {
      EXPECT_EQ(std::string(e.what()).rfind(field + ":", 0), 0u) << e.what();
    }
  };
  ViewerInputs no_lower = f.inputs;
  no_lower.lower_L = nullptr;
  expect_error(no_lower, "lower_L");
  ViewerInputs none = f.inputs;
  none.proposals.clear();
  expect_error(none, "proposals");
  ViewerInputs short_distances = f.inputs;
  short_distances.proposals[1].upper_distance_mm.pop_back();
  expect_error(short_distances, "proposals[1].upper_distance_mm");
  ViewerInputs nan_distance = f.inputs;
  nan_distance.proposals[0].lower_distance_mm[5] = std::nanf("");
  expect_error(nan_distance, "proposals[0].lower_distance_mm");
  ViewerInputs not_object = f.inputs;
  not_object.proposals[0].numbers_json = "[1, 2]";
  expect_error(not_object, "proposals[0].numbers_json");
  ViewerInputs not_json = f.inputs;
  not_json.proposals[1].numbers_json = "{area: 1}";
  expect_error(not_json, "proposals[1].numbers_json");
}

TEST(ViewerPageTest, ALivePageNamesItsStreamAndAProposalEventIsTheProposalsData) {
  const test::ViewerFixture& f = Fixture();
  EXPECT_TRUE(PageData(ViewerSection(f.inputs))["live"].is_null());
  ViewerInputs live = f.inputs;
  live.live_events_path = "/events";
  const json data = PageData(ViewerSection(live));
  EXPECT_EQ(data["live"], "/events");
  const std::string event = ViewerProposalEvent(live, live.proposals[1]);
  EXPECT_EQ(event.find('\n'), std::string::npos);  // one data: line
  EXPECT_EQ(json::parse(event), data["proposals"][1]);
  for (const char* bad : {"events", "//elsewhere.example/events", "http://x/events"}) {
    live.live_events_path = bad;
    try {
      ViewerSection(live);
      ADD_FAILURE() << "no error for " << bad;
    } catch (const std::invalid_argument& e) {
      EXPECT_EQ(std::string(e.what()).rfind("live_events_path:", 0), 0u) << e.what();
    }
  }
  ViewerProposal short_distances = f.inputs.proposals[0];
  short_distances.lower_distance_mm.pop_back();
  EXPECT_THROW(ViewerProposalEvent(f.inputs, short_distances), std::invalid_argument);
}

TEST(ContactColourTest, IsTheReportsRampAtEveryMicrometre) {
  const render::MapScale report;
  const ContactScale viewer;
  ASSERT_EQ(viewer.max_mm, report.max_mm);
  ASSERT_EQ(viewer.band_mm, report.band_mm);
  ASSERT_EQ(viewer.penetration_from_mm, report.penetration_from_mm);
  for (int um = -100; um <= 700; ++um) {
    const double d = um / 1000.0;
    const render::Rgb expected = render::DistanceColour(d, report);
    const Rgb8 got = ContactColour(d, viewer);
    EXPECT_TRUE(std::equal(got.begin(), got.end(), expected.begin())) << d << " mm";
  }
  EXPECT_TRUE(ContactColour(-0.02, viewer) == kContactPenetrationColour);
  EXPECT_TRUE(ContactColour(0.6, viewer) == kContactFarColour);
  const auto stops = ContactRampStops();
  EXPECT_EQ(stops.front().first, 0.0);
  EXPECT_EQ(stops.back().first, 1.0);
}

TEST(HtmlTextTest, Base64AndEscapes) {
  EXPECT_EQ(Base64(""), "");
  EXPECT_EQ(Base64("M"), "TQ==");
  EXPECT_EQ(Base64("Ma"), "TWE=");
  EXPECT_EQ(Base64("Man"), "TWFu");
  EXPECT_EQ(Base64(std::string("\xff\x00\x10", 3)), "/wAQ");
  const std::string bytes = "any bytes \x01\x02\xfe\xff of any length";
  EXPECT_EQ(test::DecodeBase64(Base64(bytes)), bytes);
  EXPECT_EQ(HtmlEscape("a<b>&\"'"), "a&lt;b&gt;&amp;&quot;&#39;");
  EXPECT_EQ(ScriptSafeJson(R"({"a":"</script>"})"), R"({"a":"\u003c/script>"})");
  EXPECT_EQ(json::parse(ScriptSafeJson(R"({"a":"</script>"})"))["a"], "</script>");
}

}  // namespace
}  // namespace occlude::app
