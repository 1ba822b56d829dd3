// The clinical relationships as rows, a report section and change lines
// (relationships_table.h). Normal ranges: ../shared/docs/clinical.md.
#include "report/relationships_table.h"

#include <cmath>
#include <sstream>

#include "base/text_format.h"
#include "viewer/html_text.h"

namespace occlude::app {
namespace {

constexpr double kNormalIncisorMinMm = 1.0;  // overjet and overbite: 1-3 mm
constexpr double kNormalIncisorMaxMm = 3.0;
constexpr double kAcceptableMidlineMm = 2.0;  // |midline deviation| <= 2 mm
constexpr double kClassIMm = 1.5;             // Class I: |offset| <= 1.5 mm

std::string MmText(double mm) { return Fixed(mm, 2) + " mm"; }

RelationshipRow IncisorRow(const std::string& name, const analysis::Measure& m) {
  RelationshipRow row{name, m.mm, m.mm ? MmText(*m.mm) : "not found", "1 to 3 mm", false, m.note};
  row.outside = m.mm && (*m.mm < kNormalIncisorMinMm || *m.mm > kNormalIncisorMaxMm);
  return row;
}

RelationshipRow SideRow(const std::string& name, const analysis::SideRelationship& s) {
  RelationshipRow row{name,  s.offset.mm,  "not found", "Class I: -1.5 to 1.5 mm",
                      false, s.offset.note};
  if (s.offset.mm) {
    row.value = MmText(*s.offset.mm);
    if (s.occlusion_class) {
      row.value += std::string(" (Class ") + analysis::ToString(*s.occlusion_class) +
                   (s.end_on ? ", end-on)" : ")");
    }
    row.outside = std::abs(*s.offset.mm) > kClassIMm;
  }
  return row;
}

std::string ToothList(const std::vector<int>& teeth) {
  std::string out;
  for (const int t : teeth) out += (out.empty() ? "" : ", ") + std::to_string(t);
  return out;
}

RelationshipRow CrossbiteRow(const analysis::Relationships& r) {
  RelationshipRow row{
      "posterior crossbite", std::nullopt, "none", "none", !r.crossbite.empty(), ""};
  if (!r.crossbite.empty()) row.value = ToothList(r.crossbite);
  if (!r.crossbite_unchecked.empty()) {
    row.reason = "not checked (a landmark missing): " + ToothList(r.crossbite_unchecked);
  }
  if (r.frame_source.empty()) {
    row.value = "not found";
    row.reason = "no frame to measure in";
  }
  return row;
}

}  // namespace

std::vector<RelationshipRow> RelationshipRows(const analysis::Relationships& r) {
  std::vector<RelationshipRow> rows = {IncisorRow("overjet", r.overjet),
                                       IncisorRow("overbite", r.overbite)};
  const analysis::Measure& mid = r.midline_deviation;
  rows.push_back({"midline deviation", mid.mm, mid.mm ? MmText(*mid.mm) : "not found", "-2 to 2 mm",
                  mid.mm && std::abs(*mid.mm) > kAcceptableMidlineMm, mid.note});
  rows.push_back(SideRow("molar relationship, right", r.molar[0]));
  rows.push_back(SideRow("molar relationship, left", r.molar[1]));
  rows.push_back(SideRow("canine relationship, right", r.canine[0]));
  rows.push_back(SideRow("canine relationship, left", r.canine[1]));
  rows.push_back(CrossbiteRow(r));
  return rows;
}

std::string RelationshipsHtml(const analysis::Relationships& r) {
  std::ostringstream s;
  s << "<h2>Clinical relationships</h2>\n<p class=\"note\">"
    << (r.frame_source.empty() ? std::string("No frame to measure in.")
                               : "Measured in the frame from the " + HtmlEscape(r.frame_source) +
                                     " (definitions and normal ranges: clinical.md).")
    << "</p>\n<table class=\"grid\"><tr><th>measure</th><th>value</th><th>normal</th>"
       "<th>note</th></tr>\n";
  for (const RelationshipRow& row : RelationshipRows(r)) {
    s << "<tr><td>" << HtmlEscape(row.name) << "</td><td" << (row.outside ? " class=\"bad\"" : "")
      << ">" << HtmlEscape(row.value) << (row.outside ? " (outside)" : "") << "</td><td>"
      << HtmlEscape(row.normal) << "</td><td class=\"note\">" << HtmlEscape(row.reason)
      << "</td></tr>\n";
  }
  s << "</table>\n";
  return s.str();
}

std::vector<std::string> RelationshipChanges(const analysis::Relationships& before,
                                             const analysis::Relationships& after) {
  const std::vector<RelationshipRow> b = RelationshipRows(before), a = RelationshipRows(after);
  std::vector<std::string> lines;
  for (std::size_t i = 0; i < a.size(); ++i) {
    lines.push_back(a[i].name + ": " + b[i].value + " -> " + a[i].value +
                    (a[i].outside ? " (outside " + a[i].normal + ")" : ""));
  }
  return lines;
}

}  // namespace occlude::app
