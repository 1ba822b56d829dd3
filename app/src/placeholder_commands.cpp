// Temporary registrations until the real commands land (replaced in this series).
#include "commands.h"
namespace occlude::app {
void AddSynthCommand(CLI::App&) {}
void AddDemoCommand(CLI::App&) {}
void AddCollideCommand(CLI::App&) {}
}  // namespace occlude::app
