// The viewer page's data object (see viewer_data_internal.h).
#include <cmath>
#include <nlohmann/json.hpp>
#include <stdexcept>

#include "occlude/io/dental.h"
#include "viewer/html_text.h"
#include "viewer/viewer_data_internal.h"

namespace occlude::app::viewer_detail {
namespace {

// Ordered: a proposal's numbers are listed in the order they were given.
using json = nlohmann::ordered_json;

// Little-endian bytes of unsigned values of `bytes` bytes each.
template <typename T>
std::string LittleEndian(const std::vector<T>& values, int bytes) {
  std::string out(values.size() * static_cast<std::size_t>(bytes), '\0');
  for (std::size_t i = 0; i < values.size(); ++i) {
    const auto v = static_cast<std::uint32_t>(values[i]);
    for (int k = 0; k < bytes; ++k) {
      out[i * static_cast<std::size_t>(bytes) + static_cast<std::size_t>(k)] =
          static_cast<char>((v >> (8 * k)) & 0xffu);
    }
  }
  return out;
}

json Vec(const Eigen::Vector3d& v) { return json::array({v.x(), v.y(), v.z()}); }

std::string Hex(const Rgb8& c) {
  static constexpr char kDigits[] = "0123456789abcdef";
  std::string out = "#";
  for (const std::uint8_t x : c) {
    out += kDigits[x >> 4];
    out += kDigits[x & 15];
  }
  return out;
}

json Positions(const io::TriangleMesh& mesh) {
  const Eigen::AlignedBox3d box = mesh.Bounds();
  const Eigen::Vector3d step = (box.sizes() / 65535.0).cwiseMax(1e-9);
  std::vector<std::uint16_t> q;
  q.reserve(3 * mesh.num_vertices());
  for (const Eigen::Vector3d& v : mesh.vertices) {
    for (int k = 0; k < 3; ++k) {
      q.push_back(static_cast<std::uint16_t>(std::lround((v[k] - box.min()[k]) / step[k])));
    }
  }
  return {{"origin", Vec(box.min())}, {"step", Vec(step)}, {"data", Base64(LittleEndian(q, 2))}};
}

json Index(const io::TriangleMesh& mesh) {
  std::vector<std::uint32_t> index;
  index.reserve(3 * mesh.num_triangles());
  for (const Eigen::Vector3i& t : mesh.triangles) {
    for (int k = 0; k < 3; ++k) index.push_back(static_cast<std::uint32_t>(t[k]));
  }
  const bool small = mesh.num_vertices() <= 65536;
  return {{"type", small ? "uint16" : "uint32"},
          {"data", Base64(LittleEndian(index, small ? 2 : 4))}};
}

json Parts(const io::TriangleMesh& mesh) {
  const bool small = mesh.parts.size() <= 256;
  json parts = json::array();
  for (const io::MeshPart& p : mesh.parts) {
    const bool tooth = p.tooth_number >= 1 && p.tooth_number <= 32;
    parts.push_back({{"name", p.name},
                     {"universal", tooth ? p.tooth_number : 0},
                     {"fdi", tooth ? io::FdiFromUniversal(p.tooth_number) : 0}});
  }
  return {{"type", small ? "uint8" : "uint16"},
          {"data", Base64(LittleEndian(mesh.triangle_part, small ? 1 : 2))},
          {"names", parts}};
}

json Jaw(const char* name, const char* frame, const io::TriangleMesh& mesh) {
  return {{"name", name},
          {"frame", frame},
          {"vertices", mesh.num_vertices()},
          {"triangles", mesh.num_triangles()},
          {"positions", Positions(mesh)},
          {"index", Index(mesh)},
          {"part", Parts(mesh)}};
}

json Surface(const std::vector<float>& distance_mm, const ContactScale& scale) {
  std::vector<std::uint16_t> codes;
  std::string colours;
  codes.reserve(distance_mm.size());
  colours.reserve(3 * distance_mm.size());
  for (const float d : distance_mm) {
    codes.push_back(static_cast<std::uint16_t>(DistanceCode(d)));
    for (const std::uint8_t c : ContactColour(d, scale)) colours += static_cast<char>(c);
  }
  return {{"distance_um", Base64(LittleEndian(codes, 2))}, {"colour", Base64(colours)}};
}

json Scale(const ContactScale& scale) {
  json ramp = json::array();
  for (const auto& [t, c] : ContactRampStops()) ramp.push_back({t * scale.max_mm, Hex(c)});
  return {{"max_mm", scale.max_mm},
          {"band_mm", scale.band_mm},
          {"penetration_from_mm", scale.penetration_from_mm},
          {"ramp", ramp},
          {"penetration", Hex(kContactPenetrationColour)},
          {"far", Hex(kContactFarColour)}};
}

[[noreturn]] void Bad(const std::string& field, const std::string& what) {
  throw std::invalid_argument(field + ": " + what);
}

void CheckMesh(const char* field, const io::TriangleMesh* mesh) {
  if (mesh == nullptr || mesh->empty()) Bad(field, "no display mesh given (or it is empty)");
  if (const std::string e = mesh->ConsistencyError(); !e.empty()) Bad(field, e);
}

void CheckDistances(const std::string& field, const std::vector<float>& d, std::size_t n) {
  if (d.size() != n) {
    Bad(field, std::to_string(d.size()) + " distances for " + std::to_string(n) +
                   " display vertices; give one per vertex of the display mesh");
  }
  for (std::size_t i = 0; i < d.size(); ++i) {
    if (!std::isfinite(d[i])) Bad(field, "distance " + std::to_string(i) + " is not finite");
  }
}

void CheckMeshesAndScale(const ViewerInputs& in) {
  CheckMesh("lower_L", in.lower_L);
  CheckMesh("upper_U", in.upper_U);
  if (!(in.scale.max_mm > 0.0)) Bad("scale.max_mm", "must be positive");
}

json Proposal(const ViewerInputs& in, const ViewerProposal& p, const std::string& field) {
  CheckDistances(field + ".lower_distance_mm", p.lower_distance_mm, in.lower_L->num_vertices());
  CheckDistances(field + ".upper_distance_mm", p.upper_distance_mm, in.upper_U->num_vertices());
  if (!p.X_LU.matrix().allFinite()) Bad(field + ".X_LU", "the pose is not finite");
  const json numbers = json::parse(p.numbers_json, nullptr, /*allow_exceptions=*/false);
  if (!numbers.is_object()) Bad(field + ".numbers_json", "not a JSON object");
  const Eigen::Matrix4d m = p.X_LU.matrix();
  return {{"label", p.label},
          {"X_LU", std::vector<double>(m.data(), m.data() + 16)},
          {"numbers", numbers},
          {"lower", Surface(p.lower_distance_mm, in.scale)},
          {"upper", Surface(p.upper_distance_mm, in.scale)}};
}

}  // namespace

std::int16_t DistanceCode(float d_mm) {
  if (!(d_mm < 32.7665f)) return kDistanceFarCode;  // beyond the range, or out of reach
  const long um = std::lround(static_cast<double>(d_mm) * 1000.0);
  return static_cast<std::int16_t>(std::max<long>(um, -kDistanceMaxCode));
}

std::string ViewerDataJson(const ViewerInputs& in) {
  CheckMeshesAndScale(in);
  if (in.proposals.empty()) Bad("proposals", "give at least one pose to show");
  const std::string& live = in.live_events_path;
  if (!live.empty() && (live[0] != '/' || live.rfind("//", 0) == 0)) {
    Bad("live_events_path", "\"" + live +
                                "\" is not a path on the page's server; give one "
                                "starting with a single '/', e.g. \"/events\"");
  }
  json proposals = json::array();
  for (std::size_t i = 0; i < in.proposals.size(); ++i) {
    proposals.push_back(Proposal(in, in.proposals[i], "proposals[" + std::to_string(i) + "]"));
  }
  const json data = {{"title", in.title},
                     {"axes",
                      {{"occlusal", Vec(in.axes.occlusal_L.normalized())},
                       {"anterior", Vec(in.axes.anterior_L.normalized())},
                       {"lateral", Vec(in.axes.lateral_L.normalized())}}},
                     {"scale", Scale(in.scale)},
                     {"jaws", {Jaw("lower", "L", *in.lower_L), Jaw("upper", "U", *in.upper_U)}},
                     {"proposals", proposals},
                     {"live", in.live_events_path.empty() ? json() : json(in.live_events_path)}};
  return data.dump(-1, ' ', false, json::error_handler_t::replace);  // bad UTF-8 in names: U+FFFD
}

std::string ProposalJson(const ViewerInputs& in, const ViewerProposal& proposal) {
  CheckMeshesAndScale(in);
  return Proposal(in, proposal, "proposal").dump(-1, ' ', false, json::error_handler_t::replace);
}

}  // namespace occlude::app::viewer_detail
