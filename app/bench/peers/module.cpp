// The peers' module's entry (bench/peer_module.h): the factories of the peers it was built with.
#include "bench/peer_module.h"
#include "bench/peers/peer_factories.h"

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
