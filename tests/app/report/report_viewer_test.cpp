// The report's 3D view and coloured meshes on the synthetic pair (5,000 triangles per jaw,
// decimated to 2,000 for display): the view's distances are the analysis's at the kept
// vertices (which are original vertices), report.html holds the view, and upper_at_pose.ply /
// lower.ply carry every vertex of the full jaws at the pose with the contact colour and the
// analysis's distance; the display meshes through a cache are those made without one, from a
// hit too. (In a browser: tests/app/viewer/report_page_browser_test.cpp.)
#include "report/report_viewer.h"

#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <memory>
#include <nlohmann/json.hpp>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "config/case_config.h"
#include "occlude/io/mesh_io.h"
#include "report/relationships_table.h"
#include "report/report_writer.h"
#include "test_common.h"

namespace occlude::test {
namespace {

constexpr std::size_t kDisplayTriangles = 2000;
// Vertex coordinates go through float in the PLY file.
constexpr double kFloatMm = 1e-4;

struct ViewerCase {
  app::CaseConfig config;
  std::unique_ptr<app::CaseSession> session;
  app::ReportAnalysis analysis;
};

ViewerCase& Case() {
  static ViewerCase* c = [] {
    auto* x = new ViewerCase;
    x->config = app::ParseCaseConfig(
        "[synthetic]\ntriangles = 5000\nseed = 1\n[accuracy]\nvoxel_mm = 1.0\n[report]\n"
        "image_width_px = 300\n",
        "synthetic.toml");
    x->session = std::make_unique<app::CaseSession>(x->config);
    x->analysis =
        app::AnalyzePose(*x->session, Eigen::Isometry3d(Eigen::Translation3d(0, -0.1, 0)));
    return x;
  }();
  return *c;
}

std::string FileBytes(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// What the view lists beside a pose: the contact first (in the order given), then one entry per
// clinical relationship with the text of report.html's table, in clinical.md's order.
TEST(ReportViewerTest, NumbersListTheContactThenEveryRelationship) {
  ViewerCase& c = Case();
  const nlohmann::ordered_json numbers =
      nlohmann::ordered_json::parse(app::AnalysisNumbersJson(c.analysis));
  std::vector<std::string> keys;
  for (const auto& [key, value] : numbers.items()) keys.push_back(key);
  const std::vector<app::RelationshipRow> rows = app::RelationshipRows(c.analysis.relationships);
  ASSERT_EQ(keys.size(), 3 + rows.size()) << numbers.dump();
  EXPECT_EQ(keys[0], "contact area (mm\u00b2)");
  EXPECT_EQ(numbers[keys[0]].get<double>(), c.analysis.oracle.contact_area_mm2);
  bool some_value = false;
  for (std::size_t i = 0; i < rows.size(); ++i) {
    EXPECT_EQ(keys[3 + i], rows[i].name);
    const std::string shown = numbers[rows[i].name].get<std::string>();
    EXPECT_EQ(shown.rfind(rows[i].value, 0), 0u) << rows[i].name << ": " << shown;
    EXPECT_EQ(shown.find("(outside ") != std::string::npos, rows[i].outside) << shown;
    some_value = some_value || rows[i].mm.has_value();
  }
  // The synthetic pair's teeth are found: its overjet at least is a number of mm.
  EXPECT_TRUE(some_value);
  ASSERT_TRUE(c.analysis.relationships.overjet.mm.has_value());
  EXPECT_NE(numbers["overjet"].get<std::string>().find(" mm"), std::string::npos);
  EXPECT_THROW(app::WithRelationships("[1]", c.analysis.relationships), std::invalid_argument);
}

TEST(ReportViewerTest, ViewDistancesAreTheAnalysisAtTheKeptVertices) {
  ViewerCase& c = Case();
  const app::JawPair& jaws = c.session->jaws();
  const app::DisplayJaws display = app::DecimateJawsForViewer(jaws, nullptr, kDisplayTriangles);
  ASSERT_LE(display.lower.mesh.num_triangles(), kDisplayTriangles);
  ASSERT_LE(display.upper.mesh.num_triangles(), kDisplayTriangles);
  const app::ViewerProposal p = app::ViewerProposalOf(display, c.analysis, "x", "{}");
  EXPECT_TRUE(p.X_LU.isApprox(c.analysis.X_LU));
  ASSERT_EQ(p.lower_distance_mm.size(), display.lower.mesh.num_vertices());
  ASSERT_EQ(p.upper_distance_mm.size(), display.upper.mesh.num_vertices());
  int penetrating = 0;
  for (std::size_t i = 0; i < p.lower_distance_mm.size(); ++i) {
    const auto s = static_cast<std::size_t>(display.lower.source_vertex[i]);
    EXPECT_EQ(display.lower.mesh.vertices[i], jaws.lower_L->vertices[s]);
    EXPECT_EQ(p.lower_distance_mm[i], c.analysis.lower_vertex_mm[s]);
    penetrating += p.lower_distance_mm[i] < 0 ? 1 : 0;
  }
  EXPECT_GT(penetrating, 0) << "pushed 0.1 mm into the lower jaw, some display vertices penetrate";
  for (std::size_t i = 0; i < p.upper_distance_mm.size(); ++i) {
    const auto s = static_cast<std::size_t>(display.upper.source_vertex[i]);
    EXPECT_EQ(p.upper_distance_mm[i], c.analysis.upper_vertex_mm[s]);
  }
  app::ViewerInputs in = app::ReportViewerInputs(*c.session, display);
  in.proposals = {p};
  EXPECT_EQ(in.scale.max_mm, c.config.report.map_max_mm);
  EXPECT_EQ(in.axes.occlusal_L, c.session->arch().occlusal_L);
  EXPECT_NE(app::ViewerSection(in).find("id=\"occlude-viewer-canvas\""), std::string::npos);
}

// Reads vertex `i` of a binary coloured PLY (io/coloured_ply.h): position, colour, distance.
void ReadPlyVertex(const std::string& bytes, std::size_t i, Eigen::Vector3f* p, app::Rgb8* rgb,
                   float* distance_mm) {
  const std::size_t body = bytes.find("end_header\n") + std::strlen("end_header\n");
  const std::size_t at = body + i * (3 * sizeof(float) + 3 + sizeof(float));
  std::memcpy(p->data(), bytes.data() + at, 3 * sizeof(float));  // the test host is little-endian
  std::memcpy(rgb->data(), bytes.data() + at + 12, 3);
  std::memcpy(distance_mm, bytes.data() + at + 15, sizeof(float));
}

TEST(ReportViewerTest, ReportFilesHoldTheViewAndColouredMeshesOfBothJaws) {
  ViewerCase& c = Case();
  const app::JawPair& jaws = c.session->jaws();
  app::ReportAnalysis analysis = c.analysis;
  const app::ReportFiles files = app::MakeReportFiles(*c.session, analysis, "test");
  TempDir tmp;
  app::WriteReportFiles(tmp.path(), files);
  EXPECT_NE(FileBytes(tmp / "report.html").find("id=\"occlude-viewer-data\""), std::string::npos);
  const app::ContactScale scale{c.config.report.map_max_mm, c.config.contact_band_mm,
                                c.config.report.map_penetration_from_mm};
  struct Jaw {
    const char* file;
    io::TriangleMesh mesh;  // in L, at the pose
    const std::vector<float>* distance_mm;
  };
  const Jaw both[] = {{"upper_at_pose.ply", jaws.upper_U->Transformed(c.analysis.X_LU),
                       &c.analysis.upper_vertex_mm},
                      {"lower.ply", *jaws.lower_L, &c.analysis.lower_vertex_mm}};
  for (const Jaw& jaw : both) {
    const std::string bytes = FileBytes(tmp / jaw.file);
    ASSERT_NE(bytes.find("element vertex " + std::to_string(jaw.mesh.num_vertices()) + "\n"),
              std::string::npos)
        << jaw.file;
    EXPECT_NE(bytes.find("property float distance_mm\n"), std::string::npos) << jaw.file;
    for (std::size_t i = 0; i < jaw.mesh.num_vertices(); i += 97) {
      Eigen::Vector3f p;
      app::Rgb8 rgb;
      float d = 0;
      ReadPlyVertex(bytes, i, &p, &rgb, &d);
      EXPECT_LT((p.cast<double>() - jaw.mesh.vertices[i]).norm(), kFloatMm) << jaw.file << " " << i;
      EXPECT_EQ(d, (*jaw.distance_mm)[i]) << jaw.file << " " << i;
      EXPECT_EQ(rgb, app::ContactColour(d, scale)) << jaw.file << " " << i;
    }
    EXPECT_EQ(io::LoadMesh(tmp / jaw.file).num_triangles(), jaw.mesh.num_triangles()) << jaw.file;
  }
}

TEST(ReportViewerTest, DisplayMeshesThroughACacheAreThoseMadeWithout) {
  ViewerCase& c = Case();
  const app::JawPair& jaws = c.session->jaws();
  const app::DisplayJaws made = app::DecimateJawsForViewer(jaws, nullptr, kDisplayTriangles);
  TempDir dir;
  std::ostringstream warnings;
  app::OracleCacheSettings settings;
  settings.folder = dir.path();
  app::OracleCache cache(settings, &warnings);
  for (int run = 0; run < 2; ++run) {  // a miss that saves, then a hit
    const app::DisplayJaws got = app::DecimateJawsForViewer(jaws, &cache, kDisplayTriangles);
    for (const auto& [a, b] :
         {std::pair(&made.lower, &got.lower), std::pair(&made.upper, &got.upper)}) {
      EXPECT_EQ(a->mesh.vertices, b->mesh.vertices) << run;
      EXPECT_EQ(a->mesh.triangles, b->mesh.triangles) << run;
      EXPECT_EQ(a->mesh.face_normals, b->mesh.face_normals) << run;
      EXPECT_EQ(a->mesh.triangle_part, b->mesh.triangle_part) << run;
      EXPECT_EQ(a->source_vertex, b->source_vertex) << run;
      EXPECT_EQ(a->cell_mm, b->cell_mm) << run;
    }
  }
  // Both jaws' entries were written, and read back on the second run (not made again: an
  // entry made to differ is what a third run gets).
  const std::string lower_entry = app::ByteEntryName(
      app::kDisplayEntryKind, io::DecimationKey(*jaws.lower_L, {kDisplayTriangles}));
  ASSERT_TRUE(std::filesystem::exists(dir / lower_entry));
  io::DecimationResult marked = made.lower;
  marked.cell_mm += 1.0;
  cache.PutBytes(app::kDisplayEntryKind, io::DecimationKey(*jaws.lower_L, {kDisplayTriangles}),
                 io::EncodeDecimation(marked));
  EXPECT_EQ(app::DecimateJawsForViewer(jaws, &cache, kDisplayTriangles).lower.cell_mm,
            marked.cell_mm);
  EXPECT_TRUE(warnings.str().empty()) << warnings.str();
}

}  // namespace
}  // namespace occlude::test
