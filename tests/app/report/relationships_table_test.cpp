// The clinical relationships as a reader sees them: rows with clinical.md's normal ranges and
// outside values marked, missing measures "not found" with their reason (in the rows, the
// report's table and the JSON), and refine's before -> after lines.
#include "report/relationships_table.h"

#include <gtest/gtest.h>

#include <string>

#include "report/relationships_json_internal.h"

namespace occlude::test {
namespace {

using analysis::Relationships;
using app::RelationshipChanges;
using app::RelationshipFrameJson;
using app::RelationshipRow;
using app::RelationshipRows;
using app::RelationshipsHtml;
using app::RelationshipsJson;

// Every measure found, inside its normal range except the left molar (Class II) and the
// overjet (4.2 mm); the right canine not found.
Relationships Sample() {
  Relationships r;
  r.frame_source = "landmarks";
  r.overjet = {4.2, ""};
  r.overbite = {2.0, ""};
  r.midline_deviation = {-0.5, ""};
  r.molar[0] = analysis::Classify({0.3, ""});
  r.molar[1] = analysis::Classify({2.5, ""});
  r.canine[0] = analysis::Classify({std::nullopt, "no upper 13 cusp_tip"});
  r.canine[1] = analysis::Classify({-0.2, ""});
  r.crossbite = {15};
  return r;
}

TEST(RelationshipsTable, RowsCarryValuesRangesAndOutsideMarks) {
  const std::vector<RelationshipRow> rows = RelationshipRows(Sample());
  ASSERT_EQ(rows.size(), 8u);
  EXPECT_EQ(rows[0].name, "overjet");
  EXPECT_EQ(rows[0].value, "4.20 mm");
  EXPECT_EQ(rows[0].normal, "1 to 3 mm");
  EXPECT_TRUE(rows[0].outside);
  EXPECT_FALSE(rows[1].outside);  // overbite 2.0
  EXPECT_FALSE(rows[2].outside);  // midline -0.5
  EXPECT_EQ(rows[3].value, "0.30 mm (Class I)");
  EXPECT_FALSE(rows[3].outside);
  EXPECT_EQ(rows[4].value, "2.50 mm (Class II, end-on)");
  EXPECT_TRUE(rows[4].outside);
  EXPECT_EQ(rows[5].value, "not found");
  EXPECT_FALSE(rows[5].mm.has_value());
  EXPECT_EQ(rows[5].reason, "no upper 13 cusp_tip");
  EXPECT_EQ(rows[7].name, "posterior crossbite");
  EXPECT_EQ(rows[7].value, "15");
  EXPECT_TRUE(rows[7].outside);
}

TEST(RelationshipsTable, TheReportSectionMarksOutsideValuesAndSaysWhyOneIsMissing) {
  const std::string html = RelationshipsHtml(Sample());
  EXPECT_NE(html.find("<h2>Clinical relationships</h2>"), std::string::npos);
  EXPECT_NE(html.find("<td class=\"bad\">4.20 mm (outside)</td>"), std::string::npos) << html;
  EXPECT_NE(html.find("<td>2.00 mm</td>"), std::string::npos) << html;
  EXPECT_NE(html.find("not found"), std::string::npos);
  EXPECT_NE(html.find("no upper 13 cusp_tip"), std::string::npos);
  EXPECT_NE(html.find("landmarks"), std::string::npos);
}

TEST(RelationshipsTable, TheJsonHasNullWithAReasonForWhatIsMissing) {
  const nlohmann::json j = RelationshipsJson(Sample());
  EXPECT_DOUBLE_EQ(j["overjet_mm"].get<double>(), 4.2);
  EXPECT_FALSE(j.contains("overjet_reason"));
  EXPECT_DOUBLE_EQ(j["molar_mm"]["left"].get<double>(), 2.5);
  EXPECT_EQ(j["molar_class"]["left"], "II");
  EXPECT_EQ(j["molar_end_on"]["left"], true);
  EXPECT_TRUE(j["canine_mm"]["right"].is_null());
  EXPECT_TRUE(j["canine_class"]["right"].is_null());
  EXPECT_EQ(j["canine_reason"]["right"], "no upper 13 cusp_tip");
  EXPECT_TRUE(j["canine_reason"]["left"].is_null());
  EXPECT_EQ(j["crossbite"], nlohmann::json::array({15}));
  EXPECT_EQ(j["frame_source"], "landmarks");
  Relationships none;
  none.overjet.note = "no frame";
  const nlohmann::json n = RelationshipsJson(none);
  EXPECT_TRUE(n["overjet_mm"].is_null());
  EXPECT_EQ(n["overjet_reason"], "no frame");
  EXPECT_TRUE(n["frame_source"].is_null());
  EXPECT_TRUE(RelationshipFrameJson(none).is_null());
}

TEST(RelationshipsTable, ChangesReadBeforeArrowAfter) {
  Relationships after = Sample();
  after.overjet = {2.5, ""};
  const std::vector<std::string> lines = RelationshipChanges(Sample(), after);
  ASSERT_EQ(lines.size(), 8u);
  EXPECT_EQ(lines[0], "overjet: 4.20 mm -> 2.50 mm");
  EXPECT_EQ(lines[4],
            "molar relationship, left: 2.50 mm (Class II, end-on) -> 2.50 mm (Class II, end-on) "
            "(outside Class I: -1.5 to 1.5 mm)");
  EXPECT_EQ(lines[5], "canine relationship, right: not found -> not found");
}

}  // namespace
}  // namespace occlude::test
