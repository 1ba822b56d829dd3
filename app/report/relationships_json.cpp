// The clinical relationships as JSON (relationships_json_internal.h).
#include "base/json_values.h"
#include "report/relationships_json_internal.h"

namespace occlude::app {
namespace {

using nlohmann::json;

json ValueOf(const analysis::Measure& m) { return m.mm ? json(*m.mm) : json(nullptr); }
json NoteOf(const std::string& note) { return note.empty() ? json(nullptr) : json(note); }

void PutMeasure(const std::string& name, const analysis::Measure& m, json* out) {
  (*out)[name + "_mm"] = ValueOf(m);
  if (!m.note.empty()) (*out)[name + "_reason"] = m.note;
}

json ClassOf(const analysis::SideRelationship& s) {
  return s.occlusion_class ? json(analysis::ToString(*s.occlusion_class)) : json(nullptr);
}

// molar_mm, molar_class, molar_end_on (and molar_reason when a side has a note) of both sides.
void PutSides(const std::string& name, const analysis::SideRelationship (&s)[2], json* out) {
  (*out)[name + "_mm"] = {{"right", ValueOf(s[0].offset)}, {"left", ValueOf(s[1].offset)}};
  (*out)[name + "_class"] = {{"right", ClassOf(s[0])}, {"left", ClassOf(s[1])}};
  (*out)[name + "_end_on"] = {{"right", s[0].end_on}, {"left", s[1].end_on}};
  if (!s[0].offset.note.empty() || !s[1].offset.note.empty()) {
    (*out)[name + "_reason"] = {{"right", NoteOf(s[0].offset.note)},
                                {"left", NoteOf(s[1].offset.note)}};
  }
}

}  // namespace

json RelationshipsJson(const analysis::Relationships& r) {
  json out = json::object();
  out["frame_source"] = r.frame_source.empty() ? json(nullptr) : json(r.frame_source);
  PutMeasure("overjet", r.overjet, &out);
  PutMeasure("overbite", r.overbite, &out);
  PutMeasure("midline_deviation", r.midline_deviation, &out);
  PutSides("molar", r.molar, &out);
  PutSides("canine", r.canine, &out);
  out["crossbite"] = r.crossbite;
  out["crossbite_unchecked"] = r.crossbite_unchecked;
  return out;
}

json RelationshipFrameJson(const analysis::Relationships& r) {
  if (r.frame_source.empty()) return nullptr;
  const analysis::ArchFrame& f = r.frame_L;
  return {{"origin_L", Vec(f.origin_J)},
          {"lateral", Vec(f.lateral_J)},
          {"anterior", Vec(f.anterior_J)},
          {"occlusal", Vec(f.occlusal_J)},
          {"source", r.frame_source}};
}

}  // namespace occlude::app
