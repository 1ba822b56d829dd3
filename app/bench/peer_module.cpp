// Opens the peers' module (peer_module.h) beside the running binary, once.
#include "bench/peer_module.h"

#include <dlfcn.h>

#include <filesystem>
#include <system_error>

namespace occlude::app::peers {
namespace {

struct Loaded {
  const Module* module = nullptr;
  std::string why_not;
};

Loaded Open() {
  std::error_code error;
  const std::filesystem::path binary = std::filesystem::read_symlink("/proc/self/exe", error);
  if (error)
    return {nullptr, "cannot find the running binary (/proc/self/exe): " + error.message()};
  const std::filesystem::path file = binary.parent_path() / kModuleFile;
  const std::string rebuild = "; build it with the binary (cmake --build BUILD_DIR)";
  // RTLD_LOCAL: FCL's and OpenVDB's symbols stay the module's. The handle is never closed.
  void* handle = dlopen(file.c_str(), RTLD_NOW | RTLD_LOCAL);
  if (handle == nullptr) {
    const char* message = dlerror();
    return {nullptr, "cannot open the peers' module " + file.string() + ": " +
                         (message != nullptr ? message : "unknown error") + rebuild};
  }
  using Entry = const Module* (*)();
  auto* entry = reinterpret_cast<Entry>(dlsym(handle, "occlude_peers_module"));
  const Module* module = entry != nullptr ? entry() : nullptr;
  if (module == nullptr || module->version != kModuleVersion) {
    return {nullptr, file.string() + " is not this build's peers' module" + rebuild};
  }
  return {module, ""};
}

}  // namespace

const Module* LoadModule(std::string* why_not) {
  static const Loaded loaded = Open();
  if (why_not != nullptr) *why_not = loaded.why_not;
  return loaded.module;
}

std::string WhyUnavailable(Peer peer, bool built_with) {
  const bool fcl = peer == Peer::kFcl;
  const std::string library = fcl ? "FCL" : "OpenVDB";
  if (!built_with) {
    return "occlude was built without " + library + " (apt-get install " +
           (fcl ? "libfcl-dev" : "libopenvdb-dev libboost-dev") + ", then configure again)";
  }
  std::string why_not;
  const Module* module = LoadModule(&why_not);
  if (module == nullptr) return why_not;
  const bool has = fcl ? module->make_fcl != nullptr : module->make_openvdb != nullptr;
  return has ? "" : "the peers' module was built without " + library;
}

}  // namespace occlude::app::peers
