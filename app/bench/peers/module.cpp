// The peers' module's entry (bench/peer_module.h): the factories of the peers it was built with.
#include <limits>
#include <stdexcept>
#include <string>

#include "bench/peer_module.h"
#include "bench/peers/peer_factories.h"

void occlude::app::peers::CheckPeerMesh(const io::TriangleMesh& mesh, const std::string& prefix) {
  if (mesh.triangles.empty()) throw std::invalid_argument(prefix + "has no triangles");
  const auto max_int = static_cast<std::size_t>(std::numeric_limits<int>::max());
  if (mesh.vertices.size() > max_int || mesh.triangles.size() > max_int) {
    throw std::invalid_argument(prefix + "is too large (int indices)");
  }
  const auto nv = static_cast<int>(mesh.vertices.size());
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    const Eigen::Vector3i& tri = mesh.triangles[t];
    if ((tri.array() < 0).any() || (tri.array() >= nv).any()) {
      throw std::invalid_argument(prefix + "triangle " + std::to_string(t) +
                                  " indexes a vertex outside 0.." + std::to_string(nv - 1));
    }
  }
}

extern "C" __attribute__((visibility("default"))) const occlude::app::peers::Module*
occlude_peers_module() {
  static const occlude::app::peers::Module module = [] {
    occlude::app::peers::Module m;
#ifdef OCCLUDE_HAVE_FCL
    m.make_fcl = &occlude::app::peers::MakeFclModel;
#endif
#ifdef OCCLUDE_HAVE_OPENVDB
    m.make_openvdb = &occlude::app::peers::MakeOpenVdbGrid;
#endif
    return m;
  }();
  return &module;
}
